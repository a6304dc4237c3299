//! `<texture>` → a texture description.
//!
//! | Mitsuba | lucent |
//! | --- | --- |
//! | `bitmap` (`filename`, `raw`, `filter_type`, `wrap_mode`, `to_uv`) | `{ image = …, encoding = "linear"` when `raw`, `"srgb"` otherwise`, filter, wrap, scale/offset/rotation }` |
//! | `checkerboard` (`color0` 0.4, `color1` 0.2, `to_uv`) | `{ checkerboard = { even, odd }, … }` |
//! | `mesh_attribute` (`name = "vertex_color"`) | `{ vertex_color = true }` |
//!
//! Mitsuba's `bilinear` filter has no MIP-maps; lucent's default (anisotropic, MIP-mapped) filter narrows its
//! footprint as samples accumulate and gives the same image at high sample counts, without
//! aliasing at low ones, so `bilinear` is read as lucent's default. A `to_uv` must be a
//! scale, rotation and offset (no shear, no mirror): the placement lucent describes.

use super::Convert;
use super::props::{Colorish, Plugin};
use super::xml::{Element, Loc};
use crate::desc::texture::{Encoding, Placement};
use crate::desc::{ImageMapDesc, TextureDesc};
use crate::error::LoadError;
use glam::DMat4;
use lucent::texture::{Filter, Wrap};

/// The texture types lucent reads.
pub const TYPES: &[&str] = &["bitmap", "checkerboard", "mesh_attribute"];

/// The texture or colour of `name` in `p`; `None` when not given.
pub fn param<'a>(
    cx: &mut Convert<'a>,
    p: &Plugin<'a>,
    name: &str,
) -> Result<Option<TextureDesc>, LoadError> {
    Ok(match p.color_or_texture(name)? {
        None => None,
        Some(Colorish::Color(c)) => Some(TextureDesc::Solid(c)),
        Some(Colorish::Texture(t)) => Some(texture(cx, t)?),
    })
}

/// The texture or colour of `name` in `p`, or grey `default`.
pub fn param_or<'a>(
    cx: &mut Convert<'a>,
    p: &Plugin<'a>,
    name: &str,
    default: f32,
) -> Result<TextureDesc, LoadError> {
    Ok(param(cx, p, name)?.unwrap_or(TextureDesc::gray(default)))
}

/// The description of the `<texture>` `el`.
pub fn texture<'a>(cx: &mut Convert<'a>, el: &'a Element) -> Result<TextureDesc, LoadError> {
    cx.materials.mark_seen(el);
    let t = cx.plugin(el)?;
    let out = match t.kind {
        "bitmap" => bitmap(cx, &t)?,
        "checkerboard" => {
            let even = t.color_or("color0", 0.4)?;
            let odd = t.color_or("color1", 0.2)?;
            TextureDesc::Checkerboard {
                even,
                odd,
                placement: to_uv(&t)?,
            }
        }
        "mesh_attribute" => {
            let (name, loc) = t.required_string("name")?;
            if name != "vertex_color" {
                return Err(loc.error(format!(
                    "the mesh attribute `{name}` is not read by lucent (only `vertex_color`)"
                )));
            }
            if let Some(s) = t.float("scale")?
                && s != 1.0
            {
                let scaled = TextureDesc::Product(
                    Box::new(TextureDesc::VertexColor),
                    Box::new(TextureDesc::gray(s as f32)),
                );
                t.finish(&mut cx.warnings, &[]);
                return Ok(scaled);
            }
            TextureDesc::VertexColor
        }
        other => return Err(super::unknown_type(el, other)),
    };
    t.finish(&mut cx.warnings, &[]);
    Ok(out)
}

