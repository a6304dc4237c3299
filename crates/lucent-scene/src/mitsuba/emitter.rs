//! `<emitter>` → `[[light]]`.
//!
//! | Mitsuba | lucent |
//! | --- | --- |
//! | `point` (`position` or `to_world`, `intensity` in W/sr) | point light, quadratic falloff |
//! | `spot` (`to_world`: at M·0, shining along M·+z; `intensity`, `cutoff_angle` default 20°, `beam_width` default ¾ of it) | spot light (`cutoff`, `cutoff_start`), quadratic falloff |
//! | `directional` (`direction` or `to_world`'s +z, `irradiance`) | directional light |
//! | `constant` (`radiance`) | environment light, `intensity` |
//! | `envmap` (`filename`, `scale`, `to_world`) | environment light, `file`, `intensity = scale`, `rotation` = `to_world`'s rotation after a half turn about +y (Mitsuba's image frame faces its centre towards +z, lucent's towards −z), `texels = "poles"` (Mitsuba's first and last rows of texels lie on the poles) |
//!
//! `area` emitters belong inside shapes (see `shape.rs`).

use super::Convert;
use super::xml::Element;
use crate::desc::{
    Color, FalloffName, Finite, LightDesc, LightKind, Matrix, Point, TexelsName, Vector,
};
use crate::error::LoadError;
use glam::{DMat4, DVec3};
use lucent::Rgb;
use toml::Spanned;

/// The emitter types lucent reads.
pub const TYPES: &[&str] = &["point", "spot", "directional", "constant", "envmap", "area"];

fn vector(v: DVec3, el: &Element, what: &str) -> Result<Spanned<Vector>, LoadError> {
    let v = v.as_vec3();
    if !v.is_finite() {
        return Err(el
            .loc
            .error(format!("the emitter's {what} is beyond single precision")));
    }
    Ok(Spanned::new(0..0, Vector(v)))
}

fn point(p: DVec3, el: &Element) -> Result<Spanned<Point>, LoadError> {
    if !p.as_vec3().is_finite() {
        return Err(el
            .loc
            .error("the emitter's position is beyond single precision"));
    }
    Ok(Spanned::new(0..0, Point(p)))
}

/// The light of the top-level `<emitter>` `el`.
pub fn read<'a>(cx: &mut Convert<'a>, el: &'a Element) -> Result<LightDesc, LoadError> {
    let p = cx.plugin(el)?;
    if matches!(p.kind, "constant" | "envmap") {
        // Mitsuba refuses a second environment emitter too.
        if let Some(first) = &cx.environment {
            return Err(el.loc.error(format!(
                "a second environment emitter (the first is at {first}); a scene has at most one"
            )));
        }
        cx.environment = Some(el.loc.clone());
    }
    let to_world = p.transform("to_world")?;
    let m = to_world.map_or(DMat4::IDENTITY, |(m, _)| m);
    let color = |c: Rgb| Some(Color(c));
    let light = match p.kind {
        "point" => {
            let mut l = LightDesc::new(LightKind::Point);
            let position = match (p.vector("position")?, to_world) {
                (Some(_), Some((_, loc))) => {
                    return Err(
                        loc.error("give a point emitter `position` or `to_world`, not both")
                    );
                }
                (Some(pos), None) => pos,
                (None, _) => m.transform_point3(DVec3::ZERO),
            };
            l.position = Some(point(position, el)?);
            l.intensity = color(p.emitted_color_or("intensity", 1.0)?);
            l.falloff = Some(Spanned::new(0..0, FalloffName::Quadratic));
            l
        }
        "spot" => {
            let mut l = LightDesc::new(LightKind::Spot);
            l.position = Some(point(m.transform_point3(DVec3::ZERO), el)?);
            let direction = m.transform_vector3(DVec3::Z);
            if direction == DVec3::ZERO {
                return Err(el
                    .loc
                    .error("the spot emitter's to_world flattens its direction"));
            }
            l.direction = Some(vector(direction, el, "direction")?);
            l.intensity = color(p.emitted_color_or("intensity", 1.0)?);
            let cutoff = p.float_or("cutoff_angle", 20.0)?;
            if !(cutoff > 0.0 && cutoff <= 90.0) {
                return Err(el.loc.error(format!(
                    "the spot emitter's cutoff_angle is {cutoff}°; lucent's spot lights take (0, 90]"
                )));
            }
            // A beam wider than the cutoff lights evenly up to the cutoff, as a beam as wide.
            let beam = p.float_or("beam_width", cutoff * 0.75)?.clamp(0.0, cutoff);
            l.cutoff = Some(Spanned::new(0..0, Finite(cutoff as f32)));
            l.cutoff_start = Some(Spanned::new(0..0, Finite(beam as f32)));
            l.falloff = Some(Spanned::new(0..0, FalloffName::Quadratic));
            l
        }
        "directional" => {
            let mut l = LightDesc::new(LightKind::Directional);
            let direction = match (p.vector("direction")?, to_world) {
                (Some(_), Some((_, loc))) => {
                    return Err(
                        loc.error("give a directional emitter `direction` or `to_world`, not both")
                    );
                }
                (Some(d), None) => d,
                (None, _) => m.transform_vector3(DVec3::Z),
            };
            if direction == DVec3::ZERO {
                return Err(el.loc.error("the directional emitter's direction is zero"));
            }
            l.direction = Some(vector(direction, el, "direction")?);
            l.intensity = color(p.emitted_color_or("irradiance", 1.0)?);
            l
        }
        "constant" => {
            let mut l = LightDesc::new(LightKind::Environment);
            l.intensity = color(p.emitted_color_or("radiance", 1.0)?);
            l
        }
        "envmap" => {
            let mut l = LightDesc::new(LightKind::Environment);
            let (file, loc) = p.required_string("filename")?;
            l.file = Some(Spanned::new(0..0, cx.file_name(file, loc, "image")?));
            let scale = p.float_or("scale", 1.0)?;
            if scale < 0.0 {
                return Err(el.loc.error("an envmap's scale must not be negative"));
            }
            l.intensity = color(Rgb::gray(scale as f32));
            // Mitsuba's image frame faces its centre towards +z, lucent's towards −z: a half
            // turn about +y, then to_world's rotation.
            let turned = m * DMat4::from_rotation_y(std::f64::consts::PI);
            let linear = glam::DMat3::from_mat4(turned);
            let unit = glam::DMat3::from_cols(
                linear.x_axis.normalize_or_zero(),
                linear.y_axis.normalize_or_zero(),
                linear.z_axis.normalize_or_zero(),
            );
            let rotation = (unit.transpose() * unit).abs_diff_eq(glam::DMat3::IDENTITY, 1e-6)
                && unit.determinant() > 0.0;
            if !rotation {
                let at = to_world.map_or(&el.loc, |(_, loc)| loc);
                return Err(at.error(
                    "an envmap's to_world must rotate (and may scale evenly): lucent cannot shear or mirror an environment",
                ));
            }
            l.rotation = Some(Spanned::new(0..0, Matrix(glam::DMat4::from_mat3(unit))));
            // Mitsuba's envmap puts its first and last rows of texels on the poles.
            l.texels = Some(Spanned::new(0..0, TexelsName::Poles));
            l
        }
        "area" => {
            return Err(el
                .loc
                .error("an area emitter belongs inside the <shape> that emits"));
        }
        other => return Err(super::unknown_type(el, other)),
    };
    p.finish(&mut cx.warnings, &[]);
    Ok(light)
}
