//! `<shape>` → `[[object]]`.
//!
//! | Mitsuba | lucent |
//! | --- | --- |
//! | `obj`, `ply` (`filename`, `face_normals`, `flip_normals`, `to_world`) | `mesh` (`file`, `smooth = false` for face normals, `flip_normals`, `transform`) |
//! | `serialized` (the same, and `shape_index`, default 0) | `mesh` as above, with `part` = the shape index; its texture coordinates as written, as Mitsuba reads them (see [`crate::serialized`]) |
//! | `sphere` (`center`, `radius`, `to_world`) | `sphere` when `to_world · translate(center) · scale(radius)` is a similarity, with `uv_axes` its rotation, so that textures and tangents lie as in Mitsuba; otherwise the exact `ellipsoid` it makes (Mitsuba's uvs), with a warning: Mitsuba draws a sphere there |
//! | `cylinder` (`p0`, `p1`, `radius`, `to_world`) | the exact `cylinder`, `open` (Mitsuba's has no caps), placed by `transform`; `u` may start at another turn about the axis than Mitsuba's where `p1 − p0` is not along z |
//! | `rectangle`, `cube`, `disk` (`to_world`) | the same kinds with `transform` and `flip_v` (Mitsuba's uvs): the canonical shapes agree (`[-1, 1]²` at z = 0 facing +z, `[-1, 1]³`, the unit disk at z = 0 facing +z) |
//!
//! A sphere's `flip_normals` is not read (lucent's spheres face out), with a warning.
//!
//! Its `<medium name="interior">` and `name="exterior"` are the object's media (see
//! `medium.rs`).
//!
//! A shape's nested or referenced `<bsdf>` is its material (none: Mitsuba's default, diffuse
//! 0.5); a nested `<emitter type="area">` makes a copy of that material emitting its
//! `radiance`.

use super::Convert;
use super::bsdf;
use super::transform::{self, placement};
use super::xml::Element;
use crate::build::RADIUS_RANGE;
use crate::desc::{Finite, ObjectDesc, ObjectKind, Point, Vector};
use crate::error::LoadError;
use glam::{DMat4, DVec3};
use toml::Spanned;

/// The shape types lucent reads.
pub const TYPES: &[&str] = &[
    "obj",
    "ply",
    "serialized",
    "sphere",
    "rectangle",
    "cube",
    "disk",
    "cylinder",
];

