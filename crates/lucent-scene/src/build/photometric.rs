//! `type = "photometric"` lights: an IES file's candela table, placed and turned in the scene.

use super::{Context, required};
use crate::desc::{FalloffName, LightDesc};
use crate::error::LoadError;
use glam::{Mat3, Vec3};
use lucent::Rgb;
use lucent::light::{Falloff, Light, PhotometricLight, PointLight};
use std::sync::Arc;
use toml::Spanned;

/// The photometric light of table `l`, its colour `intensity` multiplying the file's candela
/// (over 683). Its falloff is quadratic unless the table says `"none"` (and is quadratic under
/// `sppm` whatever it says).
pub fn light(
    ctx: &mut Context,
    l: &Spanned<LightDesc>,
    intensity: Rgb,
    sppm: bool,
) -> Result<Light, LoadError> {
    let d = l.get_ref();
    let kind = d.kind.name();
    let file = required(ctx.source, l.span(), kind, "file", &d.file)?;
    let (path, bytes) = ctx.read_named(file, "IES file")?;
    let ies = crate::ies::parse_ies(&path, &String::from_utf8_lossy(&bytes))?;
    let position = ctx.local(
        required(ctx.source, l.span(), kind, "position", &d.position)?
            .get_ref()
            .0,
    );
    let nadir = match &d.direction {
        None => Vec3::NEG_Y,
        Some(v) => super::rescaled(v.get_ref().0)
            .try_normalize()
            .ok_or_else(|| {
                ctx.source
                    .error(v.span(), "the light's direction must not be zero")
            })?,
    };
    let front = match &d.front {
        Some(f) => perpendicular(super::rescaled(f.get_ref().0), nadir).ok_or_else(|| {
            ctx.source.error(
                f.span(),
                "`front` must not be zero or along `direction` (it says where C = 0° lies about the nadir)",
            )
        })?,
        None => perpendicular(Vec3::X, nadir)
            .or_else(|| perpendicular(Vec3::NEG_Z, nadir))
            .expect("x and z are not both along one direction"),
    };
    // The luminaire's frame: +x its length (C = 0°), +z up (away from the nadir).
    let up = -nadir;
    let to_world = Mat3::from_cols(front, up.cross(front), up);
    // A tilt table scales the lamp's output by how far the luminaire leans from hanging
    // straight down.
    let tilt = ies.tilt.as_ref().map_or(1.0, |t| {
        t.factor(nadir.dot(Vec3::NEG_Y).clamp(-1.0, 1.0).acos().to_degrees())
    });
    let falloff = match d.falloff.as_ref().map(|f| *f.get_ref()) {
        Some(FalloffName::None) if !sppm => Falloff::None,
        _ => Falloff::Quadratic,
    };
    Ok(Light::Photometric(PhotometricLight {
        point: PointLight {
            position,
            // Candela per unit of lucent's intensity (W/sr), as the glTF reader converts.
            intensity: intensity * (tilt / crate::gltf_file::LUMENS_PER_WATT),
            falloff,
        },
        to_luminaire: to_world.transpose(),
        profile: Arc::new(ies.profile),
    }))
}

/// Unit `v` made perpendicular to unit `axis`; `None` when it lies along it.
pub(super) fn perpendicular(v: Vec3, axis: Vec3) -> Option<Vec3> {
    (v - axis * v.dot(axis))
        .try_normalize()
        .filter(|p| p.dot(v.normalize_or_zero()) > 1e-3)
}
