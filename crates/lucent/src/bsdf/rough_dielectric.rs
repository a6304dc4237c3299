//! Rough glass: microfacets (GGX or Beckmann, isotropic or anisotropic) that each reflect or
//! refract like smooth glass, after Walter, Marschner, Li & Torrance 2007, "Microfacet Models
//! for Refraction through Rough Surfaces" (Mitsuba 3 `roughdielectric`, `sample_visible =
//! true`).
//!
//! With `η'` the relative index in the direction of travel (`eta` from outside, `1/eta` from
//! inside, where `wo.z < 0`), the generalized half vector is `m = ±(wo + wi)` for reflection and
//! `m = ±(wo + η' wi)` for refraction, normalised and turned into the upper hemisphere. With
//! `G = G1(wo, m)·G1(wi, m)` and `F = F(wo·m)`:
//! - reflection: `f = F·D(m)·G / (4 |cos θo| |cos θi|)`;
//! - refraction: `f = (1 − F)·D(m)·G·|wo·m|·|wi·m| / (|cos θo| |cos θi| (wo·m + η' wi·m)²)`,
//!   times `η'²` for importance (Walter's BTDF) — radiance loses that factor, the `1/η'²`
//!   solid-angle compression the paper leaves out.
//!
//! Sampling draws `m` from the normals visible from `wo` (from `−wo` inside), reflects with
//! probability `F(wo·m)` and refracts otherwise. The Jacobians `dωm/dωi` are `1/(4|wi·m|)` and
//! `η'²|wi·m|/(wo·m + η' wi·m)²`, so the density is `D_wo(m)·F·(Jacobian)` (or `1 − F`), and the
//! weight reduces to `G1(wi, m)`, times `1/η'²` for refracted radiance.
//!
//! Energy: single scattering only, so very rough glass loses the light that would bounce
//! between facets (a few percent at α = 0.2, more at α = 1 and grazing angles).

use glam::{Vec2, Vec3};

use super::microfacet::Microfacet;
use super::{BsdfSample, Transport, fresnel};
use crate::Rgb;
use crate::optics::reflect;

/// Relative indices closer to 1 than this are index-matched: the refraction lobe collapses to a
/// straight-through Dirac delta (its Jacobian is singular at η' = 1) and nothing reflects.
const INDEX_MATCHED: f32 = 1e-3;

/// The rough dielectric's parameters.
pub(super) struct RoughDielectric {
    eta: f32,
    specular: Rgb,
    transmittance: Rgb,
    facets: Microfacet,
}

/// The generalized half vector of a pair of directions and what eval and pdf share.
struct Half {
    /// The microfacet normal, upper hemisphere.
    m: Vec3,
    /// Reflection (both on the same side) or refraction.
    reflect: bool,
    /// `η'`, the relative index in the direction of travel from `wo`.
    eta_it: f32,
    /// `wo·m + η'·wi·m` (refraction only; its square is the Jacobian's denominator).
    denom: f32,
}

impl RoughDielectric {
    pub fn new(eta: f32, specular: Rgb, transmittance: Rgb, microfacet: Microfacet) -> Self {
        Self {
            eta: fresnel::sane_eta(eta),
            specular,
            transmittance,
            facets: microfacet,
        }
    }

    fn index_matched(&self) -> bool {
        (self.eta - 1.0).abs() < INDEX_MATCHED
    }

    /// True when only the Dirac lobe of index-matched glass is left.
    pub fn is_delta(&self) -> bool {
        self.index_matched()
    }

