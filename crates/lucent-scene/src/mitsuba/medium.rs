//! `<medium>` and `<phase>` → `[[medium]]`.
//!
//! | Mitsuba | lucent |
//! | --- | --- |
//! | `homogeneous` (`sigma_t`, default 1; `albedo`, default 0.75; `scale`, default 1) | `sigma_t`, `albedo`, `scale` |
//! | `heterogeneous`: `sigma_t` a `gridvolume` (`filename`, `to_world`: the unit cube's place) | `density` (the file), `bounds` |
//! | `heterogeneous`: `albedo` a `gridvolume` (1 or 3 channels) over the same box | `albedo_grid` |
//! | a `constvolume`'s `value` for `sigma_t` or `albedo` | that constant |
//! | `<phase type="isotropic">`, `<phase type="hg">` (`g`, default 0.8), none: isotropic | `g` |
//! | a shape's `<medium name="interior">` / `name="exterior"` (nested or `<ref>`) | the object's `interior`, `exterior` |
//! | a sensor's `<medium>` | the camera's `medium` |
//!
//! A grid's `to_world` must scale and move the unit cube without turning it (a box in the
//! scene's axes), and `use_grid_bbox` places it at the box its file gives. An albedo grid elsewhere
//! than the `sigma_t` grid, a `nearest` filter and grids in a `homogeneous` medium are refused. Outside its
//! box a grid's density is 0 in lucent, where Mitsuba clamps its edge values outward: the same
//! wherever the bounding shape lies within the box. `sample_emitters` is not read: lucent
//! always samples the lights; nor are the majorant settings, which change only noise.

use super::Convert;
use super::props::Child;
use super::xml::Element;
use crate::desc::{Color, Finite, MediumDesc, Point};
use crate::error::LoadError;
use glam::{DMat4, DVec3};
use lucent::Rgb;
use std::collections::HashMap;
use toml::Spanned;

/// The medium types lucent reads.
pub const TYPES: &[&str] = &["homogeneous", "heterogeneous"];
/// The volume types lucent reads.
pub const VOLUMES: &[&str] = &["constvolume", "gridvolume"];
/// The phase function types lucent reads.
pub const PHASES: &[&str] = &["isotropic", "hg"];

/// The media read so far, each once, under a unique name.
#[derive(Default)]
pub struct Media {
    /// In the order read.
    pub list: Vec<MediumDesc>,
    by_element: HashMap<*const Element, String>,
}

/// The name of the medium of `<medium>` `el`, read on first use.
pub fn named<'a>(cx: &mut Convert<'a>, el: &'a Element) -> Result<String, LoadError> {
    if let Some(name) = cx.media.by_element.get(&std::ptr::from_ref(el)) {
        return Ok(name.clone());
    }
    let p = cx.plugin(el)?;
    if !TYPES.contains(&p.kind) {
        return Err(super::unknown_type(el, p.kind));
    }
    let name = match el.value("id") {
        Some(id) => id.to_string(),
        None => format!("medium {}", cx.media.list.len() + 1),
    };
    let mut m = MediumDesc::new(&name);
    let color = |c| Some(Spanned::new(0..0, Color(c)));
    let volumes = p.take("volume");
    let given = |name| volumes.iter().any(|v| v.name == Some(name));
    let (mut sigma_t, mut albedo) = (Rgb::WHITE, Rgb::gray(0.75));
    if !given("sigma_t") {
        sigma_t = p.color_or("sigma_t", 1.0)?;
    }
    if !given("albedo") {
        albedo = p.color_or("albedo", 0.75)?;
    }
    let mut albedo_grid = None;
    for v in volumes {
        match v.name {
            Some("sigma_t") => match volume(cx, v, p.kind == "heterogeneous")? {
                Volume::Constant(c) => sigma_t = c,
                Volume::Grid(file, bounds) => {
                    m.density = Some(Spanned::new(0..0, file));
                    m.bounds = bounds.map(|b| Spanned::new(0..0, b));
                }
            },
            Some("albedo") => match volume(cx, v, p.kind == "heterogeneous")? {
                Volume::Constant(c) => albedo = c,
                Volume::Grid(file, bounds) => albedo_grid = Some((file, bounds, v.at)),
            },
            _ => {
                return Err(v.at.error(format!(
                    "a medium's volumes are `sigma_t` and `albedo`, not `{}`",
                    v.name.unwrap_or("(unnamed)")
                )));
            }
        }
    }
    if let Some((file, bounds, at)) = albedo_grid {
        if m.density.is_none() {
            return Err(
                at.error("an albedo grid needs a `sigma_t` grid (lucent reads both or the latter)")
            );
        }
        if bounds != m.bounds.as_ref().map(|b| *b.get_ref()) {
            return Err(at.error(
                "the albedo grid must span the same box as the `sigma_t` grid (the same `to_world`)",
            ));
        }
        m.albedo_grid = Some(Spanned::new(0..0, file));
    }
    m.sigma_t = color(sigma_t);
    if albedo.max_channel() > 1.0 {
        return Err(el.loc.error(format!(
            "the albedo must be at most 1 in every channel, got {albedo:?}"
        )));
    }
    m.albedo = color(albedo);
    let scale = p.float_or("scale", 1.0)?;
    if scale.is_nan() || scale < 0.0 || !(scale as f32).is_finite() {
        return Err(el
            .loc
            .error(format!("`scale` must be at least 0, got {scale}")));
    }
    m.scale = Some(Spanned::new(0..0, Finite(scale as f32)));
    let phases = p.take("phase");
    if let Some(extra) = phases.get(1) {
        return Err(extra
            .at
            .error("a medium has one phase function; this is a second"));
    }
    if let Some(phase) = phases.first() {
        let ph = cx.plugin(phase.el)?;
        let g = match ph.kind {
            "isotropic" => 0.0,
            "hg" => ph.float_or("g", 0.8)?,
            other => return Err(super::unknown_type(phase.el, other)),
        };
        if g.is_nan() || g.abs() >= 1.0 {
            return Err(phase.el.loc.error(format!(
                "the hg phase function's g lies strictly between −1 and 1, not {g}"
            )));
        }
        m.g = Some(Spanned::new(0..0, Finite(g as f32)));
        ph.finish(&mut cx.warnings, &[]);
    }
    p.finish(
        &mut cx.warnings,
        &[
            "sample_emitters",
            "has_spectral_extinction",
            "majorant_resolution_factor",
            "majorant_factor",
        ],
    );
    cx.media.list.push(m);
    cx.media.by_element.insert(el, name.clone());
    Ok(name)
}

