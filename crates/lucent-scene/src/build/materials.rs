//! From `[[material]]` descriptions to the renderer's materials: the classic coefficients as
//! given (`whitted`), or a physically based surface whose nearest classic coefficients the
//! renderer derives (`lucent::material`, the table in `docs/scene-format.md`). Materials may
//! refer to others (`blend`'s `materials`, `back`): their surfaces are built first, once.

use super::Context;
use super::material_keys::check_keys;
use super::textures::Slot;
use crate::desc::{Color, Finite, MaterialDesc, MaterialKind, TextureDesc};
use crate::error::LoadError;
use lucent::Rgb;
use lucent::bsdf::Principled;
use lucent::bsdf::fresnel::MAX_CONDUCTOR_INDEX;
use lucent::bsdf::{Distribution, Microfacet, RoughCoat};
use lucent::material::{
    Approximation, GltfMaps, Material, PrincipledMaps, PrincipledThinMaps, Roughness, Surface,
    metals,
};
use lucent::texture::Texture;
use std::collections::HashMap;
use std::ops::Range;
use std::sync::Arc;
use toml::Spanned;

/// Deepest chain of materials referring to others (`blend` of `blend` …).
const MAX_NESTING: usize = 16;

/// Every material's description by name, and the surfaces built so far.
pub struct Materials<'d> {
    by_name: HashMap<&'d str, &'d Spanned<MaterialDesc>>,
    surfaces: HashMap<&'d str, Surface>,
}

impl<'d> Materials<'d> {
    /// The table of `descs` (names already checked unique).
    pub fn new(descs: &'d [Spanned<MaterialDesc>]) -> Self {
        Self {
            by_name: descs
                .iter()
                .map(|m| (m.get_ref().name.get_ref().as_str(), m))
                .collect(),
            surfaces: HashMap::new(),
        }
    }

    /// The renderer's material for `m`, and what the Whitted integrator approximates of it.
    pub fn material(
        &mut self,
        m: &'d Spanned<MaterialDesc>,
        ctx: &mut Context,
    ) -> Result<(Material, Option<Approximation>), LoadError> {
        let d = m.get_ref();
        let table = m.span();
        let surface = self.surface_of(m, ctx, 0)?;
        let (mut material, approx) = if d.kind() == MaterialKind::Whitted {
            let mut c = classic(m, ctx)?;
            // The classic integrators shade with the surface's own normal.
            let approx = surface
                .perturbs_normal()
                .then_some(Approximation::NormalMap);
            c.surface = surface;
            (c, approx)
        } else {
            Material::physically_based(surface, ctx.builder.images())
        };
        match &d.emission {
            None => {}
            Some(TextureDesc::Solid(c)) => material.ke = *c,
            Some(t) => {
                material.ke = Rgb::WHITE;
                material.emission_map = Some(ctx.texture(t, table.clone(), Slot::Color)?);
            }
        }
        if let Some(o) = &d.opacity {
            let t = ctx.texture(o.get_ref(), o.span(), Slot::Data)?;
            // Fully opaque everywhere is no cut-out at all.
            if t.constant().is_none_or(|c| c.r < 1.0) {
                material.opacity = Some(t);
            }
        }
        if d.kind() == MaterialKind::Null {
            material.opacity = Some(Texture::from(0.0));
        }
        material.two_sided = d.two_sided.unwrap_or(true);
        material.vertex_colors = d.vertex_colors.unwrap_or(true);
        material.cull_back = d.cull_back.unwrap_or(false);
        material.emits_back = d.emits_back.unwrap_or(false);
        // Area lights emit from their fronts: a two-sided emission is found only by the rays
        // that hit it, as a textured one is.
        if material.emits_back && material.emission_map.is_none() {
            material.emission_map = Some(Texture::from(1.0));
        }
        Ok((material, approx))
    }

