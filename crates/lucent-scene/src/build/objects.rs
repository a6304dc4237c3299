//! `[[object]]` tables: spheres, planes, triangles, meshes from files, and the unit shapes,
//! placed by a transform (the exact solids in `solids.rs`); emitting objects report their surface for area lights.

use super::lights::EmitterSurface;
use super::{Context, RADIUS_RANGE, check, refuse_keys, required, rescaled, shapes, span};
use crate::desc::{ObjectDesc, ObjectKind};
use crate::error::LoadError;
use glam::{Affine3A, DVec3, Mat3, Vec3};
use lucent::shape::{Mesh, Plane, Sphere, SphereMap, triangle};
use std::collections::HashMap;
use std::ops::Range;
use std::path::PathBuf;
use toml::Spanned;

/// What a stored mesh is: a file's part, or a unit shape; with how it is read.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct MeshKey {
    source: PathBuf,
    part: Option<String>,
    smooth: bool,
    flipped: bool,
    flip_v: bool,
}

/// Meshes already stored: their id in the scene builder.
pub type MeshCache = HashMap<MeshKey, u32>;

/// Adds the object; returns its surface when `emissive` (its material emits a colour: an area
/// light). `glows`: its material emits at all, a colour or a texture (so it cannot move).
pub fn add_object(
    ctx: &mut Context,
    meshes: &mut MeshCache,
    o: &Spanned<ObjectDesc>,
    material: u32,
    emissive: bool,
    glows: bool,
) -> Result<Option<EmitterSurface>, LoadError> {
    let d = o.get_ref();
    let kind = d.kind.name();
    check_keys(ctx.source, o, false)?;
    let table = o.span();
    let source = ctx.source;
    if super::solids::is_solid(d.kind) {
        super::solids::add_solid(ctx, d, table, material, emissive)?;
        return Ok(None);
    }
    let motion = moving(ctx, d, glows)?;
    match d.kind {
        ObjectKind::Sphere => {
            let center = ctx.local(
                required(source, table.clone(), kind, "center", &d.center)?
                    .get_ref()
                    .0,
            );
            let radius = required(source, table, kind, "radius", &d.radius)?;
            let r = radius.get_ref().0;
            check(
                source,
                radius.span(),
                r > 0.0,
                &format!("a sphere's radius must be positive, got {r}"),
            )?;
            let (lo, hi) = (RADIUS_RANGE.start(), RADIUS_RANGE.end());
            let in_range = RADIUS_RANGE.contains(&r);
            check(
                source,
                radius.span(),
                in_range,
                &format!("a sphere's radius must be between {lo:e} and {hi:e}, got {r:e}"),
            )?;
            // Below this, points of the sphere round onto its centre (and its normals to NaN).
            let least = center.abs().max_element() * MIN_RADIUS_PER_DISTANCE;
            check(
                source,
                radius.span(),
                r >= least,
                &format!(
                    "a sphere's radius must be at least 2⁻²⁰ of its centre's largest coordinate in single precision: at least {least:e} there, got {r:e}"
                ),
            )?;
            let map = match &d.uv_axes {
                None => SphereMap::default(),
                Some(a) => {
                    let [x, y, z] = a.get_ref().map(|v| rescaled(v.0).normalize_or_zero());
                    let orthonormal = [x, y, z].iter().all(|v| (v.length() - 1.0).abs() < 1e-4)
                        && x.dot(y).abs() < 1e-4
                        && y.dot(z).abs() < 1e-4
                        && z.dot(x).abs() < 1e-4;
                    check(
                        source,
                        a.span(),
                        orthonormal,
                        "a sphere's uv_axes must be three perpendicular, non-zero directions",
                    )?;
                    SphereMap { x, y, z }
                }
            };
            let id = ctx
                .builder
                .sphere_mapped(Sphere { center, radius: r }, material, map);
            if let Some(m) = motion {
                ctx.builder.motion(id, m);
            }
            let area = 4.0 * std::f32::consts::PI * r * r;
            Ok(emissive.then_some(EmitterSurface {
                area,
                centroid: center,
            }))
        }
        ObjectKind::Plane => {
            let point = ctx.local(
                required(source, table.clone(), kind, "point", &d.point)?
                    .get_ref()
                    .0,
            );
            let normal = required(source, table.clone(), kind, "normal", &d.normal)?;
            let n = normal.get_ref().0;
            check(
                source,
                normal.span(),
                n != Vec3::ZERO,
                "a plane's normal must not be zero",
            )?;
            if emissive {
                return Err(source.error(
                    table,
                    "an infinite plane cannot emit light: give its material no `emission`",
                ));
            }
            ctx.builder.plane(Plane::new(point, rescaled(n)), material);
            Ok(None)
        }
        ObjectKind::Triangle => {
            let vertices = required(source, table, kind, "vertices", &d.vertices)?;
            let v = vertices.get_ref().map(|p| ctx.local(p.0));
            let ok = triangle::double_area(v) > 0.0;
            check(
                source,
                vertices.span(),
                ok,
                "the triangle's vertices are collinear: it has no area",
            )?;
            let mesh = Mesh::new(v.to_vec(), vec![[0, 1, 2]]);
            add_world_mesh(ctx, d, mesh, material, emissive, motion)
        }
        ObjectKind::Triangles => {
            let mesh = inline_mesh(ctx, d, table.clone())?;
            add_world_mesh(ctx, d, mesh, material, emissive, motion)
        }
        _ => {
            let transform = placement(ctx, d, o.span())?;
            let flipped = d.flip_normals.unwrap_or(false);
            // Read from the path as the scene names it (errors show it so); cached by its
            // canonical form, so two names of one file share the mesh.
            let mut read_from = PathBuf::new();
            let key = if d.kind == ObjectKind::Mesh {
                let file = required(source, table, kind, "file", &d.file)?;
                let path = ctx.path(file.get_ref(), file.span())?;
                if let Err(why) = crate::input::refused(&path) {
                    return Err(
                        source.error(file.span(), format!("mesh file `{}` {why}", path.display()))
                    );
                }
                read_from = path.clone();
                MeshKey {
                    source: std::fs::canonicalize(&path).unwrap_or(path),
                    part: d.part.as_ref().map(|p| p.get_ref().clone()),
                    smooth: d.smooth.unwrap_or(true),
                    flipped,
                    flip_v: false,
                }
            } else {
                MeshKey {
                    source: PathBuf::from(format!("<{kind}>")),
                    part: None,
                    smooth: true,
                    flipped,
                    flip_v: d.flip_v.unwrap_or(false),
                }
            };
            // A mesh placed many times is read and stored once: the objects are instances of it.
            let id = match meshes.get(&key) {
                Some(&id) => id,
                None => {
                    let mut mesh = match d.kind {
                        ObjectKind::Rectangle => shapes::rectangle(),
                        ObjectKind::Cube => shapes::cube(),
                        ObjectKind::Disk => shapes::disk(),
                        _ => ctx.mesh_files.read_part(
                            &read_from,
                            key.part.as_deref(),
                            ctx.options,
                            &mut ctx.inputs,
                        )?,
                    };
                    if !key.smooth {
                        mesh.normals.clear();
                    }
                    if key.flip_v {
                        for uv in &mut mesh.uvs {
                            uv.y = 1.0 - uv.y;
                        }
                    }
                    if flipped {
                        mesh.flip();
                    }
                    let id = ctx.builder.add_mesh(mesh);
                    meshes.insert(key, id);
                    id
                }
            };
            if let Some(m) = &motion {
                moved_at_start(ctx, d, m, transform)?;
            }
            let object = ctx.builder.instance(id, transform, material);
            if let Some(m) = motion {
                ctx.builder.motion(object, m);
            }
            Ok(emissive
                .then(|| ctx.builder.stored_mesh(id).map(|m| surface(m, transform)))
                .flatten())
        }
    }
}

