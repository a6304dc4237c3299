//! From a `[[material]]` description to the renderer's material: the classic coefficients as
//! given (`whitted`), or the nearest classic equivalent of a physically based kind (the table
//! is in `docs/scene-format.md`).

use super::{Context, refuse_keys, span};
use crate::desc::{Color, DiffuseDesc, MaterialDesc, MaterialKind};
use crate::error::LoadError;
use lucent::Rgb;
use lucent::material::{Material, Surface};
use lucent::texture::Texture;
use toml::Spanned;

/// Named conductors: per-channel (R, G, B) index of refraction η and extinction k, sampled at
/// about 650, 550 and 450 nm from measured spectra (as the RGB renderers pbrt and Mitsuba use).
const METALS: [(&str, [f32; 3], [f32; 3]); 4] = [
    ("Au", [0.143, 0.374, 1.442], [3.983, 2.385, 1.603]),
    ("Ag", [0.155, 0.117, 0.138], [4.828, 3.122, 2.147]),
    ("Cu", [0.200, 0.924, 1.102], [3.912, 2.452, 2.142]),
    ("Al", [1.657, 0.880, 0.521], [9.224, 6.270, 4.837]),
];

/// Why a material is rendered other than as written, for one warning line per reason.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Approximation {
    /// A rough surface is drawn with a Phong highlight (or as smooth glass).
    Rough,
}

/// Normal-incidence Fresnel reflectance of a dielectric interface with relative index `eta`.
fn dielectric_f0(eta: f32) -> f32 {
    let r = (eta - 1.0) / (eta + 1.0);
    r * r
}

/// Normal-incidence Fresnel reflectance of a conductor, per channel.
fn conductor_f0(eta: Rgb, k: Rgb) -> Rgb {
    let f = |n: f32, k: f32| ((n - 1.0) * (n - 1.0) + k * k) / ((n + 1.0) * (n + 1.0) + k * k);
    Rgb::new(f(eta.r, k.r), f(eta.g, k.g), f(eta.b, k.b))
}

/// The Phong exponent whose lobe matches GGX roughness `alpha` (Walter et al. 2007).
fn phong_exponent(alpha: f32) -> f32 {
    (2.0 / (alpha * alpha) - 2.0).max(1.0)
}