    /// The surface of material `m`, built on first use; `depth` counts the references followed.
    fn surface_of(
        &mut self,
        m: &'d Spanned<MaterialDesc>,
        ctx: &mut Context,
        depth: usize,
    ) -> Result<Surface, LoadError> {
        let d = m.get_ref();
        let name = d.name.get_ref().as_str();
        if let Some(s) = self.surfaces.get(name) {
            return Ok(s.clone());
        }
        if depth > MAX_NESTING {
            return Err(ctx.source.error(
                d.name.span(),
                format!(
                    "materials refer to each other more than {MAX_NESTING} deep (does `{name}` refer to itself?)"
                ),
            ));
        }
        check_keys(m, ctx)?;
        let mut surface = match d.kind() {
            MaterialKind::Blend => {
                let Some(pair) = &d.materials else {
                    return Err(ctx
                        .source
                        .error(m.span(), "a blend needs `materials = [\"a\", \"b\"]`"));
                };
                let names = pair.get_ref();
                if names.len() != 2 {
                    return Err(ctx.source.error(
                        pair.span(),
                        format!("a blend takes two materials, got {}", names.len()),
                    ));
                }
                let first = self.referenced(&names[0], pair.span(), ctx, depth)?;
                let second = self.referenced(&names[1], pair.span(), ctx, depth)?;
                let weight = match &d.weight {
                    Some(w) => ctx.texture(w.get_ref(), w.span(), Slot::Data)?,
                    None => Texture::from(0.5),
                };
                Surface::Blend {
                    weight,
                    first: Box::new(first),
                    second: Box::new(second),
                }
            }
            _ => leaf(m, ctx)?,
        };
        if let Some(b) = &d.bump_map {
            surface = Surface::BumpMap {
                height: ctx.texture(b.get_ref(), b.span(), Slot::Data)?,
                scale: d.bump_scale.as_ref().map_or(1.0, |s| s.get_ref().0),
                inner: Box::new(surface),
            };
        }
        if let Some(n) = &d.normal_map {
            surface = Surface::NormalMap {
                normals: ctx.texture(n.get_ref(), n.span(), Slot::Data)?,
                strength: d.normal_scale.as_ref().map_or(1.0, |s| s.get_ref().0),
                inner: Box::new(surface),
            };
        }
        if let Some(back) = &d.back {
            if d.two_sided == Some(false) {
                return Err(ctx.source.error(
                    back.span(),
                    "`back` gives the back side a surface; it cannot go with `two_sided = false`",
                ));
            }
            let back = self.referenced(back.get_ref(), back.span(), ctx, depth)?;
            surface = Surface::TwoSided {
                front: Box::new(surface),
                back: Box::new(back),
            };
        }
        self.surfaces.insert(name, surface.clone());
        Ok(surface)
    }

    /// The surface of the material named `name`, referred to at `span`.
    fn referenced(
        &mut self,
        name: &str,
        span: Range<usize>,
        ctx: &mut Context,
        depth: usize,
    ) -> Result<Surface, LoadError> {
        let Some(&m) = self.by_name.get(name) else {
            return Err(ctx.source.error(span, format!("unknown material `{name}`")));
        };
        // A whitted material's surface reads the coefficients of the material it is shaded
        // as: inside another, they would be the other's.
        if m.get_ref().kind() == MaterialKind::Whitted {
            return Err(ctx.source.error(
                span,
                format!(
                    "`{name}` is a `whitted` material: `back` and a blend's `materials` name physically based ones"
                ),
            ));
        }
        self.surface_of(m, ctx, depth + 1)
    }
}

/// An index of refraction: bounded so that relative indices, their squares and the refraction
/// formula stay far from overflow (every real material lies well inside).
fn index_of_refraction(
    ctx: &Context,
    v: &Option<Spanned<Finite>>,
    what: &str,
    default: f32,
) -> Result<f32, LoadError> {
    const RANGE: std::ops::RangeInclusive<f32> = 1e-3..=1e3;
    match v {
        Some(s) if s.get_ref().0 <= 0.0 => Err(ctx
            .source
            .error(s.span(), format!("{what} must be positive"))),
        Some(s) if !RANGE.contains(&s.get_ref().0) => Err(ctx.source.error(
            s.span(),
            format!("{what} must be between 0.001 and 1000 (an index of refraction)"),
        )),
        Some(s) => Ok(s.get_ref().0),
        None => Ok(default),
    }
}

