//! `<bsdf>` → `[[material]]`.
//!
//! | Mitsuba | lucent |
//! | --- | --- |
//! | `diffuse` (`reflectance`, default 0.5) | `diffuse` |
//! | `conductor`, `roughconductor` (`material` or `eta`/`k`, `specular_reflectance`, `distribution`, `alpha` or `alpha_u`/`alpha_v`) | `conductor`, `roughconductor` (`metal` or `eta`/`k`, `specular`, `distribution`, `roughness` or `roughness_u`/`roughness_v`) |
//! | `dielectric`, `roughdielectric`, `thindielectric` (`int_ior` default bk7, `ext_ior` default air, `specular_reflectance`, `specular_transmittance`) | `dielectric`, `roughdielectric`, `thindielectric` (`ior`, `ext_ior`, `specular`, `transmittance`) |
//! | `plastic`, `roughplastic` (`diffuse_reflectance` default 0.5, `int_ior` default polypropylene, `nonlinear`) | `plastic`, `roughplastic` (`reflectance`, `ior`, `nonlinear`) |
//! | `twosided` around one BSDF / two BSDFs | that BSDF with `two_sided = true` / with `back` |
//! | `blendbsdf` (`weight`, two BSDFs) | `blend` (`weight`, `materials`) |
//! | `mask` (`opacity`, one BSDF) | that BSDF with `opacity` |
//! | `principled` (`base_color`, `roughness`, `anisotropic`, `metallic`, `spec_trans`, `spec_tint`, `sheen`, `sheen_tint`, `flatness`, `clearcoat`, `clearcoat_gloss`, `eta` or `specular`) | `principled` (the same names, `ior` or `specular`) |
//! | `principledthin` (`base_color`, `roughness`, `anisotropic`, `spec_trans`, `diff_trans`, `spec_tint`, `sheen`, `sheen_tint`, `flatness`, `eta`) | `principledthin` (the same names, `ior`) |
//! | `bumpmap` (a texture, `scale`, one BSDF) / `normalmap` (`normalmap`, one BSDF) | that BSDF with `bump_map`, `bump_scale` / `normal_map` |
//!
//! Every parameter Mitsuba textures may be a `<texture>` (see `mitsuba/texture.rs`).
//! Microfacets default to Beckmann (α 0.1), as Mitsuba's do. Mitsuba's reflecting BSDFs are
//! one-sided (black from behind) unless wrapped in `twosided`, so they become
//! `two_sided = false`. Dielectrics scatter from both sides in Mitsuba (the inside refracts
//! with the inverse ratio), which is what the kind itself means, so their `two_sided` is left
//! unset.
//!
//! A `mask`'s cut-away parts let shadow rays through in lucent (as a cut-out should, and as
//! glTF's alpha requires); Mitsuba's shadow rays are blocked by them, so a masked surface
//! that stands between a light and what it lights renders darker shadows in Mitsuba.

use super::Convert;
use super::ior;
use super::props::Plugin;
use super::texture::{param, param_or};
use super::xml::{Element, Loc};
use crate::desc::{Finite, MaterialDesc, MaterialKind, TextureDesc};
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
    "blendbsdf",
    "mask",
    "bumpmap",
    "normalmap",
    "principled",
    "principledthin",
    "null",
];

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

    /// Notes that `el` has been read.
    pub fn mark_seen(&mut self, el: &Element) {
        self.seen.insert(el);
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
    material_at(cx, el, 0)
}

fn material_at<'a>(
    cx: &mut Convert<'a>,
    el: &'a Element,
    depth: usize,
) -> Result<String, LoadError> {
    let key: *const Element = el;
    if let Some(&i) = cx.materials.by_element.get(&key) {
        return Ok(cx.materials.name(i));
    }
    let mut desc = describe(cx, el, depth)?;
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
    let mut m = MaterialDesc::of_kind(&name, MaterialKind::Diffuse);
    m.reflectance = Some(TextureDesc::gray(0.5));
    m.two_sided = Some(false);
    m.vertex_colors = Some(false);
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
    m.emission = Some(TextureDesc::Solid(radiance));
    cx.materials.push(m);
    name
}

fn spanned<T>(v: T) -> Spanned<T> {
    Spanned::new(0..0, v)
}

fn finite(v: f64) -> Option<Spanned<Finite>> {
    Some(spanned(Finite(v as f32)))
}