/// The renderer's material for `m`, and what had to be approximated.
pub fn whitted_material(
    m: &Spanned<MaterialDesc>,
    ctx: &mut Context,
) -> Result<(Material, Option<Approximation>), LoadError> {
    let table = m.span();
    let d = m.get_ref();
    let kind = d.kind();
    let keys = [
        ("ka", d.ka.map(|_| table.clone())),
        ("kd", d.kd.as_ref().map(|_| table.clone())),
        ("ks", d.ks.map(|_| table.clone())),
        ("shininess", span(&d.shininess)),
        ("kr", d.kr.map(|_| table.clone())),
        ("kt", d.kt.map(|_| table.clone())),
        ("ior", span(&d.ior)),
        ("ext_ior", span(&d.ext_ior)),
        ("reflectance", d.reflectance.as_ref().map(|_| table.clone())),
        ("specular", d.specular.map(|_| table.clone())),
        ("transmittance", d.transmittance.map(|_| table.clone())),
        ("eta", d.eta.map(|_| table.clone())),
        ("k", d.k.map(|_| table.clone())),
        ("metal", span(&d.metal)),
        ("roughness", span(&d.roughness)),
    ];
    let takes: &[&str] = match kind {
        MaterialKind::Whitted => &["ka", "kd", "ks", "shininess", "kr", "kt", "ior"],
        MaterialKind::Diffuse => &["reflectance"],
        MaterialKind::Conductor => &["specular", "eta", "k", "metal"],
        MaterialKind::RoughConductor => &["specular", "eta", "k", "metal", "roughness"],
        MaterialKind::Dielectric => &["ior", "ext_ior", "specular", "transmittance"],
        MaterialKind::RoughDielectric => {
            &["ior", "ext_ior", "specular", "transmittance", "roughness"]
        }
        MaterialKind::Plastic => &["reflectance", "ior", "ext_ior", "specular", "roughness"],
    };
    let others: Vec<_> = keys
        .into_iter()
        .filter(|(k, _)| !takes.contains(k))
        .collect();
    refuse_keys(ctx.source, &format!("{} material", kind.name()), &others)?;

    let positive = |v: &Option<Spanned<crate::desc::Finite>>, what: &str, default: f32| match v {
        Some(s) if s.get_ref().0 <= 0.0 => Err(ctx
            .source
            .error(s.span(), format!("{what} must be positive"))),
        Some(s) => Ok(s.get_ref().0),
        None => Ok(default),
    };
    let ior = positive(
        &d.ior,
        "ior",
        if kind == MaterialKind::Whitted {
            1.0
        } else {
            1.5
        },
    )?;
    let ext_ior = positive(&d.ext_ior, "ext_ior", 1.0)?;
    if let Some(s) = &d.shininess
        && s.get_ref().0 < 0.0
    {
        return Err(ctx.source.error(s.span(), "shininess must not be negative"));
    }
    let alpha = match &d.roughness {
        Some(r) if !(r.get_ref().0 > 0.0 && r.get_ref().0 <= 1.0) => {
            return Err(ctx.source.error(r.span(), "roughness must be in (0, 1]"));
        }
        Some(r) => r.get_ref().0,
        None => 0.1,
    };
    let c = |o: Option<Color>, default: Rgb| o.map_or(default, |c| c.0);
    let specular = c(d.specular, Rgb::WHITE);

    let mut material = Material {
        ke: c(d.emission, Rgb::BLACK),
        two_sided: d.two_sided.unwrap_or(true),
        ..Material::default()
    };
    // GGX roughness of the rough kinds (0: smooth) for the path tracer.
    let rough = |k: MaterialKind| {
        if matches!(
            k,
            MaterialKind::RoughConductor | MaterialKind::RoughDielectric
        ) || (k == MaterialKind::Plastic && d.roughness.is_some())
        {
            alpha
        } else {
            0.0
        }
    };
    let mut approx = None;
    match kind {
        MaterialKind::Whitted => {
            material.ka = c(d.ka, Rgb::BLACK);
            material.kd =
                texture(d.kd.as_ref(), table.clone(), ctx)?.unwrap_or(Texture::Solid(Rgb::BLACK));
            material.ks = c(d.ks, Rgb::BLACK);
            material.shininess = d.shininess.as_ref().map_or(0.0, |s| s.get_ref().0);
            material.kr = c(d.kr, Rgb::BLACK);
            material.kt = c(d.kt, Rgb::BLACK);
            material.ior = ior;
        }
        MaterialKind::Diffuse | MaterialKind::Plastic => {
            let kd = texture(d.reflectance.as_ref(), table.clone(), ctx)?
                .unwrap_or(Texture::Solid(Rgb::gray(0.5)));
            material.ka = mean_colour(&kd, ctx);
            material.kd = kd;
            material.surface = if kind == MaterialKind::Plastic {
                Surface::Plastic {
                    eta: ior / ext_ior,
                    specular,
                    alpha: rough(kind),
                }
            } else {
                Surface::Diffuse
            };
            if kind == MaterialKind::Plastic {
                let f0 = dielectric_f0(ior / ext_ior);
                if d.roughness.is_some() {
                    material.shininess = phong_exponent(alpha);
                    material.ks = specular * (f0 * (material.shininess + 2.0) / 2.0).min(1.0);
                    approx = Some(Approximation::Rough);
                } else {
                    material.kr = specular * f0;
                }
            }
        }
        MaterialKind::Conductor | MaterialKind::RoughConductor => {
            let (eta, k) = match (&d.metal, d.eta, d.k) {
                (Some(name), None, None) => {
                    let Some((_, eta, k)) = METALS
                        .iter()
                        .find(|(n, _, _)| n.eq_ignore_ascii_case(name.get_ref()))
                    else {
                        let known: Vec<_> = METALS.iter().map(|m| m.0).collect();
                        return Err(ctx.source.error(
                            name.span(),
                            format!(
                                "unknown metal `{}` (known: {})",
                                name.get_ref(),
                                known.join(", ")
                            ),
                        ));
                    };
                    (Rgb::from(*eta), Rgb::from(*k))
                }
                (None, Some(eta), k) => (eta.0, k.map_or(Rgb::BLACK, |k| k.0)),
                // A perfect mirror: Mitsuba's default is aluminium, but a conductor without
                // its constants has always been white here; an index of 0 with no extinction
                // reflects everything at every angle.
                (None, None, None) => (Rgb::BLACK, Rgb::gray(1e4)),
                (None, None, Some(_)) => {
                    return Err(ctx
                        .source
                        .error(table, "a conductor's `k` needs its `eta` (or give `metal`)"));
                }
                _ => {
                    return Err(ctx.source.error(
                        table,
                        "give a conductor either `metal` or `eta` (and `k`), not both",
                    ));
                }
            };
            let f0 = conductor_f0(eta, k);
            material.surface = Surface::Conductor {
                eta,
                k,
                specular,
                alpha: rough(kind),
            };
            if kind == MaterialKind::RoughConductor {
                material.shininess = phong_exponent(alpha);
                material.ks = specular * f0;
                approx = Some(Approximation::Rough);
            } else {
                material.kr = specular * f0;
            }
        }
        MaterialKind::Dielectric | MaterialKind::RoughDielectric => {
            let f0 = dielectric_f0(ior / ext_ior);
            material.ior = ior / ext_ior;
            material.surface = Surface::Dielectric {
                eta: ior / ext_ior,
                specular,
                transmittance: c(d.transmittance, Rgb::WHITE),
                alpha: rough(kind),
            };
            material.kr = specular * f0;
            material.kt = c(d.transmittance, Rgb::WHITE) * (1.0 - f0);
            if kind == MaterialKind::RoughDielectric {
                approx = Some(Approximation::Rough);
            }
        }
    }
    Ok((material, approx))
}