/// `ior / ext_ior` (defaults 1.5 and 1).
fn relative_ior(d: &MaterialDesc, ctx: &Context) -> Result<f32, LoadError> {
    Ok(index_of_refraction(ctx, &d.ior, "ior", 1.5)?
        / index_of_refraction(ctx, &d.ext_ior, "ext_ior", 1.0)?)
}

/// The classic material of a `whitted` description (its surface set by the caller).
fn classic(m: &Spanned<MaterialDesc>, ctx: &mut Context) -> Result<Material, LoadError> {
    let d = m.get_ref();
    if let Some(s) = &d.shininess
        && s.get_ref().0 < 0.0
    {
        return Err(ctx.source.error(s.span(), "shininess must not be negative"));
    }
    let c = |o: Option<Color>| o.map_or(Rgb::BLACK, |c| c.0);
    let kd = match &d.kd {
        Some(t) => ctx.texture(t, m.span(), Slot::Color)?,
        None => Texture::Solid(Rgb::BLACK),
    };
    let blinn = match &d.highlight {
        None => false,
        Some(h) => match h.get_ref().as_str() {
            "phong" => false,
            "blinn" => true,
            other => {
                return Err(ctx.source.error(
                    h.span(),
                    format!("unknown highlight `{other}` (phong or blinn)"),
                ));
            }
        },
    };
    let brilliance = d.brilliance.as_ref().map_or(Ok(1.0), |b| {
        let v = b.get_ref().0;
        if v > 0.0 && v <= 1000.0 {
            Ok(v)
        } else {
            Err(ctx
                .source
                .error(b.span(), "brilliance must be in (0, 1000]"))
        }
    })?;
    let ka_map = match &d.ka_map {
        Some(t) => Some(ctx.texture(t, m.span(), Slot::Color)?),
        None => None,
    };
    Ok(Material {
        ka: c(d.ka),
        ka_map,
        kd,
        ks: c(d.ks),
        shininess: d.shininess.as_ref().map_or(0.0, |s| s.get_ref().0),
        blinn,
        brilliance,
        kr: c(d.kr),
        kt: c(d.kt),
        ior: index_of_refraction(ctx, &d.ior, "ior", 1.0)?,
        bump: d.bump.as_ref().map(|b| b.0.clone()),
        ..Material::default()
    })
}

/// The microfacet distribution named in `d` (default GGX).
fn distribution(d: &MaterialDesc, ctx: &Context) -> Result<Distribution, LoadError> {
    match &d.distribution {
        None => Ok(Distribution::Ggx),
        Some(s) => match s.get_ref().to_lowercase().as_str() {
            "ggx" => Ok(Distribution::Ggx),
            "beckmann" => Ok(Distribution::Beckmann),
            other => Err(ctx.source.error(
                s.span(),
                format!("unknown microfacet distribution `{other}` (known: ggx, beckmann)"),
            )),
        },
    }
}

/// A roughness texture, its constant value checked to lie in (0, 1].
fn alpha(ctx: &mut Context, v: &Spanned<TextureDesc>, what: &str) -> Result<Texture, LoadError> {
    if let TextureDesc::Solid(c) = v.get_ref() {
        let a = c.r;
        if !(a > 0.0 && a <= 1.0) || c.g != c.r || c.b != c.r {
            return Err(ctx
                .source
                .error(v.span(), format!("{what} must be a number in (0, 1]")));
        }
    }
    ctx.texture(v.get_ref(), v.span(), Slot::Data)
}