/// Adds a mesh given in world coordinates (a triangle's, a `triangles` object's), moving as
/// `motion` says; its surface when `emissive`.
fn add_world_mesh(
    ctx: &mut Context,
    d: &ObjectDesc,
    mesh: Mesh,
    material: u32,
    emissive: bool,
    motion: Option<lucent::motion::Motion>,
) -> Result<Option<EmitterSurface>, LoadError> {
    let surface = emissive.then(|| surface(&mesh, Affine3A::IDENTITY));
    if let Some(m) = &motion {
        moved_at_start(ctx, d, m, Affine3A::IDENTITY)?;
    }
    let id = ctx.builder.mesh(mesh, material);
    if let Some(m) = motion {
        ctx.builder.motion(id, m);
    }
    Ok(surface)
}

/// The mesh a `triangles` object writes out: every index within `positions`, `normals` one
/// per position (zero normals make the mesh flat).
fn inline_mesh(ctx: &Context, d: &ObjectDesc, table: Range<usize>) -> Result<Mesh, LoadError> {
    let source = ctx.source;
    let kind = d.kind.name();
    let positions = required(source, table.clone(), kind, "positions", &d.positions)?;
    let indices = required(source, table, kind, "indices", &d.indices)?;
    let n = positions.get_ref().len();
    check(
        source,
        positions.span(),
        n > 0,
        "a mesh needs at least one position",
    )?;
    check(
        source,
        indices.span(),
        !indices.get_ref().is_empty(),
        "a mesh needs at least one triangle",
    )?;
    if let Some(bad) = indices
        .get_ref()
        .iter()
        .flatten()
        .find(|&&i| i as usize >= n)
    {
        return Err(source.error(
            indices.span(),
            format!("index {bad} is past the {n} positions"),
        ));
    }
    let points = positions.get_ref().iter().map(|p| ctx.local(p.0)).collect();
    let mut mesh = Mesh::new(points, indices.get_ref().clone());
    if let Some(normals) = &d.normals {
        let ns = normals.get_ref();
        check(
            source,
            normals.span(),
            ns.len() == n,
            &format!(
                "{} normals for {n} positions: give one per position",
                ns.len()
            ),
        )?;
        if ns.iter().all(|v| v.0.length_squared() > 0.0) {
            mesh.normals = ns.iter().map(|v| v.0.normalize()).collect();
        }
    }
    Ok(mesh)
}

