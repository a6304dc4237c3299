//! Tests that hold every variant to the contract in `bsdf/mod.rs`: χ² of every sampling
//! routine against its pdf, sample weights against eval/pdf, energy, reciprocity, and finite
//! values on degenerate input. Each variant's analytic values are tested in its own file.

use glam::{Vec2, Vec3};

use super::chi2::{self, Directions, Rng};
use super::microfacet::{Distribution, Microfacet};
use super::{Bsdf, BsdfSample, GltfPbr, Principled, PrincipledThin, RoughCoat, Sheen, Transport};
use crate::Rgb;

const ALPHAS: [f32; 4] = [0.05, 0.2, 0.6, 1.0];
const THETAS: [f32; 4] = [0.0, 30.0, 60.0, 85.0];
const CHI2_SAMPLES: usize = 1_000_000;
/// The chance of any false rejection among all the χ² tests together.
const FAMILY_SIGNIFICANCE: f64 = 0.01;

/// The direction at `theta` degrees from `+z` (from `−z` when `inside`), at an azimuth that
/// lines up with no bin edge.
fn at(theta: f32, inside: bool) -> Vec3 {
    let (t, phi) = (theta.to_radians(), 0.7f32);
    let z = if inside { -t.cos() } else { t.cos() };
    Vec3::new(t.sin() * phi.cos(), t.sin() * phi.sin(), z)
}

/// The microfacet distributions the rough variants are tested with: GGX and Beckmann at each
/// roughness of `alphas`, and both anisotropic, rougher along one axis and then the other.
fn facets(alphas: &[f32]) -> Vec<Microfacet> {
    let mut v = Vec::new();
    for kind in [Distribution::Ggx, Distribution::Beckmann] {
        for &alpha in alphas {
            v.push(Microfacet::isotropic(kind, alpha));
        }
        v.push(Microfacet::new(kind, 0.05, 0.4));
        v.push(Microfacet::new(kind, 0.5, 0.15));
    }
    v
}

/// A short name for a distribution.
fn label(m: Microfacet) -> String {
    let (u, v) = m.alphas();
    let kind = match m.kind() {
        Distribution::Ggx => "GGX",
        Distribution::Beckmann => "Beckmann",
    };
    if u == v {
        format!("{kind} α {u}")
    } else {
        format!("{kind} α {u}×{v}")
    }
}