/// The microfacets of a rough kind: `roughness` (default 0.1), or `roughness_u` and
/// `roughness_v` together.
fn roughness(m: &Spanned<MaterialDesc>, ctx: &mut Context) -> Result<Roughness, LoadError> {
    let d = m.get_ref();
    let distribution = distribution(d, ctx)?;
    match (&d.roughness, &d.roughness_u, &d.roughness_v) {
        (Some(r), None, None) => {
            let t = alpha(ctx, r, "roughness")?;
            Ok(Roughness {
                distribution,
                alpha_u: t.clone(),
                alpha_v: t,
            })
        }
        (None, Some(u), Some(v)) => Ok(Roughness {
            distribution,
            alpha_u: alpha(ctx, u, "roughness_u")?,
            alpha_v: alpha(ctx, v, "roughness_v")?,
        }),
        (None, None, None) => Ok(Roughness::isotropic(distribution, 0.1)),
        (Some(r), _, _) => Err(ctx.source.error(
            r.span(),
            "give either `roughness` or `roughness_u` and `roughness_v`, not both",
        )),
        (None, Some(s), None) | (None, None, Some(s)) => Err(ctx.source.error(
            s.span(),
            "anisotropic roughness needs both `roughness_u` and `roughness_v`",
        )),
    }
}

/// The surface of a physically based leaf kind (or the classic lobes of `whitted`).
fn leaf(m: &Spanned<MaterialDesc>, ctx: &mut Context) -> Result<Surface, LoadError> {
    let d = m.get_ref();
    let table = m.span();
    let kind = d.kind();
    let tex = |ctx: &mut Context, t: &Option<TextureDesc>, default: f32, slot: Slot| match t {
        Some(t) => ctx.texture(t, table.clone(), slot),
        None => Ok(Texture::from(default)),
    };
    Ok(match kind {
        MaterialKind::Whitted => Surface::Classic,
        MaterialKind::Null => Surface::Diffuse {
            reflectance: Texture::from(0.0),
        },
        MaterialKind::Diffuse => Surface::Diffuse {
            reflectance: tex(ctx, &d.reflectance, 0.5, Slot::Color)?,
        },
        MaterialKind::Conductor | MaterialKind::RoughConductor => {
            let specular = tex(ctx, &d.specular, 1.0, Slot::Color)?;
            let (eta, k) = conductor_index(m, ctx)?;
            let roughness = if kind == MaterialKind::RoughConductor {
                Some(roughness(m, ctx)?)
            } else {
                None
            };
            Surface::Conductor {
                eta,
                k,
                specular,
                roughness,
            }
        }
        MaterialKind::Dielectric | MaterialKind::RoughDielectric | MaterialKind::ThinDielectric => {
            let specular = tex(ctx, &d.specular, 1.0, Slot::Color)?;
            let transmittance = tex(ctx, &d.transmittance, 1.0, Slot::Color)?;
            let eta = relative_ior(d, ctx)?;
            match kind {
                MaterialKind::ThinDielectric => Surface::ThinDielectric {
                    eta,
                    specular,
                    transmittance,
                },
                _ => Surface::Dielectric {
                    eta,
                    specular,
                    transmittance,
                    roughness: if kind == MaterialKind::RoughDielectric {
                        Some(roughness(m, ctx)?)
                    } else {
                        None
                    },
                },
            }
        }
        MaterialKind::Plastic | MaterialKind::RoughPlastic => {
            let diffuse = tex(ctx, &d.reflectance, 0.5, Slot::Color)?;
            let specular = tex(ctx, &d.specular, 1.0, Slot::Color)?;
            let eta = relative_ior(d, ctx)?;
            let rough = kind == MaterialKind::RoughPlastic || d.roughness.is_some();
            let coat = if rough {
                Some(plastic_coat(m, eta, ctx)?)
            } else {
                if let Some(s) = &d.distribution {
                    return Err(ctx.source.error(
                        s.span(),
                        "`distribution` needs a rough coat: give `roughness` (or use roughplastic)",
                    ));
                }
                None
            };
            Surface::plastic_with(diffuse, eta, specular, d.nonlinear.unwrap_or(false), coat)
        }
        MaterialKind::Principled => Surface::Principled(Box::new(principled(m, ctx)?)),
        MaterialKind::PrincipledThin => Surface::PrincipledThin(Box::new(principled_thin(m, ctx)?)),
        MaterialKind::Pbr => Surface::Gltf(Box::new(pbr(m, ctx)?)),
        MaterialKind::Blend => unreachable!("blends are built from their materials"),
    })
}