/// The one nested BSDF of a wrapper (`mask`, `bumpmap`, `normalmap`, `twosided`).
fn one_bsdf<'a>(p: &Plugin<'a>, el: &'a Element) -> Result<&'a Element, LoadError> {
    let inner = p.take("bsdf");
    match inner[..] {
        [one] => Ok(one.el),
        [] => Err(el.loc.error(format!("a {} needs one bsdf inside", p.kind))),
        _ => Err(inner[1]
            .at
            .error(format!("a {} holds one bsdf; this is a second", p.kind))),
    }
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
    cx.materials.mark_seen(el);
    let p = cx.plugin(el)?;
    let mut m = MaterialDesc::named("");
    m.vertex_colors = Some(false);
    let kind = |k| Some(spanned(k));
    let mut silent: &[&str] = &[];
    match p.kind {
        "null" => m.kind = kind(MaterialKind::Null),
        "diffuse" => {
            m.kind = kind(MaterialKind::Diffuse);
            m.reflectance = Some(param_or(cx, &p, "reflectance", 0.5)?);
            m.two_sided = Some(false);
        }
        "conductor" | "roughconductor" => {
            let rough = p.kind == "roughconductor";
            m.kind = kind(if rough {
                MaterialKind::RoughConductor
            } else {
                MaterialKind::Conductor
            });
            conductor(cx, &p, &mut m)?;
            m.specular = param(cx, &p, "specular_reflectance")?;
            if rough {
                microfacets(cx, &p, &mut m, true)?;
                silent = &["sample_visible"];
            }
            m.two_sided = Some(false);
        }
        "dielectric" | "roughdielectric" | "thindielectric" => {
            m.kind = kind(match p.kind {
                "roughdielectric" => MaterialKind::RoughDielectric,
                "thindielectric" => MaterialKind::ThinDielectric,
                _ => MaterialKind::Dielectric,
            });
            m.ior = finite(ior::read(&p, "int_ior", "bk7")?);
            m.ext_ior = finite(ior::read(&p, "ext_ior", "air")?);
            m.specular = param(cx, &p, "specular_reflectance")?;
            m.transmittance = param(cx, &p, "specular_transmittance")?;
            if p.kind == "roughdielectric" {
                microfacets(cx, &p, &mut m, true)?;
                silent = &["sample_visible"];
            }
        }
        "plastic" | "roughplastic" => {
            let rough = p.kind == "roughplastic";
            m.kind = kind(if rough {
                MaterialKind::RoughPlastic
            } else {
                MaterialKind::Plastic
            });
            m.reflectance = Some(param_or(cx, &p, "diffuse_reflectance", 0.5)?);
            m.specular = param(cx, &p, "specular_reflectance")?;
            m.ior = finite(ior::read(&p, "int_ior", "polypropylene")?);
            m.ext_ior = finite(ior::read(&p, "ext_ior", "air")?);
            if p.boolean("nonlinear")? == Some(true) {
                m.nonlinear = Some(true);
            }
            if rough {
                microfacets(cx, &p, &mut m, false)?;
                silent = &["sample_visible"];
            }
            m.two_sided = Some(false);
        }
        "principled" | "principledthin" => {
            principled(cx, &p, &mut m)?;
            silent = SAMPLING_RATES;
        }
        "twosided" => {
            let inner = p.take("bsdf");
            match inner[..] {
                [one] => {
                    m = describe(cx, one.el, depth + 1)?;
                    if matches!(
                        m.kind(),
                        MaterialKind::Dielectric
                            | MaterialKind::RoughDielectric
                            | MaterialKind::ThinDielectric
                    ) {
                        return Err(one.at.error(
                            "a twosided bsdf cannot hold a dielectric (it has two sides already)",
                        ));
                    }
                    m.two_sided = Some(true);
                }
                [front, back] => {
                    m = describe(cx, front.el, depth + 1)?;
                    let back = material_at(cx, back.el, depth + 1)?;
                    m.back = Some(spanned(back));
                    m.two_sided = Some(true);
                }
                [] => {
                    return Err(el
                        .loc
                        .error("a twosided bsdf needs one or two bsdfs inside"));
                }
                _ => {
                    return Err(inner[2]
                        .at
                        .error("a twosided bsdf holds one or two bsdfs; this is a third"));
                }
            }
        }
        "blendbsdf" => {
            let inner = p.take("bsdf");
            let [a, b] = inner[..] else {
                return Err(el.loc.error(format!(
                    "a blendbsdf blends two bsdfs; it holds {}",
                    inner.len()
                )));
            };
            m.kind = kind(MaterialKind::Blend);
            m.weight = Some(spanned(param_or(cx, &p, "weight", 0.5)?));
            let first = material_at(cx, a.el, depth + 1)?;
            let second = material_at(cx, b.el, depth + 1)?;
            let sided = [&first, &second].map(|n| {
                cx.materials
                    .list
                    .iter()
                    .find(|d| d.name.get_ref() == n)
                    .and_then(|d| d.two_sided)
            });
            // Two-sidedness is the whole material's in lucent: both parts', or one-sided.
            m.two_sided = match sided {
                [Some(true), Some(true)] => Some(true),
                [Some(true), Some(false)] | [Some(false), Some(true)] => {
                    p.warn(
                        &el.loc,
                        "a blendbsdf of a two-sided and a one-sided bsdf is read as one-sided",
                    );
                    Some(false)
                }
                [None, None] => None,
                _ => Some(false),
            };
            m.materials = Some(spanned(vec![first, second]));
        }
        "mask" => {
            let inner = one_bsdf(&p, el)?;
            let opacity = param_or(cx, &p, "opacity", 0.5)?;
            m = describe(cx, inner, depth + 1)?;
            if m.opacity.is_some() {
                return Err(el.loc.error("a mask inside a mask is not read by lucent"));
            }
            m.opacity = Some(spanned(opacity));
        }
        "bumpmap" => {
            let textures = p.take("texture");
            let [height] = textures[..] else {
                return Err(el.loc.error("a bumpmap needs one texture inside"));
            };
            let height = super::texture::texture(cx, height.el)?;
            let scale = p.float_or("scale", 1.0)?;
            let inner = one_bsdf(&p, el)?;
            m = describe(cx, inner, depth + 1)?;
            if m.bump_map.is_some() || m.normal_map.is_some() {
                return Err(el
                    .loc
                    .error("a bumpmap around a bump or normal map is not read by lucent"));
            }
            m.bump_map = Some(spanned(height));
            if scale != 1.0 {
                m.bump_scale = finite(scale);
            }
        }
        "normalmap" => {
            let Some(normals) = param(cx, &p, "normalmap")? else {
                return Err(el.loc.error("a normalmap needs its `normalmap` texture"));
            };
            let inner = one_bsdf(&p, el)?;
            m = describe(cx, inner, depth + 1)?;
            if m.bump_map.is_some() || m.normal_map.is_some() {
                return Err(el
                    .loc
                    .error("a normalmap around a bump or normal map is not read by lucent"));
            }
            m.normal_map = Some(spanned(normals));
        }
        other => return Err(super::unknown_type(el, other)),
    }
    p.finish(&mut cx.warnings, silent);
    Ok(m)
}