    /// The half vector of `wo` and `wi`, or `None` when no facet links them: a grazing
    /// direction, or a facet seen from its back by either direction.
    fn half(&self, wo: Vec3, wi: Vec3) -> Option<Half> {
        if wo.z == 0.0 || wi.z == 0.0 || self.index_matched() {
            return None;
        }
        let reflect = wo.z * wi.z > 0.0;
        let eta_it = if wo.z > 0.0 { self.eta } else { 1.0 / self.eta };
        let h = if reflect { wo + wi } else { wo + eta_it * wi };
        let len = h.length();
        // |wo + η' wi| vanishes only for η' = 1 (excluded above) and wi = −wo.
        if len.is_nan() || len <= 1e-6 {
            return None;
        }
        let m = if h.z < 0.0 { -h / len } else { h / len };
        let (cos_om, cos_im) = (wo.dot(m), wi.dot(m));
        if cos_om * wo.z <= 0.0 || cos_im * wi.z <= 0.0 {
            return None;
        }
        Some(Half {
            m,
            reflect,
            eta_it,
            denom: cos_om + eta_it * cos_im,
        })
    }

    /// `wo` turned into the upper hemisphere, the direction whose visible normals are sampled.
    fn viewer(wo: Vec3) -> Vec3 {
        if wo.z < 0.0 { -wo } else { wo }
    }