/// The object of the `<shape>` `el`.
pub fn read<'a>(cx: &mut Convert<'a>, el: &'a Element) -> Result<ObjectDesc, LoadError> {
    let p = cx.plugin(el)?;
    let kind = match p.kind {
        "obj" | "ply" | "serialized" => ObjectKind::Mesh,
        "sphere" => ObjectKind::Sphere,
        "rectangle" => ObjectKind::Rectangle,
        "cube" => ObjectKind::Cube,
        "disk" => ObjectKind::Disk,
        "cylinder" => ObjectKind::Cylinder,
        other => return Err(super::unknown_type(el, other)),
    };
    let mut o = ObjectDesc::new(kind, "");
    if matches!(
        kind,
        ObjectKind::Rectangle | ObjectKind::Cube | ObjectKind::Disk
    ) {
        // Mitsuba's v grows with the shape's y.
        o.flip_v = Some(true);
    }
    let to_world = p.transform("to_world")?;
    let place = |o: &mut ObjectDesc| -> Result<(), LoadError> {
        if let Some((m, loc)) = to_world
            && !transform::is_identity(&m)
        {
            o.transform = Some(Spanned::new(0..0, placement(&m, loc)?));
        }
        Ok(())
    };
    match kind {
        ObjectKind::Mesh => {
            let (file, loc) = p.required_string("filename")?;
            o.file = Some(Spanned::new(0..0, cx.file_name(file, loc, "mesh")?));
            if p.kind == "serialized" {
                // The file's shapes are the mesh file's parts, by index.
                let index = match p.integer("shape_index")? {
                    None => 0,
                    Some((i, loc)) => u32::try_from(i).map_err(|_| {
                        loc.error(format!(
                            "a shape index is a number of 0 or more (at most {}), not {i}",
                            u32::MAX
                        ))
                    })?,
                };
                o.part = Some(Spanned::new(0..0, index.to_string()));
            }
            if p.boolean("face_normals")? == Some(true) {
                o.smooth = Some(false);
            }
            place(&mut o)?;
        }
        ObjectKind::Sphere => {
            let center = p.vector("center")?.unwrap_or(DVec3::ZERO);
            let radius = p.float_or("radius", 1.0)?;
            if radius <= 0.0 {
                return Err(el
                    .loc
                    .error(format!("a sphere's radius must be positive, got {radius}")));
            }
            let m = to_world.map_or(DMat4::IDENTITY, |(m, _)| m)
                * DMat4::from_translation(center)
                * DMat4::from_scale(DVec3::splat(radius));
            let Some(scale) = transform::uniform_scale(&m) else {
                // Scaled unevenly: the exact ellipsoid, placed by the whole transform. Mitsuba
                // warns and draws a sphere instead (of the scale its decomposition puts first).
                let at = to_world.map_or(&el.loc, |(_, loc)| loc);
                p.warn(
                    at,
                    "this sphere's to_world scales unevenly: lucent renders the ellipsoid it makes, where Mitsuba warns and renders a sphere",
                );
                o.kind = ObjectKind::Ellipsoid;
                o.center = Some(Spanned::new(0..0, Point(center)));
                let r = Vector(glam::Vec3::splat(radius as f32));
                o.radii = Some(Spanned::new(0..0, r));
                place(&mut o)?;
                return finish(cx, el, p, o);
            };
            let center = m.transform_point3(DVec3::ZERO);
            let c = center.as_vec3();
            let r = scale as f32;
            if !c.is_finite() || !r.is_finite() {
                return Err(el.loc.error("the sphere is beyond single precision"));
            }
            if !RADIUS_RANGE.contains(&r) {
                let (lo, hi) = (RADIUS_RANGE.start(), RADIUS_RANGE.end());
                return Err(el.loc.error(format!(
                    "the sphere's radius {r:e} (after to_world) is outside lucent's range, {lo:e} to {hi:e}"
                )));
            }
            o.center = Some(Spanned::new(0..0, Point(center)));
            o.radius = Some(Spanned::new(0..0, Finite(r)));
            // Mitsuba's texture coordinates (and tangents): u from the object's +x about its
            // +z, whatever the rotation.
            let axes = [m.x_axis, m.y_axis, m.z_axis].map(|a| a.truncate().normalize().as_vec3());
            o.uv_axes = Some(Spanned::new(0..0, axes.map(Vector)));
        }
        ObjectKind::Cylinder => {
            let p0 = p.vector("p0")?.unwrap_or(DVec3::ZERO);
            let p1 = p.vector("p1")?.unwrap_or(DVec3::Z);
            let radius = p.float_or("radius", 1.0)?;
            o.base = Some(Spanned::new(0..0, Point(p0)));
            o.cap = Some(Spanned::new(0..0, Point(p1)));
            o.radius = Some(Spanned::new(0..0, Finite(radius as f32)));
            o.open = Some(true);
            place(&mut o)?;
        }
        _ => place(&mut o)?,
    }
    finish(cx, el, p, o)
}

/// A shape's flipped normals, material, emitter and media, read into `o`.
fn finish<'a>(
    cx: &mut Convert<'a>,
    el: &'a Element,
    p: super::props::Plugin<'a>,
    mut o: ObjectDesc,
) -> Result<ObjectDesc, LoadError> {
    let kind = o.kind;
    if p.boolean("flip_normals")? == Some(true) {
        if matches!(
            kind,
            ObjectKind::Sphere | ObjectKind::Ellipsoid | ObjectKind::Cylinder
        ) {
            p.warn(
                &el.loc,
                format!(
                    "`flip_normals` of a {} is not read: lucent's spheres and exact solids face outwards (an emitting sphere emits outwards)",
                    kind.name()
                ),
            );
        } else {
            o.flip_normals = Some(true);
        }
    }

    let bsdfs = p.take("bsdf");
    if let Some(extra) = bsdfs.get(1) {
        return Err(extra.at.error("a shape has one bsdf; this is a second"));
    }
    let mut material = match bsdfs.first() {
        Some(b) => bsdf::material(cx, b.el)?,
        None => bsdf::default_material(cx),
    };
    let emitters = p.take("emitter");
    if let Some(extra) = emitters.get(1) {
        return Err(extra.at.error("a shape has one emitter; this is a second"));
    }
    if let Some(e) = emitters.first() {
        let ep = cx.plugin(e.el)?;
        if ep.kind != "area" {
            return Err(e.at.error(format!(
                "a {} emitter cannot be inside a shape; only an area emitter can",
                ep.kind
            )));
        }
        let radiance = ep.emitted_color_or("radiance", 1.0)?;
        ep.finish(&mut cx.warnings, &[]);
        cx.used_area_emitters.push(std::ptr::from_ref(e.el));
        material = bsdf::emissive(cx, &material, radiance, e.at);
    }
    o.material = Spanned::new(0..0, material);
    for m in p.take("medium") {
        let name = Some(Spanned::new(0..0, super::medium::named(cx, m.el)?));
        match m.name {
            Some("interior") => o.interior = name,
            Some("exterior") => o.exterior = name,
            _ => {
                return Err(m.at.error(
                    "a shape's medium is named \"interior\" or \"exterior\" (name=\"interior\")",
                ));
            }
        }
    }
    p.finish(&mut cx.warnings, &[]);
    Ok(o)
}