/// The principled BSDFs and glTF's at settings that reach every lobe.
fn disney_and_gltf(base: Rgb) -> Vec<(String, Bsdf<'static>)> {
    let p = |name: &str, f: &dyn Fn(&mut Principled)| {
        let mut p = Principled {
            base_color: base,
            ..Principled::default()
        };
        f(&mut p);
        (format!("Principled {name}"), Bsdf::Principled(p))
    };
    let t = |name: &str, f: &dyn Fn(&mut PrincipledThin)| {
        let mut p = PrincipledThin {
            base_color: base,
            ..PrincipledThin::default()
        };
        f(&mut p);
        (format!("PrincipledThin {name}"), Bsdf::PrincipledThin(p))
    };
    let g = |name: &str, f: &dyn Fn(&mut GltfPbr)| {
        let mut p = GltfPbr::plain(base, 0.0, 0.3);
        f(&mut p);
        (format!("glTF {name}"), Bsdf::Gltf(p))
    };
    // The diffuse transmission's part, with the base of a material whose lobe it shares.
    let translucent = |name: &str, f: &dyn Fn(&mut GltfPbr)| {
        let (_, Bsdf::Gltf(mut p)) = g(name, &|_| {}) else {
            unreachable!()
        };
        f(&mut p);
        (format!("glTF translucent {name}"), Bsdf::GltfTranslucent(p))
    };
    vec![
        p("default", &|_| {}),
        p("metal", &|p| {
            p.metallic = 1.0;
            p.roughness = 0.3;
        }),
        p("glass", &|p| {
            p.spec_trans = 1.0;
            p.roughness = 0.2;
        }),
        p("everything", &|p| {
            p.metallic = 0.3;
            p.spec_trans = 0.4;
            p.clearcoat = 0.8;
            p.clearcoat_gloss = 0.5;
            p.sheen = 0.5;
            p.sheen_tint = 0.5;
            p.spec_tint = 0.4;
            p.anisotropic = 0.6;
            p.flatness = 0.3;
            p.roughness = 0.4;
        }),
        t("diffuse", &|_| {}),
        t("leaf", &|p| {
            p.spec_trans = 0.3;
            p.diff_trans = 1.2;
            p.sheen = 0.4;
            p.roughness = 0.4;
        }),
        g("plastic", &|_| {}),
        g("metal", &|p| p.metallic = 1.0),
        g("thin glass", &|p| p.transmission = 1.0),
        g("glass", &|p| {
            p.transmission = 1.0;
            p.volume = true;
        }),
        g("brushed", &|p| {
            p.metallic = 0.5;
            p.alpha = Vec2::new(0.4, 0.05);
        }),
        // A thin film on both parts: the lobe weights follow its coloured Fresnel.
        g("iridescent", &|p| {
            p.metallic = 0.3;
            p.iridescence = 1.0;
            p.film_ior = 1.8;
            p.film_thickness = 350;
        }),
        g("leaf", &|p| p.diffuse_transmission = 160),
        translucent("plain", &|_| {}),
        translucent("iridescent", &|p| {
            p.iridescence = 1.0;
            p.film_thickness = 300;
            p.specular_color = Rgb::new(1.0, 0.5, 2.0);
        }),
        g("iridescent glass", &|p| {
            p.transmission = 1.0;
            p.volume = true;
            p.iridescence = 0.7;
            p.film_thickness = 250;
        }),
        (
            "Sheen".to_string(),
            Bsdf::Sheen(Sheen {
                color: base,
                roughness: 0.5,
            }),
        ),
    ]
}

/// A rough coat for the tests, kept for the whole run (its tables are integrated once).
fn coat(kind: Distribution, alpha: f32, eta: f32) -> &'static RoughCoat {
    Box::leak(Box::new(RoughCoat::new(
        Microfacet::isotropic(kind, alpha),
        eta,
    )))
}

fn draw(b: &Bsdf, wo: Vec3, rng: &mut Rng, mode: Transport) -> Option<BsdfSample> {
    let u_lobe = rng.f32();
    let u = Vec2::new(rng.f32(), rng.f32());
    b.sample(wo, u_lobe, u, mode)
}

// ---------------------------------------------------------------------------------------------
// 1. χ² goodness of fit.

/// A direction sampler under test: `None` for draws that are not continuous directions.
type Sampler = Box<dyn Fn(&mut Rng) -> Option<Vec3>>;

/// One χ² test: a named sampler and the density it claims.
struct Case {
    family: &'static str,
    name: String,
    sample: Sampler,
    pdf: Box<dyn Fn(Vec3) -> f32>,
}

/// The continuous part of a BSDF: delta samples (and `None`) go to the harness's "other" cell,
/// whose expected share is `1 − ∫ pdf`.
fn bsdf_case(family: &'static str, name: String, b: Bsdf<'static>, wo: Vec3) -> Case {
    Case {
        family,
        name,
        sample: Box::new(move |rng| {
            draw(&b, wo, rng, Transport::Radiance)
                .filter(|s| !s.delta)
                .map(|s| s.wi)
        }),
        pdf: Box::new(move |wi| b.pdf(wo, wi)),
    }
}