/// A texture in `[0, max]` (its constant value checked), or `default`.
fn bounded(
    ctx: &mut Context,
    v: &Option<Spanned<TextureDesc>>,
    what: &str,
    max: f32,
    default: f32,
) -> Result<Texture, LoadError> {
    let Some(v) = v else {
        return Ok(Texture::from(default));
    };
    if let TextureDesc::Solid(c) = v.get_ref()
        && [c.r, c.g, c.b].iter().any(|x| !(0.0..=max).contains(x))
    {
        return Err(ctx
            .source
            .error(v.span(), format!("{what} must lie in [0, {max}]")));
    }
    ctx.texture(v.get_ref(), v.span(), Slot::Data)
}

/// A colour texture, or a grey `default`.
fn color(
    ctx: &mut Context,
    table: &Range<usize>,
    v: &Option<TextureDesc>,
    default: f32,
) -> Result<Texture, LoadError> {
    match v {
        Some(t) => ctx.texture(t, table.clone(), Slot::Color),
        None => Ok(Texture::from(default)),
    }
}

/// The principled BSDF's index: `ior`, or Burley's mapping of `specular` (a number in
/// `[0, 1]`), or Mitsuba's default (specular 0.5).
fn principled_eta(m: &Spanned<MaterialDesc>, ctx: &Context) -> Result<f32, LoadError> {
    let d = m.get_ref();
    match (&d.ior, &d.specular) {
        (Some(_), Some(_)) => Err(ctx.source.error(
            m.span(),
            "give a principled material either `ior` or `specular`, not both",
        )),
        (Some(_), None) => index_of_refraction(ctx, &d.ior, "ior", 1.5),
        (None, Some(TextureDesc::Solid(c)))
            if c.r == c.g && c.g == c.b && c.r > 0.0 && c.r <= 1.0 =>
        {
            Ok(lucent::bsdf::principled::eta_of_specular(c.r))
        }
        (None, Some(_)) => Err(ctx.source.error(
            m.span(),
            "a principled material's `specular` is one number in (0, 1] (it sets the index)",
        )),
        (None, None) => Ok(Principled::default().eta),
    }
}

/// A `principled` material's parameters (Mitsuba's defaults where absent).
fn principled(m: &Spanned<MaterialDesc>, ctx: &mut Context) -> Result<PrincipledMaps, LoadError> {
    let d = m.get_ref();
    Ok(PrincipledMaps {
        base_color: color(ctx, &m.span(), &d.base_color, 0.5)?,
        roughness: bounded(ctx, &d.roughness, "roughness", 1.0, 0.5)?,
        anisotropic: bounded(ctx, &d.anisotropic, "anisotropic", 1.0, 0.0)?,
        metallic: bounded(ctx, &d.metallic, "metallic", 1.0, 0.0)?,
        spec_trans: bounded(ctx, &d.spec_trans, "spec_trans", 1.0, 0.0)?,
        spec_tint: bounded(ctx, &d.spec_tint, "spec_tint", 1.0, 0.0)?,
        sheen: bounded(ctx, &d.sheen, "sheen", 1.0, 0.0)?,
        sheen_tint: bounded(ctx, &d.sheen_tint, "sheen_tint", 1.0, 0.0)?,
        flatness: bounded(ctx, &d.flatness, "flatness", 1.0, 0.0)?,
        clearcoat: bounded(ctx, &d.clearcoat, "clearcoat", 1.0, 0.0)?,
        clearcoat_gloss: bounded(ctx, &d.clearcoat_gloss, "clearcoat_gloss", 1.0, 0.0)?,
        eta: principled_eta(m, ctx)?,
    })
}