    /// `f·|cos θi|` by the formulas above, with `G1(wo)/|cos θo|` kept as one finite factor.
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: Transport) -> Rgb {
        let Some(h) = self.half(wo, wi) else {
            return Rgb::BLACK;
        };
        let g = self.facets;
        let cos_om = wo.dot(h.m);
        let f = fresnel::dielectric(cos_om, self.eta).r;
        let dg = g.d(h.m) * g.g1_over_cos(wo, h.m) * g.g1(wi, h.m);
        if h.reflect {
            return self.specular * (f * dg * 0.25);
        }
        let cos_im = wi.dot(h.m);
        let scale = match mode {
            Transport::Radiance => 1.0,
            Transport::Importance => h.eta_it * h.eta_it,
        };
        let value = (1.0 - f) * dg * (cos_om * cos_im).abs() / (h.denom * h.denom) * scale;
        self.transmittance * value
    }

    /// `D_wo(m)·F·/(4|wi·m|)` for reflection, `D_wo(m)·(1 − F)·η'²|wi·m|/(wo·m + η' wi·m)²`
    /// for refraction.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some(h) = self.half(wo, wi) else {
            return 0.0;
        };
        let visible = self.facets.visible_pdf(Self::viewer(wo), h.m);
        let f = fresnel::dielectric(wo.dot(h.m), self.eta).r;
        let cos_im = wi.dot(h.m).abs();
        if h.reflect {
            visible * f / (4.0 * cos_im)
        } else {
            visible * (1.0 - f) * h.eta_it * h.eta_it * cos_im / (h.denom * h.denom)
        }
    }

    /// A visible facet, then its reflection (`u_lobe < F`) or refraction.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: Transport) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        if self.index_matched() {
            // No boundary: the light goes straight through, unscaled (η' = 1).
            return Some(BsdfSample {
                wi: -wo,
                weight: self.transmittance,
                pdf: 1.0,
                delta: true,
            });
        }
        let v = Self::viewer(wo);
        let m = self.facets.sample_visible(v, u);
        let visible = self.facets.visible_pdf(v, m);
        let cos_om = wo.dot(m);
        if visible <= 0.0 || cos_om * wo.z <= 0.0 {
            return None;
        }
        let f = fresnel::dielectric(cos_om, self.eta);
        if u_lobe < f.r {
            let wi = reflect(-wo, m);
            // The facet may send the light through the macro-surface: no such path.
            if wi.z * wo.z <= 0.0 {
                return None;
            }
            return Some(BsdfSample {
                wi,
                weight: self.specular * self.facets.g1(wi, m),
                pdf: visible * f.r / (4.0 * wi.dot(m).abs()),
                delta: false,
            });
        }
        let wi = fresnel::refract(wo, m, &f).normalize_or_zero();
        if wi.z * wo.z >= 0.0 {
            return None;
        }
        let cos_im = wi.dot(m);
        let denom = cos_om + f.eta_it * cos_im;
        let scale = match mode {
            Transport::Radiance => f.eta_ti * f.eta_ti,
            Transport::Importance => 1.0,
        };
        Some(BsdfSample {
            wi,
            weight: self.transmittance * (self.facets.g1(wi, m) * scale),
            pdf: visible * (1.0 - f.r) * f.eta_it * f.eta_it * cos_im.abs() / (denom * denom),
            delta: false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glass(alpha: f32) -> RoughDielectric {
        RoughDielectric::new(1.5, Rgb::WHITE, Rgb::WHITE, Microfacet::ggx(alpha))
    }

    #[test]
    fn the_half_vector_of_a_refraction_is_the_facet_that_bends_it() {
        // Refract through a tilted facet by Snell's law; the half vector must find that facet.
        let b = glass(0.3);
        let m = Vec3::new(0.3, -0.1, 0.95).normalize();
        for wo in [
            Vec3::new(0.4, 0.2, 0.89).normalize(),
            Vec3::new(-0.2, 0.1, -0.97).normalize(),
        ] {
            let f = fresnel::dielectric(wo.dot(m), 1.5);
            let wi = fresnel::refract(wo, m, &f);
            let h = b.half(wo, wi).expect("a refraction");
            assert!(!h.reflect && (h.m - m).length() < 1e-5, "{} vs {m}", h.m);
        }
    }

    #[test]
    fn importance_is_eta_squared_times_radiance_on_refraction() {
        let b = glass(0.4);
        let wo = Vec3::new(0.3, 0.2, 0.93).normalize();
        let wi = Vec3::new(-0.2, -0.1, -0.97).normalize();
        let r = b.eval(wo, wi, Transport::Radiance);
        let i = b.eval(wo, wi, Transport::Importance);
        assert!(
            r.r > 0.0 && (i.r / r.r - 2.25).abs() < 1e-5,
            "{}",
            i.r / r.r
        );
        // Reflection does not care.
        let wr = Vec3::new(-0.1, 0.3, 0.95).normalize();
        assert_eq!(
            b.eval(wo, wr, Transport::Radiance),
            b.eval(wo, wr, Transport::Importance)
        );
    }

    #[test]
    fn a_radiance_refraction_is_the_adjoint_of_the_importance_one() {
        // f_radiance(wo → wi) / |cos θi| = f_importance(wi → wo) / |cos θo|: the BTDF is not
        // symmetric, but radiance and importance are each other's adjoint.
        let b = glass(0.25);
        let pairs = [
            (Vec3::new(0.3, 0.2, 0.93), Vec3::new(-0.2, -0.1, -0.97)),
            (Vec3::new(-0.5, 0.1, 0.86), Vec3::new(0.3, 0.2, -0.93)),
            (Vec3::new(0.1, 0.6, -0.79), Vec3::new(0.1, -0.3, 0.95)),
        ];
        for (wo, wi) in pairs {
            let (wo, wi) = (wo.normalize(), wi.normalize());
            let a = b.eval(wo, wi, Transport::Radiance).r / wi.z.abs();
            let c = b.eval(wi, wo, Transport::Importance).r / wo.z.abs();
            assert!(a > 0.0 && (a - c).abs() <= 1e-4 * a, "{a} vs {c}");
        }
    }

    #[test]
    fn index_matched_rough_glass_is_a_window() {
        let b = RoughDielectric::new(1.0, Rgb::WHITE, Rgb::WHITE, Microfacet::ggx(0.5));
        let wo = Vec3::new(0.6, 0.0, 0.8);
        let s = b
            .sample(wo, 0.3, Vec2::new(0.2, 0.7), Transport::Radiance)
            .unwrap();
        assert!(s.delta && s.wi == -wo && s.weight == Rgb::WHITE);
        assert!(b.is_delta() && b.eval(wo, -wo, Transport::Radiance).is_black());
        assert_eq!(b.pdf(wo, Vec3::new(-0.6, 0.0, -0.8)), 0.0);
    }
}
