//! `<medium>` and `<phase>` → `[[medium]]`.
//!
//! | Mitsuba | lucent |
//! | --- | --- |
//! | `homogeneous` (`sigma_t`, default 1; `albedo`, default 0.75; `scale`, default 1) | `sigma_t`, `albedo`, `scale` |
//! | `<phase type="isotropic">`, `<phase type="hg">` (`g`, default 0.8), none: isotropic | `g` |
//! | a shape's `<medium name="interior">` / `name="exterior"` (nested or `<ref>`) | the object's `interior`, `exterior` |
//! | a sensor's `<medium>` | the camera's `medium` |
//!
//! Constant values only (a number, `<rgb>`, `<spectrum>`); grids (`heterogeneous`, volumes)
//! are refused. `sample_emitters` is not read: lucent always samples the lights.

use super::Convert;
use super::xml::Element;
use crate::desc::{Color, Finite, MediumDesc};
use crate::error::LoadError;
use std::collections::HashMap;
use toml::Spanned;

/// The medium types lucent reads.
pub const TYPES: &[&str] = &["homogeneous"];
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
    m.sigma_t = color(p.color_or("sigma_t", 1.0)?);
    let albedo = p.color_or("albedo", 0.75)?;
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
    p.finish(&mut cx.warnings, &["sample_emitters"]);
    cx.media.list.push(m);
    cx.media.by_element.insert(el, name.clone());
    Ok(name)
}