/// A `principledthin` material's parameters (Mitsuba's defaults where absent).
fn principled_thin(
    m: &Spanned<MaterialDesc>,
    ctx: &mut Context,
) -> Result<PrincipledThinMaps, LoadError> {
    let d = m.get_ref();
    Ok(PrincipledThinMaps {
        base_color: color(ctx, &m.span(), &d.base_color, 0.5)?,
        roughness: bounded(ctx, &d.roughness, "roughness", 1.0, 0.5)?,
        anisotropic: bounded(ctx, &d.anisotropic, "anisotropic", 1.0, 0.0)?,
        spec_trans: bounded(ctx, &d.spec_trans, "spec_trans", 1.0, 0.0)?,
        diff_trans: bounded(ctx, &d.diff_trans, "diff_trans", 2.0, 0.0)?,
        spec_tint: bounded(ctx, &d.spec_tint, "spec_tint", 1.0, 0.0)?,
        sheen: bounded(ctx, &d.sheen, "sheen", 1.0, 0.0)?,
        sheen_tint: bounded(ctx, &d.sheen_tint, "sheen_tint", 1.0, 0.0)?,
        flatness: bounded(ctx, &d.flatness, "flatness", 1.0, 0.0)?,
        eta: match &d.ior {
            Some(_) => Texture::from(index_of_refraction(ctx, &d.ior, "ior", 1.5)?),
            None => PrincipledThinMaps::default().eta,
        },
    })
}

/// A `pbr` (glTF metallic-roughness) material's parameters, glTF's defaults where absent.
fn pbr(m: &Spanned<MaterialDesc>, ctx: &mut Context) -> Result<GltfMaps, LoadError> {
    let d = m.get_ref();
    let table = m.span();
    let clearcoat_normals = match &d.clearcoat_normal_map {
        Some(n) => Some((
            ctx.texture(n.get_ref(), n.span(), Slot::Data)?,
            d.clearcoat_normal_scale
                .as_ref()
                .map_or(1.0, |s| s.get_ref().0),
        )),
        None => None,
    };
    let specular = match &d.specular {
        Some(t) => ctx.texture(t, table.clone(), Slot::Data)?,
        None => Texture::from(1.0),
    };
    let sheen_color = color(ctx, &table, &d.sheen_color, 0.0)?;
    let sheen_albedo =
        (sheen_color.constant().is_none_or(|c| !c.is_black())).then(|| ctx.sheen_albedo());
    Ok(GltfMaps {
        base_color: color(ctx, &table, &d.base_color, 1.0)?,
        metallic: bounded(ctx, &d.metallic, "metallic", 1.0, 1.0)?,
        roughness: bounded(ctx, &d.roughness, "roughness", 1.0, 1.0)?,
        ior: index_of_refraction(ctx, &d.ior, "ior", 1.5)?,
        specular,
        specular_color: color(ctx, &table, &d.specular_color, 1.0)?,
        transmission: bounded(ctx, &d.transmission, "transmission", 1.0, 0.0)?,
        volume: d.volume.unwrap_or(false),
        clearcoat: bounded(ctx, &d.clearcoat, "clearcoat", 1.0, 0.0)?,
        clearcoat_roughness: bounded(ctx, &d.clearcoat_roughness, "clearcoat_roughness", 1.0, 0.0)?,
        clearcoat_normals,
        sheen_color,
        sheen_roughness: bounded(ctx, &d.sheen_roughness, "sheen_roughness", 1.0, 0.0)?,
        sheen_albedo,
        anisotropy: bounded(ctx, &d.anisotropy, "anisotropy", 1.0, 0.0)?,
        anisotropy_rotation: d
            .anisotropy_rotation
            .as_ref()
            .map_or(0.0, |r| r.get_ref().0.to_radians()),
        anisotropy_direction: match &d.anisotropy_direction {
            Some(t) => Some(ctx.texture(t.get_ref(), t.span(), Slot::Data)?),
            None => None,
        },
        diffuse_transmission: bounded(
            ctx,
            &d.diffuse_transmission,
            "diffuse_transmission",
            1.0,
            0.0,
        )?,
        diffuse_transmission_color: color(ctx, &table, &d.diffuse_transmission_color, 1.0)?,
        iridescence: bounded(ctx, &d.iridescence, "iridescence", 1.0, 0.0)?,
        iridescence_ior: index_of_refraction(ctx, &d.iridescence_ior, "iridescence_ior", 1.3)?,
        // Nanometres; the renderer keeps whole ones in 16 bits (`GltfPbr::film_thickness`).
        iridescence_thickness: bounded(
            ctx,
            &d.iridescence_thickness,
            "iridescence_thickness",
            f32::from(u16::MAX),
            400.0,
        )?,
    })
}

