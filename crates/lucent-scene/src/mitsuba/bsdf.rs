//! `<bsdf>` → `[[material]]`.
//!
//! | Mitsuba | lucent |
//! | --- | --- |
//! | `diffuse` (`reflectance`: colour or bitmap, default 0.5) | `diffuse` |
//! | `conductor`, `roughconductor` (`material` or `eta`/`k`, `specular_reflectance`, `alpha`) | `conductor`, `roughconductor` (`metal` or `eta`/`k`, `specular`, `roughness`) |
//! | `dielectric`, `roughdielectric`, `thindielectric` (`int_ior` default bk7, `ext_ior` default air, `specular_reflectance`, `specular_transmittance`) | `dielectric`, `roughdielectric` (`ior`, `ext_ior`, `specular`, `transmittance`) |
//! | `plastic`, `roughplastic` (`diffuse_reflectance` default 0.5, `int_ior` default polypropylene) | `plastic` (`reflectance`, `ior`, `roughness` when rough) |
//! | `twosided` around one BSDF | that BSDF with `two_sided = true` |
//!
//! Mitsuba's reflecting BSDFs are one-sided (black from behind) unless wrapped in `twosided`,
//! so they become `two_sided = false`. Dielectrics scatter from both sides in Mitsuba (the
//! inside refracts with the inverse ratio), which is what the kind itself means, so their
//! `two_sided` is left unset.

use super::Convert;
use super::ior;
use super::props::{Colorish, Plugin};
use super::xml::{Element, Loc};
use crate::desc::{Color, DiffuseDesc, Finite, MaterialDesc, MaterialKind};
use crate::error::LoadError;
use lucent::Rgb;
use std::collections::{HashMap, HashSet};
use toml::Spanned;

/// The BSDF types lucent reads.
pub const TYPES: &[&str] = &[
    "diffuse",
    "conductor",
    "roughconductor",
    "dielectric",
    "roughdielectric",
    "thindielectric",
    "plastic",
    "roughplastic",
    "twosided",
];

/// The conductors Mitsuba names that lucent knows as `metal`.
const METALS: &[&str] = &["Au", "Ag", "Cu", "Al"];

/// Deepest nesting of BSDFs (`twosided` in `twosided` …), against reference cycles.
const MAX_NESTING: usize = 8;

/// The materials made so far, each under a unique name.
pub struct Materials {
    /// In the order made.
    pub list: Vec<MaterialDesc>,
    by_element: HashMap<*const Element, usize>,
    names: HashSet<String>,
    default: Option<usize>,
    /// Every `<bsdf>` described (nested ones too) and every `<texture>` read.
    seen: HashSet<*const Element>,
}

impl Materials {
    /// No materials yet; `reserved` are the scene's ids (the names of declared BSDFs), kept
    /// apart from the names made up for anonymous ones.
    pub fn new<'a>(reserved: impl Iterator<Item = &'a str>) -> Self {
        Self {
            list: Vec::new(),
            by_element: HashMap::new(),
            names: reserved.map(str::to_string).collect(),
            default: None,
            seen: HashSet::new(),
        }
    }

    /// `base`, or `base (2)`, `base (3)`, … whichever is free.
    fn unique(&mut self, base: String) -> String {
        let mut name = base.clone();
        let mut n = 2;
        while self.names.contains(&name) {
            name = format!("{base} ({n})");
            n += 1;
        }
        self.names.insert(name.clone());
        name
    }

    /// Whether the `<bsdf>` `el` has been described, or the `<texture>` `el` read.
    pub fn seen(&self, el: &Element) -> bool {
        self.seen.contains(&std::ptr::from_ref(el))
    }

    fn push(&mut self, m: MaterialDesc) -> usize {
        self.list.push(m);
        self.list.len() - 1
    }

    fn name(&self, index: usize) -> String {
        self.list[index].name.get_ref().clone()
    }
}

/// `file:line:column` with the file's name only, for made-up names.
fn short(loc: &Loc) -> String {
    let file = loc.file.file_name().map_or_else(
        || loc.file.display().to_string(),
        |f| f.to_string_lossy().into_owned(),
    );
    format!("{file}:{}:{}", loc.line, loc.column)
}

/// The name of the material of the `<bsdf>` `el`, described and added on first use; named by
/// its `id`, or after its type and place.
pub fn material<'a>(cx: &mut Convert<'a>, el: &'a Element) -> Result<String, LoadError> {
    let key: *const Element = el;
    if let Some(&i) = cx.materials.by_element.get(&key) {
        return Ok(cx.materials.name(i));
    }
    let mut desc = describe(cx, el, 0)?;
    let name = match el.value("id") {
        Some(id) => id.to_string(),
        None => {
            let kind = el.value("type").unwrap_or("bsdf");
            cx.materials.unique(format!("{kind} at {}", short(&el.loc)))
        }
    };
    desc.name = Spanned::new(0..0, name.clone());
    let i = cx.materials.push(desc);
    cx.materials.by_element.insert(key, i);
    Ok(name)
}

