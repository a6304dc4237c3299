//! `[[object]]` tables of combined solids: `union`, `intersection`, `difference` and `merge`
//! (POV-Ray's), whose `children` are inline tables of the exact solids, spheres and further
//! combinations, each with its own placement and, optionally, its own material and `inverse`.

use super::objects::check_keys;
use super::solids::{placed, solid_of};
use super::{Context, check, required};
use crate::desc::{ObjectDesc, ObjectKind};
use crate::error::LoadError;
use glam::DAffine3;
use lucent::shape::{Csg, CsgOp, CsgTree};
use toml::Spanned;

/// Finds a material by name: its index, and whether it emits a colour.
pub(super) type Resolve<'a> = dyn Fn(&Spanned<String>) -> Result<(u32, bool), LoadError> + 'a;

/// The operation that `kind` names, if it is a combination.
pub(super) fn operation(kind: ObjectKind) -> Option<CsgOp> {
    match kind {
        ObjectKind::Union => Some(CsgOp::Union),
        ObjectKind::Intersection => Some(CsgOp::Intersection),
        ObjectKind::Difference => Some(CsgOp::Difference),
        ObjectKind::Merge => Some(CsgOp::Merge),
        _ => None,
    }
}

/// Adds the combination of table `o`, wearing `material` where a child names none.
pub(super) fn add_csg(
    ctx: &mut Context,
    o: &Spanned<ObjectDesc>,
    material: u32,
    resolve: &Resolve,
) -> Result<(), LoadError> {
    check_keys(ctx.source, o, false)?;
    let tree = tree(ctx, o, material, DAffine3::IDENTITY, resolve)?;
    let csg = Csg::new(&tree).map_err(|e| ctx.source.error(o.span(), e.to_string()))?;
    ctx.builder.csg(csg, material);
    Ok(())
}

/// The tree of table `o`, inside a combination placed by `parent`, `inherited` its material
/// where it names none.
fn tree(
    ctx: &Context,
    o: &Spanned<ObjectDesc>,
    inherited: u32,
    parent: DAffine3,
    resolve: &Resolve,
) -> Result<CsgTree, LoadError> {
    let d = o.get_ref();
    let kind = d.kind.name();
    let source = ctx.source;
    if let Some(m) = &d.motion {
        let what = format!("a {kind} cannot move yet (spheres, meshes and the unit shapes can)");
        return Err(source.error(m.span(), what));
    }
    let material = if d.material.get_ref().is_empty() {
        inherited
    } else {
        let (id, emits) = resolve(&d.material)?;
        let why = format!(
            "a {kind} cannot be an area light yet, and material `{}` emits light",
            d.material.get_ref()
        );
        check(source, d.material.span(), !emits, &why)?;
        id
    };
    let inverse = d.inverse.unwrap_or(false);
    if let Some(op) = operation(d.kind) {
        let children = required(source, o.span(), kind, "children", &d.children)?;
        let n = children.get_ref().len();
        let why = format!("a {kind} needs at least two `children`, got {n}");
        check(source, children.span(), n >= 2, &why)?;
        let here = parent * placed(ctx, d, o.span())?;
        let mut parts = Vec::with_capacity(n);
        for child in children.get_ref() {
            check_keys(source, child, true)?;
            parts.push(tree(ctx, child, material, here, resolve)?);
        }
        return Ok(CsgTree::Node {
            op,
            children: parts,
            inverse,
        });
    }
    if !(super::solids::is_solid(d.kind)
        || matches!(d.kind, ObjectKind::Sphere | ObjectKind::Plane))
    {
        return Err(source.error(
            o.span(),
            format!(
                "a {kind} cannot be part of a combination: only the exact solids, spheres, planes and other combinations can"
            ),
        ));
    }
    let solid = solid_of(ctx, d, o.span(), parent)?;
    let why = if d.kind == ObjectKind::Disc {
        "a disc bounds no volume, so it cannot be combined".to_string()
    } else {
        format!("an open {kind} bounds no volume, so it cannot be combined (leave out `open`)")
    };
    check(source, o.span(), solid.is_closed(), &why)?;
    Ok(CsgTree::Leaf {
        solid,
        material,
        inverse,
    })
}