/// Refuses the keys of table `o` that its kind does not take (`child`: it is a combination's
/// child, which may be `inverse`).
pub(super) fn check_keys(
    source: &super::Source,
    o: &Spanned<ObjectDesc>,
    child: bool,
) -> Result<(), LoadError> {
    let d = o.get_ref();
    let kind = d.kind.name();
    let keys = [
        ("center", span(&d.center)),
        ("radius", span(&d.radius)),
        ("point", span(&d.point)),
        ("normal", span(&d.normal)),
        ("vertices", span(&d.vertices)),
        ("positions", span(&d.positions)),
        ("indices", span(&d.indices)),
        ("normals", span(&d.normals)),
        ("file", span(&d.file)),
        ("part", span(&d.part)),
        ("smooth", d.smooth.map(|_| o.span())),
        ("flip_normals", d.flip_normals.map(|_| o.span())),
        ("transform", span(&d.transform)),
        ("translate", span(&d.translate)),
        ("rotate", span(&d.rotate)),
        ("scale", span(&d.scale)),
        ("motion", span(&d.motion)),
        ("uv_axes", span(&d.uv_axes)),
        ("flip_v", d.flip_v.map(|_| o.span())),
        ("min", span(&d.min)),
        ("max", span(&d.max)),
        ("base", span(&d.base)),
        ("cap", span(&d.cap)),
        ("base_radius", span(&d.base_radius)),
        ("cap_radius", span(&d.cap_radius)),
        ("open", d.open.map(|_| o.span())),
        ("hole", span(&d.hole)),
        ("radii", span(&d.radii)),
        ("exponents", span(&d.exponents)),
        ("terms", span(&d.terms)),
        ("bounds", span(&d.bounds)),
        ("major", span(&d.major)),
        ("minor", span(&d.minor)),
        ("children", span(&d.children)),
        ("inverse", d.inverse.map(|_| o.span())),
    ];
    const PLACED: [&str; 5] = ["flip_normals", "transform", "translate", "rotate", "scale"];
    const SOLID_PLACED: [&str; 4] = ["transform", "translate", "rotate", "scale"];
    let mut takes: Vec<&str> = match d.kind {
        ObjectKind::Sphere => vec!["center", "radius", "uv_axes"],
        ObjectKind::Plane => vec!["point", "normal"],
        ObjectKind::Triangle => vec!["vertices"],
        ObjectKind::Triangles => vec!["positions", "indices", "normals"],
        ObjectKind::Mesh => ["file", "part", "smooth"]
            .into_iter()
            .chain(PLACED)
            .collect(),
        ObjectKind::Rectangle | ObjectKind::Cube | ObjectKind::Disk => {
            PLACED.iter().copied().chain(["flip_v"]).collect()
        }
        ObjectKind::Union
        | ObjectKind::Intersection
        | ObjectKind::Difference
        | ObjectKind::Merge => ["children"].into_iter().chain(SOLID_PLACED).collect(),
        solid => super::solids::keys(solid).chain(SOLID_PLACED).collect(),
    };
    if child {
        takes.push("inverse");
    }
    if let (ObjectKind::Plane, Some(m)) = (d.kind, &d.motion) {
        return Err(source.error(
            m.span(),
            "an infinite plane cannot move (move a large rectangle instead)",
        ));
    }
    takes.push("motion");
    let others: Vec<_> = keys
        .into_iter()
        .filter(|(k, _)| !takes.contains(k))
        .collect();
    refuse_keys(source, kind, &others)
}