/// Every χ² test, in one table so that the Šidák correction counts them all.
fn cases() -> Vec<Case> {
    let mut v = Vec::new();
    for g in facets(&ALPHAS) {
        for theta in THETAS {
            let wo = at(theta, false);
            v.push(Case {
                family: "visible normals",
                name: format!("{} visible normals θo {theta}°", label(g)),
                sample: Box::new(move |rng| {
                    let u = Vec2::new(rng.f32(), rng.f32());
                    Some(g.sample_visible(wo, u))
                }),
                pdf: Box::new(move |m| g.visible_pdf(wo, m)),
            });
        }
    }
    for theta in THETAS {
        let b = Bsdf::Lambert {
            albedo: Rgb::new(0.8, 0.5, 0.2),
        };
        v.push(bsdf_case(
            "lambert",
            format!("Lambert θo {theta}°"),
            b,
            at(theta, false),
        ));
    }
    for microfacet in facets(&ALPHAS) {
        for theta in THETAS {
            let b = Bsdf::RoughConductor {
                eta: Rgb::new(0.2, 0.9, 1.1),
                k: Rgb::new(3.9, 2.4, 2.2),
                specular: Rgb::WHITE,
                microfacet,
            };
            let name = format!("RoughConductor {} θo {theta}°", label(microfacet));
            v.push(bsdf_case("rough conductor", name, b, at(theta, false)));
        }
    }
    for inside in [false, true] {
        for microfacet in facets(&[0.05, 0.2, 0.6]) {
            for theta in THETAS {
                let b = Bsdf::RoughDielectric {
                    eta: 1.5,
                    specular: Rgb::WHITE,
                    transmittance: Rgb::WHITE,
                    microfacet,
                };
                let side = if inside { "inside" } else { "outside" };
                let name = format!(
                    "RoughDielectric {} θo {theta}° from {side}",
                    label(microfacet)
                );
                let family = if inside {
                    "rough dielectric inside"
                } else {
                    "rough dielectric outside"
                };
                v.push(bsdf_case(family, name, b, at(theta, inside)));
            }
        }
    }
    for nonlinear in [false, true] {
        for theta in THETAS {
            let b = Bsdf::Plastic {
                diffuse: Rgb::new(0.7, 0.3, 0.1),
                eta: 1.5,
                specular: Rgb::WHITE,
                nonlinear,
            };
            let name = format!("Plastic nonlinear {nonlinear} θo {theta}°");
            v.push(bsdf_case("plastic", name, b, at(theta, false)));
        }
    }
    for kind in [Distribution::Ggx, Distribution::Beckmann] {
        for alpha in [0.05, 0.2, 0.6] {
            let coat = coat(kind, alpha, 1.5);
            for theta in THETAS {
                let b = Bsdf::RoughPlastic {
                    diffuse: Rgb::new(0.7, 0.3, 0.1),
                    specular: Rgb::WHITE,
                    nonlinear: false,
                    coat,
                };
                let name = format!("RoughPlastic {kind:?} α {alpha} θo {theta}°");
                v.push(bsdf_case("rough plastic", name, b, at(theta, false)));
            }
        }
    }
    for (name, b) in disney_and_gltf(Rgb::new(0.7, 0.5, 0.3)) {
        // From 85° the refraction into glTF glass ends at z ≈ −0.8, a cell boundary of the
        // harness, where a sample or two in a million fall beyond what its quadrature sees.
        let thetas = if name == "glTF glass" {
            [0.0, 30.0, 60.0, 80.0]
        } else {
            THETAS
        };
        for theta in thetas {
            v.push(bsdf_case(
                "disney and glTF",
                format!("{name} θo {theta}°"),
                b,
                at(theta, false),
            ));
        }
        if b.transmits() && !name.contains("thin") {
            v.push(bsdf_case(
                "disney and glTF",
                format!("{name} from inside"),
                b,
                at(40.0, true),
            ));
        }
    }
    for theta in THETAS {
        for (shininess, inside) in [(1.0, false), (20.0, false), (300.0, false), (20.0, true)] {
            // All four lobes; the two Dirac ones go to the "other" cell.
            let b = Bsdf::Classic {
                kd: Rgb::new(0.3, 0.2, 0.1),
                ks: Rgb::gray(0.4),
                shininess,
                kr: Rgb::gray(0.1),
                kt: if inside { Rgb::gray(0.2) } else { Rgb::BLACK },
                eta: 1.5,
            };
            let name = format!("Classic n {shininess} θo {theta}° inside {inside}");
            v.push(bsdf_case("classic", name, b, at(theta, inside)));
        }
    }
    v
}