/// The principled BSDFs' lobe-sampling weights, which change noise and not the image.
const SAMPLING_RATES: &[&str] = &[
    "diffuse_reflectance_sampling_rate",
    "specular_reflectance_sampling_rate",
    "spec_trans_sampling_rate",
    "diff_trans_sampling_rate",
    "clearcoat_sampling_rate",
    "main_specular_sampling_rate",
];

/// Mitsuba's `principled` or `principledthin`: every parameter a texture but the index
/// (`eta`, or `principled`'s `specular`).
fn principled<'a>(
    cx: &mut Convert<'a>,
    p: &Plugin<'a>,
    m: &mut MaterialDesc,
) -> Result<(), LoadError> {
    let thin = p.kind == "principledthin";
    m.kind = Some(spanned(if thin {
        MaterialKind::PrincipledThin
    } else {
        MaterialKind::Principled
    }));
    let mut unit = |name: &str| -> Result<Option<Spanned<TextureDesc>>, LoadError> {
        Ok(param(cx, p, name)?.map(spanned))
    };
    m.roughness = unit("roughness")?;
    m.anisotropic = unit("anisotropic")?;
    m.spec_trans = unit("spec_trans")?;
    m.spec_tint = unit("spec_tint")?;
    m.sheen = unit("sheen")?;
    m.sheen_tint = unit("sheen_tint")?;
    m.flatness = unit("flatness")?;
    if thin {
        m.diff_trans = unit("diff_trans")?;
    } else {
        m.metallic = unit("metallic")?;
        m.clearcoat = unit("clearcoat")?;
        m.clearcoat_gloss = unit("clearcoat_gloss")?;
    }
    m.base_color = param(cx, p, "base_color")?;
    let eta = p.float("eta")?;
    let specular = if thin { None } else { p.float("specular")? };
    match (eta, specular) {
        (Some(_), Some(_)) => {
            return Err(p
                .el
                .loc
                .error("give a principled bsdf either `eta` or `specular`, not both"));
        }
        (Some(eta), None) => m.ior = finite(eta),
        (None, Some(s)) => m.specular = Some(TextureDesc::gray(s as f32)),
        (None, None) => {}
    }
    // The BSDF tells its sides apart itself (from inside, only the dielectric's reflection).
    if !thin {
        m.two_sided = Some(false);
    }
    Ok(())
}