/// The object's motion, if it has one, checked against what it is.
fn moving(
    ctx: &Context,
    d: &ObjectDesc,
    glows: bool,
) -> Result<Option<lucent::motion::Motion>, LoadError> {
    let Some(desc) = &d.motion else {
        return Ok(None);
    };
    let m = super::motion::motion(ctx.source, desc, ctx.origin)?;
    if glows && !m.is_static() {
        return Err(ctx.source.error(
            desc.span(),
            "an object that emits light cannot move: the light tables are built once for every instant (give it no `motion`, or a material without `emission`)",
        ));
    }
    if d.kind == ObjectKind::Sphere && !m.scales_uniformly() {
        return Err(ctx.source.error(
            desc.span(),
            "a sphere's motion must scale alike on every axis (give `scale` as one number)",
        ));
    }
    Ok(Some(m))
}

/// A sphere's least radius per unit of its centre's largest coordinate, 2⁻²⁰: its points are
/// then at least 8 ulps of that coordinate away from the centre (a sphere at 1e6 needs a radius
/// of 0.95; one at 1e-2 any radius the range allows).
const MIN_RADIUS_PER_DISTANCE: f32 = 1.0 / 1_048_576.0;

/// The object's placement: `transform`, or scale, then rotate about x, y, z, then translate;
/// `table` is the object's, for errors.
pub(super) fn placement(
    ctx: &Context,
    d: &ObjectDesc,
    table: Range<usize>,
) -> Result<Affine3A, LoadError> {
    if let Some(t) = &d.transform {
        if d.translate.is_some() || d.rotate.is_some() || d.scale.is_some() {
            return Err(ctx.source.error(
                t.span(),
                "give `transform` or `scale`/`rotate`/`translate`, not both",
            ));
        }
        let m = t.get_ref().0;
        let rebased = Affine3A::from_mat3_translation(
            glam::DMat3::from_mat4(m).as_mat3(),
            ctx.local(m.w_axis.truncate()),
        );
        return invertible(ctx, rebased, t.span(), "the transform");
    }
    let scale = d.scale.as_ref().map_or(Vec3::ONE, |s| s.get_ref().0);
    let deg = d.rotate.as_ref().map_or(Vec3::ZERO, |r| r.get_ref().0);
    let rotation = Mat3::from_rotation_z(deg.z.to_radians())
        * Mat3::from_rotation_y(deg.y.to_radians())
        * Mat3::from_rotation_x(deg.x.to_radians());
    let translate = ctx.local(d.translate.as_ref().map_or(DVec3::ZERO, |t| t.get_ref().0));
    let placed = Affine3A::from_translation(translate)
        * Affine3A::from_mat3(rotation)
        * Affine3A::from_scale(scale);
    // Rotations and translations always invert: only the scale can make it singular.
    let at = d.scale.as_ref().map_or(table, Spanned::span);
    invertible(ctx, placed, at, "the placement")
}