/// A bitmap's image lookup.
fn bitmap<'a>(cx: &mut Convert<'a>, t: &Plugin<'a>) -> Result<TextureDesc, LoadError> {
    let (file, loc) = t.required_string("filename")?;
    let file = cx.file_name(file, loc, "image")?;
    let mut image = ImageMapDesc::new(file);
    image.encoding = Some(if t.boolean("raw")? == Some(true) {
        Encoding::Linear
    } else {
        Encoding::Srgb
    });
    if let Some((f, loc)) = t.string("filter_type")? {
        image.filter = match f {
            "bilinear" => None,
            "nearest" => Some(Filter::Nearest),
            other => {
                return Err(loc.error(format!(
                    "unknown filter_type `{other}` (Mitsuba's are bilinear and nearest)"
                )));
            }
        };
    }
    if let Some((w, loc)) = t.string("wrap_mode")? {
        let mode = match w {
            "repeat" => Wrap::Repeat,
            "mirror" => Wrap::Mirror,
            "clamp" => Wrap::Clamp,
            other => {
                return Err(loc.error(format!(
                    "unknown wrap_mode `{other}` (Mitsuba's are repeat, mirror and clamp)"
                )));
            }
        };
        image.wrap = Some([mode; 2]);
    }
    image.placement = to_uv(t)?;
    Ok(TextureDesc::Image(image))
}

/// A texture's `to_uv` as a placement: Mitsuba applies the 4 × 4 matrix's upper-left 2 × 2
/// and its translation's x and y to `(u, v)`.
fn to_uv(t: &Plugin) -> Result<Placement, LoadError> {
    let Some((m, loc)) = t.transform("to_uv")? else {
        return Ok(Placement::default());
    };
    placement(&m, loc)
}

/// The scale, rotation and offset of a 2D affine map, or an error when it shears or mirrors.
fn placement(m: &DMat4, loc: &Loc) -> Result<Placement, LoadError> {
    let (a, b) = (m.x_axis.x, m.y_axis.x);
    let (c, d) = (m.x_axis.y, m.y_axis.y);
    let (tx, ty) = (m.w_axis.x, m.w_axis.y);
    // M = R(θ)·diag(su, sv): its columns are orthogonal, of lengths su and sv.
    let su = (a * a + c * c).sqrt();
    let sv = (b * b + d * d).sqrt();
    let det = a * d - b * c;
    let orthogonal = (a * b + c * d).abs() <= 1e-6 * su * sv;
    if !(su > 0.0 && sv > 0.0 && det > 0.0 && orthogonal) {
        return Err(loc.error(
            "a texture's to_uv must scale, rotate and translate (no shear, mirror or projection)",
        ));
    }
    let rotation = c.atan2(a).to_degrees();
    let round = |v: f64| v as f32;
    Ok(Placement {
        scale: Some([round(su), round(sv)]).filter(|s| *s != [1.0, 1.0]),
        offset: Some([round(tx), round(ty)]).filter(|o| *o != [0.0, 0.0]),
        rotation: Some(round(rotation)).filter(|r| *r != 0.0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mitsuba::xml::Loc;

    #[test]
    fn a_uv_transform_splits_into_scale_rotation_and_offset() {
        let loc = Loc {
            file: std::rc::Rc::from(std::path::Path::new("t.xml")),
            line: 1,
            column: 1,
        };
        let m = DMat4::from_translation(glam::DVec3::new(0.5, 0.25, 0.0))
            * DMat4::from_rotation_z(30f64.to_radians())
            * DMat4::from_scale(glam::DVec3::new(4.0, 2.0, 1.0));
        let p = placement(&m, &loc).unwrap();
        assert_eq!(p.scale, Some([4.0, 2.0]));
        assert_eq!(p.offset, Some([0.5, 0.25]));
        assert!((p.rotation.unwrap() - 30.0).abs() < 1e-4);
        // The placement's transform is the matrix's.
        let t = p.transform();
        let uv = glam::Vec2::new(0.3, 0.7);
        let want = m.transform_point3(glam::DVec3::new(0.3, 0.7, 0.0));
        assert!((t.apply(uv) - glam::Vec2::new(want.x as f32, want.y as f32)).length() < 1e-5);
        let shear = DMat4::from_cols_array(&[
            1.0, 0.0, 0.0, 0.0, 0.5, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0,
        ]);
        assert!(placement(&shear, &loc).is_err());
    }
}