/// A conductor's `material` (default `none`: Mitsuba's perfect mirror) or `eta` and `k`.
fn conductor<'a>(
    cx: &mut Convert<'a>,
    p: &Plugin<'a>,
    m: &mut MaterialDesc,
) -> Result<(), LoadError> {
    let eta = param(cx, p, "eta")?;
    let k = param(cx, p, "k")?;
    match p.string("material")? {
        None | Some(("none", _)) if eta.is_none() && k.is_none() => {
            // Mitsuba's "none" is η = 0, k = 1: a Fresnel reflectance of 1 at every angle.
            m.eta = Some(TextureDesc::gray(0.0));
            m.k = Some(TextureDesc::gray(1.0));
        }
        None => {
            m.eta = Some(eta.unwrap_or(TextureDesc::gray(0.0)));
            m.k = Some(k.unwrap_or(TextureDesc::gray(1.0)));
        }
        Some((name, loc)) => {
            if eta.is_some() || k.is_some() {
                return Err(loc.error("give either `material` or `eta` and `k`, not both"));
            }
            if name == "none" {
                m.eta = Some(TextureDesc::gray(0.0));
                m.k = Some(TextureDesc::gray(1.0));
            } else if lucent::material::metals::metal(name).is_some() {
                m.metal = Some(spanned(name.to_string()));
            } else {
                return Err(loc.error(format!(
                    "conductor material `{name}` is not one Mitsuba knows; give `eta` and `k` instead"
                )));
            }
        }
    }
    Ok(())
}

/// A rough BSDF's microfacets: `distribution` (default Beckmann, as Mitsuba's), and `alpha`
/// (default 0.1) or `alpha_u` and `alpha_v` — textures where `textured` (rough conductors and
/// dielectrics; a rough plastic's roughness is one number). Constant values are clamped to
/// `[1e-4, 1]`, Mitsuba's floor and lucent's roughest.
fn microfacets<'a>(
    cx: &mut Convert<'a>,
    p: &Plugin<'a>,
    m: &mut MaterialDesc,
    textured: bool,
) -> Result<(), LoadError> {
    let distribution = match p.string("distribution")? {
        None => "beckmann".to_string(),
        Some((d, loc)) => {
            let d = d.to_lowercase();
            if d != "ggx" && d != "beckmann" {
                return Err(loc.error(format!(
                    "unknown microfacet distribution `{d}` (Mitsuba's are beckmann and ggx)"
                )));
            }
            d
        }
    };
    m.distribution = Some(spanned(distribution));
    let mut alpha = |name: &str| -> Result<Option<TextureDesc>, LoadError> {
        let v = if textured {
            param(cx, p, name)?
        } else {
            p.float(name)?.map(|a| TextureDesc::gray(a as f32))
        };
        Ok(v.map(|t| match t {
            TextureDesc::Solid(c) => {
                if c.r > 1.0 {
                    p.warn(
                        &p.el.loc,
                        format!(
                            "the {}'s {name} {} is read as 1, lucent's roughest",
                            p.what(),
                            c.r
                        ),
                    );
                }
                TextureDesc::Solid(c.clamp(1e-4, 1.0))
            }
            t => t,
        }))
    };
    let a = alpha("alpha")?;
    let u = alpha("alpha_u")?;
    let v = alpha("alpha_v")?;
    match (a, u, v) {
        (Some(a), None, None) => m.roughness = Some(spanned(a)),
        (None, Some(u), Some(v)) if u == v => m.roughness = Some(spanned(u)),
        (None, Some(u), Some(v)) => {
            if !textured {
                return Err(p.el.loc.error(
                    "a roughplastic's roughness is isotropic (Mitsuba refuses alpha_u ≠ alpha_v too)",
                ));
            }
            m.roughness_u = Some(spanned(u));
            m.roughness_v = Some(spanned(v));
        }
        (None, None, None) => m.roughness = Some(spanned(TextureDesc::gray(0.1))),
        (Some(_), _, _) => {
            return Err(p
                .el
                .loc
                .error("give either `alpha` or `alpha_u` and `alpha_v`, not both"));
        }
        _ => {
            return Err(p
                .el
                .loc
                .error("anisotropic roughness needs both `alpha_u` and `alpha_v`"));
        }
    }
    Ok(())
}