/// What a `<volume>` gives: a constant, or a grid file with the box it spans (`None`: the
/// file's own).
enum Volume {
    Constant(Rgb),
    Grid(String, Option<[Point; 2]>),
}

/// The `<volume>` `v`; a grid only where `grid_allowed`.
fn volume<'a>(cx: &mut Convert<'a>, v: Child<'a>, grid_allowed: bool) -> Result<Volume, LoadError> {
    let g = cx.plugin(v.el)?;
    let volume = match g.kind {
        "constvolume" => Volume::Constant(g.color_or("value", 1.0)?),
        "gridvolume" if !grid_allowed => {
            return Err(v.at.error(format!(
                "a grid of `{}` is not read: lucent reads a `heterogeneous` medium's grids",
                v.name.unwrap_or("")
            )));
        }
        "gridvolume" => {
            let (file, loc) = g.required_string("filename")?;
            let file = cx.file_name(file, loc, "volume grid")?;
            if let Some((filter, loc)) = g.string("filter_type")?
                && filter != "trilinear"
            {
                return Err(loc.error(format!(
                    "filter_type `{filter}` is not read: lucent interpolates grids trilinearly"
                )));
            }
            let to_world = g.transform("to_world")?;
            let bounds = if g.boolean("use_grid_bbox")? == Some(true) {
                if let Some((_, loc)) = to_world {
                    return Err(loc.error(
                        "a `to_world` with `use_grid_bbox` is not read: give one or the other",
                    ));
                }
                None
            } else {
                let (m, loc) = to_world.map_or((DMat4::IDENTITY, None), |(m, l)| (m, Some(l)));
                Some(box_of(&m).ok_or_else(|| {
                    let message = "a grid's `to_world` must scale and move the unit cube without turning or mirroring it";
                    match loc {
                        Some(loc) => loc.error(message),
                        None => v.at.error(message),
                    }
                })?)
            };
            Volume::Grid(file, bounds)
        }
        other => return Err(super::unknown_type(v.el, other)),
    };
    g.finish(&mut cx.warnings, &["raw"]);
    Ok(volume)
}

/// The box `m` makes of the unit cube, if it only scales (by positive factors) and moves it.
fn box_of(m: &DMat4) -> Option<[Point; 2]> {
    let axes = [m.x_axis, m.y_axis, m.z_axis];
    let turned = (0..3).any(|a| (0..3).any(|b| a != b && axes[a][b] != 0.0));
    let flat = (0..3).any(|a| axes[a][a] <= 0.0 || axes[a][a].is_nan());
    let projective = m.row(3) != glam::DVec4::new(0.0, 0.0, 0.0, 1.0);
    if turned || flat || projective {
        return None;
    }
    let min = m.transform_point3(DVec3::ZERO);
    let max = m.transform_point3(DVec3::ONE);
    Some([Point(min), Point(max)])
}