/// A rough plastic's coat: its roughness is one number (the coat's tables are integrated for
/// it), shared between materials of the same distribution, roughness and index.
fn plastic_coat(
    m: &Spanned<MaterialDesc>,
    eta: f32,
    ctx: &mut Context,
) -> Result<Arc<RoughCoat>, LoadError> {
    let d = m.get_ref();
    let distribution = distribution(d, ctx)?;
    let alpha = match &d.roughness {
        None => 0.1,
        Some(r) => match r.get_ref() {
            TextureDesc::Solid(c) if c.r > 0.0 && c.r <= 1.0 && c.r == c.g && c.g == c.b => c.r,
            TextureDesc::Solid(_) => {
                return Err(ctx
                    .source
                    .error(r.span(), "roughness must be a number in (0, 1]"));
            }
            _ => {
                return Err(ctx.source.error(
                    r.span(),
                    "a plastic's roughness is one number (its coat's transmittance is tabulated for it), not a texture",
                ));
            }
        },
    };
    let key = (distribution as u8, alpha.to_bits(), eta.to_bits());
    Ok(ctx
        .coats
        .entry(key)
        .or_insert_with(|| {
            Arc::new(RoughCoat::new(
                Microfacet::isotropic(distribution, alpha),
                eta,
            ))
        })
        .clone())
}

/// A conductor's `(eta, k)`: `metal` by name, `eta` (and `k`), or a perfect mirror.
fn conductor_index(
    m: &Spanned<MaterialDesc>,
    ctx: &mut Context,
) -> Result<(Texture, Texture), LoadError> {
    let d = m.get_ref();
    let table = m.span();
    match (&d.metal, &d.eta, &d.k) {
        (Some(name), None, None) => {
            let Some((eta, k)) = metals::metal(name.get_ref()) else {
                let known: Vec<_> = metals::METALS.iter().map(|m| m.0).collect();
                return Err(ctx.source.error(
                    name.span(),
                    format!(
                        "unknown metal `{}` (known: {})",
                        name.get_ref(),
                        known.join(", ")
                    ),
                ));
            };
            Ok((Texture::Solid(Rgb::from(eta)), Texture::Solid(Rgb::from(k))))
        }
        (None, Some(eta), k) => {
            conductor_bound(ctx, &table, eta, "eta", "a conductor's index of refraction")?;
            if let Some(k) = k {
                conductor_bound(ctx, &table, k, "k", "an extinction coefficient")?;
            }
            Ok((
                ctx.texture(eta, table.clone(), Slot::Data)?,
                match k {
                    Some(k) => ctx.texture(k, table, Slot::Data)?,
                    None => Texture::Solid(Rgb::BLACK),
                },
            ))
        }
        // A perfect mirror: an index of 0 with a large extinction reflects everything at every
        // angle (Mitsuba's `none` is η = 0, k = 1, which its reader says explicitly).
        (None, None, None) => Ok((Texture::Solid(Rgb::BLACK), Texture::Solid(Rgb::gray(1e4)))),
        (None, None, Some(_)) => Err(ctx
            .source
            .error(table, "a conductor's `k` needs its `eta` (or give `metal`)")),
        _ => Err(ctx.source.error(
            table,
            "give a conductor either `metal` or `eta` (and `k`), not both",
        )),
    }
}

/// Refuses a constant `eta` or `k` (`what`, `meaning`) with a channel above
/// [`MAX_CONDUCTOR_INDEX`]; a texture's values are clamped to it where they are used.
fn conductor_bound(
    ctx: &Context,
    table: &Range<usize>,
    v: &TextureDesc,
    what: &str,
    meaning: &str,
) -> Result<(), LoadError> {
    match v {
        TextureDesc::Solid(c) if [c.r, c.g, c.b].iter().any(|x| *x > MAX_CONDUCTOR_INDEX) => {
            Err(ctx.source.error(
                table.clone(),
                format!("{what} must be between 0 and {MAX_CONDUCTOR_INDEX} ({meaning})"),
            ))
        }
        _ => Ok(()),
    }
}