/// Mitsuba's material for shapes without a BSDF: one-sided diffuse, reflectance 0.5.
pub fn default_material(cx: &mut Convert) -> String {
    if let Some(i) = cx.materials.default {
        return cx.materials.name(i);
    }
    let name = cx.materials.unique("default diffuse".to_string());
    let mut m = MaterialDesc::named(&name);
    m.kind = Some(Spanned::new(0..0, MaterialKind::Diffuse));
    m.reflectance = Some(DiffuseDesc::Solid(Rgb::gray(0.5)));
    m.two_sided = Some(false);
    let i = cx.materials.push(m);
    cx.materials.default = Some(i);
    name
}

/// A copy of material `base` that emits `radiance`: an area emitter at `at`.
pub fn emissive(cx: &mut Convert, base: &str, radiance: Rgb, at: &Loc) -> String {
    let index = cx
        .materials
        .list
        .iter()
        .position(|m| m.name.get_ref() == base)
        .expect("the base material was made first");
    let name = cx
        .materials
        .unique(format!("{base} emitting at {}", short(at)));
    let mut m = cx.materials.list[index].clone();
    m.name = Spanned::new(0..0, name.clone());
    m.emission = Some(Color(radiance));
    cx.materials.push(m);
    name
}

/// The description of the `<bsdf>` `el` (its name left empty).
pub fn describe<'a>(
    cx: &mut Convert<'a>,
    el: &'a Element,
    depth: usize,
) -> Result<MaterialDesc, LoadError> {
    if depth > MAX_NESTING {
        return Err(el.loc.error(format!(
            "BSDFs nested more than {MAX_NESTING} deep (does a <ref> refer to its own bsdf?)"
        )));
    }
    cx.materials.seen.insert(el);
    let p = cx.plugin(el)?;
    let mut m = MaterialDesc::named("");
    let kind = |k| Some(Spanned::new(0..0, k));
    let finite = |v: f64| Some(Spanned::new(0..0, Finite(v as f32)));
    let mut silent: &[&str] = &[];
    match p.kind {
        "diffuse" => {
            m.kind = kind(MaterialKind::Diffuse);
            m.reflectance = Some(diffuse(cx, &p, "reflectance")?);
            m.two_sided = Some(false);
        }
        "conductor" | "roughconductor" => {
            let rough = p.kind == "roughconductor";
            m.kind = kind(if rough {
                MaterialKind::RoughConductor
            } else {
                MaterialKind::Conductor
            });
            conductor(&p, &mut m)?;
            m.specular = p.color("specular_reflectance")?.map(Color);
            if rough {
                m.roughness = finite(roughness(cx, &p)?);
                silent = &["sample_visible"];
            }
            m.two_sided = Some(false);
        }
        "dielectric" | "roughdielectric" | "thindielectric" => {
            let rough = p.kind == "roughdielectric";
            m.kind = kind(if rough {
                MaterialKind::RoughDielectric
            } else {
                MaterialKind::Dielectric
            });
            if p.kind == "thindielectric" {
                p.warn(
                    &el.loc,
                    "a thindielectric (a thin sheet: no offset through it) is read as a solid dielectric",
                );
            }
            m.ior = finite(ior::read(&p, "int_ior", "bk7")?);
            m.ext_ior = finite(ior::read(&p, "ext_ior", "air")?);
            m.specular = p.color("specular_reflectance")?.map(Color);
            m.transmittance = p.color("specular_transmittance")?.map(Color);
            if rough {
                m.roughness = finite(roughness(cx, &p)?);
                silent = &["sample_visible"];
            }
        }
        "plastic" | "roughplastic" => {
            m.kind = kind(MaterialKind::Plastic);
            m.reflectance = Some(diffuse(cx, &p, "diffuse_reflectance")?);
            m.specular = p.color("specular_reflectance")?.map(Color);
            m.ior = finite(ior::read(&p, "int_ior", "polypropylene")?);
            m.ext_ior = finite(ior::read(&p, "ext_ior", "air")?);
            if p.kind == "roughplastic" {
                m.roughness = finite(roughness(cx, &p)?);
                silent = &["sample_visible"];
            }
            m.two_sided = Some(false);
        }
        "twosided" => {
            let inner = p.take("bsdf");
            let one = match inner[..] {
                [one] => one,
                [] => return Err(el.loc.error("a twosided bsdf needs one bsdf inside")),
                _ => {
                    return Err(inner[1].at.error(
                        "a twosided bsdf with different front and back bsdfs is not read by lucent",
                    ));
                }
            };
            m = describe(cx, one.el, depth + 1)?;
            if matches!(
                m.kind(),
                MaterialKind::Dielectric | MaterialKind::RoughDielectric
            ) {
                return Err(one
                    .at
                    .error("a twosided bsdf cannot hold a dielectric (it has two sides already)"));
            }
            m.two_sided = Some(true);
        }
        other => return Err(super::unknown_type(el, other)),
    }
    p.finish(&mut cx.warnings, silent);
    Ok(m)
}