/// Refuses a motion that puts the object's placement `placed` out of single precision at time 0
/// (where the scene is built, and a batch render shows it by default), at the `motion` table.
fn moved_at_start(
    ctx: &Context,
    d: &ObjectDesc,
    m: &lucent::motion::Motion,
    placed: Affine3A,
) -> Result<(), LoadError> {
    let span = d.motion.as_ref().map_or(0..0, Spanned::span);
    let at_start = m.at(0.0) * placed;
    invertible(
        ctx,
        at_start,
        span,
        "moved to its place at time 0, the placement",
    )
    .map(|_| ())
}

/// `placed`, or an error at `span` when the renderer could not use it in single precision
/// ([`lucent::shape::Transform::new`] decides): a determinant that is zero or infinite (a scale
/// of 1e-20 on every axis has 1e-60, which is 0 in `f32`), an inverse that is not finite (at
/// 1e-13 on every axis the determinant is 1e-39, and its reciprocal overflows), or scales so
/// unequal (1e-18 against 1e18) that normals would underflow.
fn invertible(
    ctx: &Context,
    placed: Affine3A,
    span: Range<usize>,
    what: &str,
) -> Result<Affine3A, LoadError> {
    if lucent::shape::Transform::new(placed).is_some() {
        return Ok(placed);
    }
    let det = placed.matrix3.determinant();
    let inverse = Mat3::from(placed.matrix3).inverse();
    let why = if !placed.translation.is_finite() {
        "the translation overflows".to_string()
    } else if det.is_finite() && det != 0.0 && inverse.is_finite() {
        "its scales differ by more than 1e30 to 1, and normals would underflow".to_string()
    } else {
        format!("a scale too small or too large: the determinant is {det:e}")
    };
    Err(ctx.source.error(
        span,
        format!("{what} is singular or overflows in single precision ({why})"),
    ))
}

/// World-space area and area-weighted centre of `mesh` placed by `transform`.
fn surface(mesh: &Mesh, transform: Affine3A) -> EmitterSurface {
    let (mut area, mut weighted) = (0.0f64, glam::DVec3::ZERO);
    for t in 0..mesh.triangles.len() as u32 {
        let v = mesh.vertices(t).map(|p| transform.transform_point3(p));
        let a = 0.5 * f64::from((v[1] - v[0]).cross(v[2] - v[0]).length());
        area += a;
        weighted += a * ((v[0] + v[1] + v[2]) / 3.0).as_dvec3();
    }
    let centroid = if area > 0.0 {
        (weighted / area).as_vec3()
    } else {
        transform.translation.into()
    };
    EmitterSurface {
        area: area as f32,
        centroid,
    }
}