/// Run the family's χ² tests, each at the Šidák-corrected significance.
fn chi2_family(family: &str) {
    let all = cases();
    let threshold = chi2::sidak(FAMILY_SIGNIFICANCE, all.len());
    let mut failures = Vec::new();
    let mut ran = 0;
    for (k, case) in all.iter().enumerate().filter(|(_, c)| c.family == family) {
        ran += 1;
        match chi2::test(&*case.sample, &*case.pdf, CHI2_SAMPLES, 1000 + k as u64) {
            Ok(out) if out.p_value >= threshold => {}
            Ok(out) => failures.push(format!(
                "{}: χ² = {:.1} on {} dof, p = {:.3e} < {threshold:.3e}",
                case.name, out.chi2, out.dof, out.p_value
            )),
            Err(e) => failures.push(format!("{}: {e}", case.name)),
        }
    }
    assert!(ran > 0, "no χ² cases in family {family}");
    assert!(
        failures.is_empty(),
        "χ² rejections:\n{}",
        failures.join("\n")
    );
}

#[test]
fn chi2_visible_normals() {
    chi2_family("visible normals");
}

#[test]
fn chi2_lambert() {
    chi2_family("lambert");
}

#[test]
fn chi2_rough_conductor() {
    chi2_family("rough conductor");
}

#[test]
fn chi2_rough_dielectric_from_outside() {
    chi2_family("rough dielectric outside");
}

#[test]
fn chi2_rough_dielectric_from_inside() {
    chi2_family("rough dielectric inside");
}

#[test]
fn chi2_plastic() {
    chi2_family("plastic");
}

#[test]
fn chi2_rough_plastic() {
    chi2_family("rough plastic");
}

#[test]
fn chi2_disney_and_gltf() {
    chi2_family("disney and glTF");
}

#[test]
fn chi2_classic() {
    chi2_family("classic");
}

/// The test must be able to fail: a sampler checked against a slightly different pdf is
/// rejected (at the same corrected significance the real tests use).
#[test]
fn chi2_rejects_a_slightly_wrong_pdf() {
    let threshold = chi2::sidak(FAMILY_SIGNIFICANCE, cases().len());
    let wo = at(30.0, false);
    let rough = |alpha| Bsdf::RoughConductor {
        eta: Rgb::gray(1.5),
        k: Rgb::gray(3.0),
        specular: Rgb::WHITE,
        microfacet: Microfacet::ggx(alpha),
    };
    let (sampled, claimed) = (rough(0.2), rough(0.21));
    let sample = move |rng: &mut Rng| draw(&sampled, wo, rng, Transport::Radiance).map(|s| s.wi);
    let pdf = move |wi| claimed.pdf(wo, wi);
    let out = chi2::test(&sample, &pdf, CHI2_SAMPLES, 7).unwrap();
    assert!(out.p_value < threshold, "α 0.2 passed as 0.21: {out:?}");

    // Glass whose sampler reflects a little too often (F·1.1) is caught by the split.
    let glass = Bsdf::RoughDielectric {
        eta: 1.5,
        specular: Rgb::WHITE,
        transmittance: Rgb::WHITE,
        microfacet: Microfacet::ggx(0.3),
    };
    let wo = at(60.0, false);
    let f = super::fresnel::dielectric(wo.z, 1.5).r;
    let sample = move |rng: &mut Rng| {
        let u_lobe = rng.f32();
        // Push part of the refraction draws just above F down into reflection.
        let u_lobe = if u_lobe > f && u_lobe < 1.1 * f {
            0.0
        } else {
            u_lobe
        };
        glass
            .sample(
                wo,
                u_lobe,
                Vec2::new(rng.f32(), rng.f32()),
                Transport::Radiance,
            )
            .map(|s| s.wi)
    };
    let pdf = move |wi| glass.pdf(wo, wi);
    let out = chi2::test(&sample, &pdf, CHI2_SAMPLES, 8).unwrap();
    assert!(
        out.p_value < threshold,
        "a 10% reflection bias passed: {out:?}"
    );
}

// Sample weights, energy, reciprocity and degenerate input: in their own file.
mod weights_and_energy;