/// A diffuse albedo: a colour (default 0.5) or a `bitmap` texture's file.
fn diffuse<'a>(cx: &mut Convert<'a>, p: &Plugin<'a>, name: &str) -> Result<DiffuseDesc, LoadError> {
    Ok(match p.color_or_texture(name)? {
        None => DiffuseDesc::Solid(Rgb::gray(0.5)),
        Some(Colorish::Color(c)) => DiffuseDesc::Solid(c),
        Some(Colorish::Texture(t)) => DiffuseDesc::Image(bitmap(cx, t)?),
    })
}

/// The file of a `<texture type="bitmap">`, as written (relative to the scene's folder).
pub fn bitmap<'a>(cx: &mut Convert<'a>, el: &'a Element) -> Result<String, LoadError> {
    cx.materials.seen.insert(el);
    let t = cx.plugin(el)?;
    if t.kind != "bitmap" {
        return Err(super::unknown_type(el, t.kind));
    }
    let (file, loc) = t.required_string("filename")?;
    let file = cx.file_name(file, loc, "image")?;
    if t.boolean("raw")? == Some(true) {
        t.warn(
            &el.loc,
            "`raw` is not read: lucent decodes 8-bit images as sRGB and float images as linear",
        );
    }
    t.finish(&mut cx.warnings, &[]);
    Ok(file)
}

/// A conductor's `material` (default `none`: Mitsuba's perfect mirror) or `eta` and `k`.
fn conductor(p: &Plugin, m: &mut MaterialDesc) -> Result<(), LoadError> {
    let eta = p.color("eta")?;
    let k = p.color("k")?;
    match p.string("material")? {
        None | Some(("none", _)) => {
            // Mitsuba's "none" is η = 0, k = 1: a Fresnel reflectance of 1 at every angle.
            m.eta = Some(Color(eta.unwrap_or(Rgb::BLACK)));
            m.k = Some(Color(k.unwrap_or(Rgb::WHITE)));
        }
        Some((name, loc)) => {
            if eta.is_some() || k.is_some() {
                return Err(loc.error("give either `material` or `eta` and `k`, not both"));
            }
            if !METALS.contains(&name) {
                return Err(loc.error(format!(
                    "conductor material `{name}`: lucent knows {} and none; give `eta` and `k` instead",
                    METALS.join(", ")
                )));
            }
            m.metal = Some(Spanned::new(0..0, name.to_string()));
        }
    }
    Ok(())
}

/// A rough BSDF's α (default 0.1): `alpha`, or the mean of `alpha_u` and `alpha_v` (lucent's
/// microfacets are isotropic), clamped to `[1e-4, 1]`. lucent's microfacets are GGX; Mitsuba's
/// default, Beckmann, is read as GGX of the same α, and its place noted for one warning about
/// them all ([`beckmann_warning`]).
fn roughness(cx: &mut Convert, p: &Plugin) -> Result<f64, LoadError> {
    let distribution = p.string("distribution")?;
    match distribution.map(|(d, loc)| (d.to_lowercase(), loc)) {
        Some((d, _)) if d == "ggx" => {}
        Some((d, loc)) if d != "beckmann" => {
            return Err(loc.error(format!(
                "unknown microfacet distribution `{d}` (Mitsuba's are beckmann and ggx)"
            )));
        }
        _ => {
            if !cx.beckmann.contains(&p.el.loc) {
                cx.beckmann.push(p.el.loc.clone());
            }
        }
    }
    let alpha = match p.float("alpha")? {
        Some(alpha) => alpha,
        None => {
            let u = p.float_or("alpha_u", 0.1)?;
            let v = p.float_or("alpha_v", 0.1)?;
            if u != v {
                p.warn(
                    &p.el.loc,
                    format!(
                        "anisotropic roughness (alpha_u {u}, alpha_v {v}) is read as their mean {}: lucent's microfacets are isotropic",
                        (u + v) / 2.0
                    ),
                );
            }
            (u + v) / 2.0
        }
    };
    // Mitsuba clamps α to at least 1e-4 (its microfacet distribution's own floor); lucent's
    // roughness ends at 1, the roughest surface GGX describes well.
    if alpha > 1.0 {
        p.warn(
            &p.el.loc,
            format!(
                "the {}'s alpha {alpha} is read as 1, lucent's roughest",
                p.what()
            ),
        );
    }
    Ok(alpha.clamp(1e-4, 1.0))
}

/// The one warning about every rough BSDF (at `places`) whose Beckmann microfacets are read as
/// GGX; `None` when there are none.
pub fn beckmann_warning(places: &[Loc]) -> Option<String> {
    let (first, others) = places.split_first()?;
    let also = match others.len() {
        0 => "the rough BSDF here uses".to_string(),
        n => {
            const LISTED: usize = 3;
            let listed: Vec<String> = others.iter().take(LISTED).map(short).collect();
            let more = if n > LISTED {
                format!(" and {} more", n - LISTED)
            } else {
                String::new()
            };
            format!(
                "the rough BSDFs here and at {}{more} use",
                listed.join(", ")
            )
        }
    };
    Some(first.warning(format!(
        "{also} Mitsuba's default Beckmann microfacets, read as GGX with the same alpha"
    )))
}
