//! `[[light]]` tables, and area lights (emitting objects) under the classic integrators.

use super::{Context, refuse_keys, required, span};
use crate::desc::texture::Encoding;
use crate::desc::{FalloffName, LightKind, SceneDesc, TexelsName};
use crate::error::LoadError;
use glam::Vec3;
use lucent::Rgb;
use lucent::light::{Cone, DirectionalLight, Falloff, Light, PointLight, SpotLight};
use lucent::texture::image::LatLongTexels;

/// An emitting object's surface: its area and (area-weighted) centre, in world space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EmitterSurface {
    /// Area.
    pub area: f32,
    /// Centre.
    pub centroid: Vec3,
}

/// Adds every `[[light]]`; an environment light sets the background, and under the classic
/// integrators (not `path`, which samples it as a light) the ambient light too.
///
/// The photon mapper (`sppm`) needs lights with a flux: a point or spot light without falloff
/// (the classic model) becomes one with quadratic falloff, said in one warning.
pub fn add_lights(
    desc: &SceneDesc,
    ctx: &mut Context,
    path: bool,
    sppm: bool,
) -> Result<(), LoadError> {
    let mut environment = None;
    let mut made_physical = 0;
    for l in &desc.lights {
        let d = l.get_ref();
        let kind = d.kind.name();
        let intensity = d.intensity.map_or(Rgb::WHITE, |c| c.0);
        let keys = [
            ("position", span(&d.position)),
            ("falloff", span(&d.falloff)),
            ("direction", span(&d.direction)),
            ("cutoff", span(&d.cutoff)),
            ("cutoff_start", span(&d.cutoff_start)),
            ("file", span(&d.file)),
            ("rotation", span(&d.rotation)),
            ("front", span(&d.front)),
            ("texels", span(&d.texels)),
            ("mapping", span(&d.mapping)),
            ("up", span(&d.up)),
            ("fov", span(&d.fov)),
        ];
        let takes: &[&str] = match d.kind {
            LightKind::Point => &["position", "falloff"],
            LightKind::Spot if d.file.is_some() => &[
                "position",
                "falloff",
                "direction",
                "cutoff",
                "cutoff_start",
                "file",
                "up",
            ],
            LightKind::Spot => &["position", "falloff", "direction", "cutoff", "cutoff_start"],
            LightKind::Directional => &["direction"],
            LightKind::Environment => &["file", "rotation", "texels"],
            LightKind::Photometric => &["file", "position", "falloff", "direction", "front"],
            LightKind::Goniometric => &["file", "mapping", "position", "up", "front", "falloff"],
            LightKind::Projection => &["file", "position", "direction", "up", "fov", "falloff"],
        };
        let others: Vec<_> = keys
            .into_iter()
            .filter(|(k, _)| !takes.contains(k))
            .collect();
        refuse_keys(ctx.source, kind, &others)?;
        let direction = |ctx: &Context| -> Result<Vec3, LoadError> {
            let dir = required(ctx.source, l.span(), kind, "direction", &d.direction)?;
            super::rescaled(dir.get_ref().0)
                .try_normalize()
                .ok_or_else(|| {
                    ctx.source
                        .error(dir.span(), "the light's direction must not be zero")
                })
        };
        let point = |ctx: &Context| -> Result<PointLight, LoadError> {
            let position = ctx.local(
                required(ctx.source, l.span(), kind, "position", &d.position)?
                    .get_ref()
                    .0,
            );
            // Lights given in physical terms (an image of intensities) fall off as 1/d² unless
            // told otherwise; the classic ones do not.
            let physical = matches!(d.kind, LightKind::Goniometric | LightKind::Projection);
            let falloff = match d.falloff.as_ref().map(|f| *f.get_ref()) {
                None if physical => Falloff::Quadratic,
                None | Some(FalloffName::None) if sppm => Falloff::Quadratic,
                None | Some(FalloffName::None) => Falloff::None,
                Some(FalloffName::Quadratic) => Falloff::Quadratic,
            };
            Ok(PointLight {
                position,
                intensity,
                falloff,
            })
        };
        let said_none = |unset: bool| {
            d.falloff
                .as_ref()
                .map_or(unset, |f| *f.get_ref() == FalloffName::None)
        };
        let classic = match d.kind {
            LightKind::Point | LightKind::Spot => said_none(true),
            LightKind::Goniometric | LightKind::Projection => said_none(false),
            _ => false,
        };
        if sppm && classic {
            made_physical += 1;
        }
        let light = match d.kind {
            LightKind::Point => Light::Point(point(ctx)?),
            LightKind::Photometric => super::photometric::light(ctx, l, intensity, sppm)?,
            LightKind::Goniometric | LightKind::Projection => {
                super::image_lights::light(ctx, l, point(ctx)?)?
            }
            LightKind::Directional => Light::Directional(DirectionalLight {
                direction: direction(ctx)?,
                intensity,
            }),
            LightKind::Spot => {
                let cutoff = required(ctx.source, l.span(), kind, "cutoff", &d.cutoff)?;
                let outer = cutoff.get_ref().0;
                if !(outer > 0.0 && outer <= 90.0) {
                    return Err(ctx.source.error(
                        cutoff.span(),
                        "a spot light's cutoff must be in (0, 90] degrees",
                    ));
                }
                let inner = match &d.cutoff_start {
                    Some(s) if !(s.get_ref().0 >= 0.0 && s.get_ref().0 <= outer) => {
                        return Err(ctx
                            .source
                            .error(s.span(), "cutoff_start must be between 0 and cutoff"));
                    }
                    Some(s) => s.get_ref().0,
                    None => outer,
                };
                let cone = Cone {
                    cos_cutoff: outer.to_radians().cos(),
                    cos_start: inner.to_radians().cos(),
                };
                match &d.file {
                    Some(file) => super::image_lights::textured_spot(
                        ctx,
                        l,
                        point(ctx)?,
                        (direction(ctx)?, cone),
                        file,
                    )?,
                    None => Light::Spot(SpotLight {
                        point: point(ctx)?,
                        direction: direction(ctx)?,
                        cos_cutoff: cone.cos_cutoff,
                        cos_start: cone.cos_start,
                    }),
                }
            }
            LightKind::Environment => {
                if environment.is_some() {
                    return Err(ctx
                        .source
                        .error(l.span(), "a scene has at most one environment light"));
                }
                // Under the classic integrators the sky is seen by rays that miss, and lights
                // surfaces as ambient light of its mean radiance over directions (no shadows).
                let mean = match &d.file {
                    Some(file) => {
                        let id =
                            ctx.image(file.get_ref(), file.span(), intensity, Encoding::Srgb)?;
                        ctx.builder.environment(Some(id));
                        if let Some(r) = &d.rotation {
                            let to_image = environment_rotation(r.get_ref().0.as_mat4())
                                .ok_or_else(|| ctx.source.error(r.span(), "an environment's `rotation` must be a rotation: orthonormal columns, no mirror"))?;
                            ctx.builder.environment_rotation(to_image);
                        }
                        if let Some(t) = &d.texels {
                            ctx.builder.environment_texels(match t.get_ref() {
                                TexelsName::Cells => LatLongTexels::Cells,
                                TexelsName::Poles => LatLongTexels::Poles,
                            });
                        }
                        ctx.builder
                            .stored_image(id)
                            .map_or(Rgb::BLACK, |i| i.latlong_mean())
                    }
                    None => {
                        ctx.builder.background(intensity);
                        intensity
                    }
                };
                environment = Some(mean);
                continue;
            }
        };
        ctx.builder.light(light);
    }
    if made_physical > 0 {
        ctx.warnings.push(format!(
            "{}: {made_physical} light{} without falloff fall{} off as 1/d² under the sppm integrator (photons need a physical light)",
            ctx.source.path.display(),
            if made_physical == 1 { "" } else { "s" },
            if made_physical == 1 { "s" } else { "" },
        ));
    }
    if let Some(mean) = environment.filter(|_| !path) {
        ctx.builder.add_ambient(mean);
        ctx.warnings.push(format!(
            "{}: the environment light is seen by rays that miss and lights surfaces as ambient light (no shadows) under the classic integrators",
            ctx.source.path.display()
        ));
    }
    Ok(())
}

