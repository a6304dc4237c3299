//! Lights read from images: `type = "goniometric"` (an image of intensity over the sphere),
//! `type = "projection"` (an image thrown through a frustum) and `type = "spot"` with a `file`
//! (the image across the spot's cone).

use super::photometric::perpendicular;
use super::{Context, required};
use crate::desc::texture::Encoding;
use crate::desc::{LightDesc, MappingName};
use crate::error::LoadError;
use glam::{Mat3, Vec3};
use lucent::light::{Cone, ImageLight, IntensityImage, Light, Mapping, PointLight};
use std::sync::Arc;
use toml::Spanned;

/// The default vertical angle of a projector's image, in degrees.
const DEFAULT_FOV: f32 = 30.0;

/// The image of `file` as intensities (sRGB images decoded to linear; the light's `intensity`
/// scales them), laid on the sphere by `mapping` of its size and under `cone`.
fn intensity_image(
    ctx: &mut Context,
    file: &Spanned<String>,
    cone: Option<Cone>,
    mapping: impl FnOnce(usize, usize) -> Mapping,
) -> Result<Arc<IntensityImage>, LoadError> {
    let path = ctx.path(file.get_ref(), file.span())?;
    let image = crate::images::read_image(&path, Encoding::Srgb, &mut ctx.inputs)?;
    let (w, h) = (image.width() as usize, image.height() as usize);
    IntensityImage::new(mapping(w, h), cone, w, h, image.texels().to_vec())
        .map(Arc::new)
        .map_err(|e| LoadError::file(&path, e.to_string()))
}

/// A unit vector from the optional key `v` (or `default`), refused when zero.
fn unit(
    ctx: &Context,
    v: &Option<Spanned<crate::desc::Vector>>,
    default: Vec3,
    what: &str,
) -> Result<Vec3, LoadError> {
    match v {
        None => Ok(default),
        Some(v) => super::rescaled(v.get_ref().0)
            .try_normalize()
            .ok_or_else(|| {
                ctx.source
                    .error(v.span(), format!("`{what}` must not be zero"))
            }),
    }
}

/// The frame of a light looking along `forward` with `up` (made perpendicular to it) to the
/// image's top: rows right, up, forward — the world-to-light rotation of [`Mapping`]'s frame.
fn looking(forward: Vec3, up: Vec3) -> Option<Mat3> {
    let up = perpendicular(up, forward)?;
    let right = forward.cross(up);
    Some(Mat3::from_cols(right, up, forward).transpose())
}

/// The light of table `l` (goniometric or projection) with point light `point`.
pub fn light(
    ctx: &mut Context,
    l: &Spanned<LightDesc>,
    point: PointLight,
) -> Result<Light, LoadError> {
    let d = l.get_ref();
    let kind = d.kind.name();
    let file = required(ctx.source, l.span(), kind, "file", &d.file)?.clone();
    let (mapping, to_light) = match d.kind {
        crate::desc::LightKind::Goniometric => {
            let up = unit(ctx, &d.up, Vec3::Y, "up")?;
            let front = match &d.front {
                Some(f) => perpendicular(super::rescaled(f.get_ref().0), up).ok_or_else(|| {
                    ctx.source
                        .error(f.span(), "`front` must not be zero or along `up`")
                })?,
                None => perpendicular(Vec3::X, up)
                    .or_else(|| perpendicular(Vec3::NEG_Z, up))
                    .expect("x and z are not both along one direction"),
            };
            let mapping = match d.mapping.as_ref().map(|m| *m.get_ref()) {
                None | Some(MappingName::EqualArea) => Mapping::EqualArea,
                Some(MappingName::LatLong) => Mapping::LatLong,
            };
            // Right-handed: +x front, +y up, +z = x × y.
            let to_world = Mat3::from_cols(front, up, front.cross(up));
            (mapping, to_world.transpose())
        }
        _ => {
            let forward = unit(ctx, &d.direction, Vec3::NEG_Z, "direction")?;
            let up = unit(ctx, &d.up, Vec3::Y, "up")?;
            let to_light = looking(forward, up).ok_or_else(|| {
                let at = d.up.as_ref().map_or(l.span(), Spanned::span);
                ctx.source
                    .error(at, "a projector's `up` must not lie along its `direction`")
            })?;
            let fov = match &d.fov {
                None => DEFAULT_FOV,
                Some(f) if f.get_ref().0 > 0.0 && f.get_ref().0 < 180.0 => f.get_ref().0,
                Some(f) => {
                    return Err(ctx
                        .source
                        .error(f.span(), "a projector's fov must be in (0, 180) degrees"));
                }
            };
            let tan_y = (fov.to_radians() / 2.0).tan();
            // The horizontal angle follows from the image's aspect.
            let image = intensity_image(ctx, &file, None, |w, h| Mapping::Projection {
                tan_x: tan_y * w as f32 / h as f32,
                tan_y,
            })?;
            return Ok(Light::Image(ImageLight {
                point,
                to_light,
                image,
            }));
        }
    };
    let image = intensity_image(ctx, &file, None, |_, _| mapping)?;
    Ok(Light::Image(ImageLight {
        point,
        to_light,
        image,
    }))
}

/// A spot light of table `l` with an image `file` across its cone (a square circumscribing the
/// cutoff cone), under the spot's edge.
pub fn textured_spot(
    ctx: &mut Context,
    l: &Spanned<LightDesc>,
    point: PointLight,
    (direction, cone): (Vec3, Cone),
    file: &Spanned<String>,
) -> Result<Light, LoadError> {
    let d = l.get_ref();
    let to_light = match &d.up {
        Some(up) => {
            let v = unit(ctx, &d.up, Vec3::Y, "up")?;
            looking(direction, v).ok_or_else(|| {
                ctx.source.error(
                    up.span(),
                    "a spot's `up` must not lie along its `direction`",
                )
            })?
        }
        None => looking(direction, Vec3::Y)
            .or_else(|| looking(direction, Vec3::NEG_Z))
            .expect("y and z are not both along one direction"),
    };
    let tan = cone.cos_cutoff.acos().tan().min(1e4);
    let mapping = Mapping::Projection {
        tan_x: tan,
        tan_y: tan,
    };
    Ok(Light::Image(ImageLight {
        point,
        to_light,
        image: intensity_image(ctx, file, Some(cone), |_, _| mapping)?,
    }))
}