/// The texture of a colour description, loading image files through `ctx`.
fn texture(
    d: Option<&DiffuseDesc>,
    table: std::ops::Range<usize>,
    ctx: &mut Context,
) -> Result<Option<Texture>, LoadError> {
    Ok(match d {
        None => None,
        Some(DiffuseDesc::Solid(c)) => Some(Texture::Solid(*c)),
        Some(DiffuseDesc::Checker(c)) => Some(Texture::Checker(*c)),
        Some(DiffuseDesc::Image(file)) => {
            Some(Texture::Image(ctx.image(file, table, Rgb::WHITE)?))
        }
    })
}

/// The average colour of a texture: the ambient coefficient of imported materials.
fn mean_colour(t: &Texture, ctx: &Context) -> Rgb {
    match t {
        Texture::Solid(c) => *c,
        Texture::Checker(c) => (c.even + c.odd) * 0.5,
        Texture::Image(i) => ctx.image_mean(*i),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fresnel_at_normal_incidence() {
        assert!((dielectric_f0(1.5) - 0.04).abs() < 1e-6);
        let gold = conductor_f0(Rgb::from(METALS[0].1), Rgb::from(METALS[0].2));
        // Gold reflects red most and blue least.
        assert!(gold.r > 0.9 && gold.g > 0.6 && gold.b < 0.5, "{gold:?}");
        assert_eq!(phong_exponent(1.0), 1.0);
        assert!((phong_exponent(0.1) - 198.0).abs() < 1e-3);
    }
}