/// Under the classic integrators an area light becomes a point light at its centre with the
/// same power: a one-sided Lambertian emitter of radiance `L` and area `A` emits `Φ = π·L·A`,
/// and an isotropic point light of intensity `I = Φ / 4π = L·A / 4` emits as much. Emitting
/// surfaces cast no shadows (see the Whitted integrator), so the light is not blocked by its
/// own shape.
pub fn area_lights_as_points(
    ctx: &mut Context,
    emitters: &[(Rgb, EmitterSurface)],
    integrator: &str,
) {
    for (radiance, s) in emitters {
        ctx.builder.light(Light::Point(PointLight {
            position: s.centroid,
            intensity: *radiance * (s.area / 4.0),
            falloff: Falloff::Quadratic,
        }));
    }
    if !emitters.is_empty() {
        let what = if emitters.len() == 1 {
            "1 area light becomes a point light of the same power at its centre".to_string()
        } else {
            format!(
                "{} area lights become point lights of the same power at their centres",
                emitters.len()
            )
        };
        ctx.warnings.push(format!(
            "{}: {what} under the {integrator} integrator",
            ctx.source.path.display(),
        ));
    }
}

/// The rotation taking world directions to an environment image's frame, from the rotation
/// `m` (its linear part) places the image by; `None` unless that part is a rotation (to within
/// single-precision rounding of its entries).
fn environment_rotation(m: glam::Mat4) -> Option<glam::Mat3> {
    let r = glam::Mat3::from_mat4(m);
    let orthonormal = (r.transpose() * r).abs_diff_eq(glam::Mat3::IDENTITY, 1e-4);
    (orthonormal && r.determinant() > 0.0).then(|| r.transpose())
}
