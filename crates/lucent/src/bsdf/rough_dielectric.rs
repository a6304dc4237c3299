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

use super::ggx::Facets;
use super::microfacet::Microfacet;
use super::{BsdfSample, Transport, fresnel};
use crate::Rgb;
use crate::lanes::{Real, V3};

/// Relative indices closer to 1 than this are index-matched: the refraction lobe collapses to a
/// straight-through Dirac delta (its Jacobian is singular at η' = 1) and nothing reflects.
pub(crate) const INDEX_MATCHED: f32 = 1e-3;

/// The rough dielectric's parameters.
pub(super) struct RoughDielectric {
    eta: f32,
    specular: Rgb,
    transmittance: Rgb,
    facets: Microfacet,
}

/// The generalized half vector of a pair of directions and what eval and pdf share, written
/// once over [`Real`] ([`half`]).
struct Half<R: Real> {
    /// A facet links the two directions (neither grazing, neither seeing a facet's back).
    linked: R::Mask,
    /// The microfacet normal, upper hemisphere.
    m: V3<R>,
    /// Reflection (both on the same side) or refraction.
    reflect: R::Mask,
    /// `η'`, the relative index in the direction of travel from `wo`.
    eta_it: R,
    /// `wo·m + η'·wi·m` (refraction only; its square is the Jacobian's denominator).
    denom: R,
}

/// What a rough dielectric's value and density for `(wo, wi)` are without colours: where they
/// are not zero, whether `wi` is reflected, the factor of `specular` or `transmittance`, and
/// the density ([`value_and_pdf`]).
pub(crate) struct Scatter<R: Real> {
    pub linked: R::Mask,
    pub reflect: R::Mask,
    pub value: R,
    pub pdf: R,
}

/// A rough dielectric's sample without colours ([`sampled`]): where there is one, whether it
/// reflects (a factor of `specular`, else of `transmittance`), the direction, the factor and
/// the density.
pub(crate) struct Sampled<R: Real> {
    pub ok: R::Mask,
    pub reflect: R::Mask,
    pub wi: V3<R>,
    pub weight: R,
    pub pdf: R,
}

/// The half vector of `wo` and `wi` for a sane index `eta` that is not index-matched.
#[inline(always)]
fn half<R: Real>(eta: R, wo: V3<R>, wi: V3<R>) -> Half<R> {
    let zero = R::splat(0.0);
    let reflect = (wo.z * wi.z).gt(zero);
    let eta_it = R::select(wo.z.gt(zero), eta, R::splat(1.0) / eta);
    let h = V3::select(reflect, wo + wi, wo + wi * eta_it);
    let len = h.length_squared().sqrt();
    // |wo + η' wi| vanishes only for η' = 1 (excluded) and wi = −wo.
    let m = V3::select(h.z.lt(zero), (-h) / len, h / len);
    let (cos_om, cos_im) = (wo.dot(m), wi.dot(m));
    let grazing = wo.z.eq(zero) | wi.z.eq(zero);
    let backs = (cos_om * wo.z).le(zero) | (cos_im * wi.z).le(zero);
    Half {
        linked: !grazing & len.gt(R::splat(1e-6)) & !backs,
        m,
        reflect,
        eta_it,
        denom: cos_om + eta_it * cos_im,
    }
}

/// `wo` turned into the upper hemisphere, the direction whose visible normals are sampled.
#[inline(always)]
fn viewer<R: Real>(wo: V3<R>) -> V3<R> {
    V3::select(wo.z.lt(R::splat(0.0)), -wo, wo)
}

/// `f·|cos θi|` and the density by the formulas above, without colours, for a sane index `eta`
/// that is not index-matched; `importance` scales refraction by `η'²`.
#[inline(always)]
pub(crate) fn value_and_pdf<R: Real>(
    facets: impl Facets<R>,
    eta: R,
    (wo, wi): (V3<R>, V3<R>),
    importance: bool,
) -> Scatter<R> {
    let one = R::splat(1.0);
    let h = half(eta, wo, wi);
    let cos_om = wo.dot(h.m);
    let f = fresnel::dielectric_of(cos_om, eta).r;
    // G1(wo)/|cos θo| kept as one finite factor.
    let dg = facets.d(h.m) * facets.g1_over_cos(wo, h.m) * facets.g1(wi, h.m);
    let cos_im = wi.dot(h.m);
    let scale = if importance { h.eta_it * h.eta_it } else { one };
    let refracted = (one - f) * dg * (cos_om * cos_im).abs() / (h.denom * h.denom) * scale;
    let value = R::select(h.reflect, f * dg * R::splat(0.25), refracted);
    let visible = facets.visible_pdf(viewer(wo), h.m);
    let abs_im = cos_im.abs();
    let pdf = R::select(
        h.reflect,
        visible * f / (R::splat(4.0) * abs_im),
        visible * (one - f) * h.eta_it * h.eta_it * abs_im / (h.denom * h.denom),
    );
    Scatter {
        linked: h.linked,
        reflect: h.reflect,
        value,
        pdf,
    }
}

/// A visible facet, then its reflection (`u_lobe < F`) or refraction, without colours, for a
/// sane index `eta` that is not index-matched; `importance` leaves refraction unscaled.
#[inline(always)]
pub(crate) fn sampled<R: Real>(
    facets: impl Facets<R>,
    eta: R,
    wo: V3<R>,
    (u_lobe, u): (R, (R, R)),
    importance: bool,
) -> Sampled<R> {
    let (zero, one) = (R::splat(0.0), R::splat(1.0));
    let v = viewer(wo);
    let m = facets.sample_visible(v, u);
    let visible = facets.visible_pdf(v, m);
    let cos_om = wo.dot(m);
    let seen = !(wo.z.eq(zero) | visible.le(zero) | (cos_om * wo.z).le(zero));
    let f = fresnel::dielectric_of(cos_om, eta);
    let reflect = u_lobe.lt(f.r);
    // Reflected: the facet may send the light through the macro-surface (no such path).
    let wr = (-wo).reflect(m);
    let reflected_ok = !(wr.z * wo.z).le(zero);
    let pdf_r = visible * f.r / (R::splat(4.0) * wr.dot(m).abs());
    // Refracted: it must cross the macro-surface.
    let wt = fresnel::refract_of(wo, m, &f).normalize_or(Vec3::ZERO);
    let refracted_ok = !(wt.z * wo.z).ge(zero);
    let cos_im = wt.dot(m);
    let denom = cos_om + f.eta_it * cos_im;
    let scale = if importance { one } else { f.eta_ti * f.eta_ti };
    let pdf_t = visible * (one - f.r) * f.eta_it * f.eta_it * cos_im.abs() / (denom * denom);
    let wi = V3::select(reflect, wr, wt);
    Sampled {
        ok: seen & ((reflect & reflected_ok) | (!reflect & refracted_ok)),
        reflect,
        wi,
        weight: R::select(reflect, facets.g1(wr, m), facets.g1(wt, m) * scale),
        pdf: R::select(reflect, pdf_r, pdf_t),
    }
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

    /// The value and density without colours, `None` where both are zero (index-matched glass
    /// has only its Dirac lobe).
    fn scatter(&self, wo: Vec3, wi: Vec3, mode: Transport) -> Option<Scatter<f32>> {
        if self.index_matched() {
            return None;
        }
        let importance = mode == Transport::Importance;
        let s = value_and_pdf(self.facets, self.eta, (wo.into(), wi.into()), importance);
        s.linked.then_some(s)
    }

    /// `f·|cos θi|` by the formulas above.
    pub fn eval(&self, wo: Vec3, wi: Vec3, mode: Transport) -> Rgb {
        match self.scatter(wo, wi, mode) {
            None => Rgb::BLACK,
            Some(s) if s.reflect => self.specular * s.value,
            Some(s) => self.transmittance * s.value,
        }
    }

    /// `D_wo(m)·F·/(4|wi·m|)` for reflection, `D_wo(m)·(1 − F)·η'²|wi·m|/(wo·m + η' wi·m)²`
    /// for refraction.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.scatter(wo, wi, Transport::Radiance)
            .map_or(0.0, |s| s.pdf)
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
        let importance = mode == Transport::Importance;
        let s = sampled(
            self.facets,
            self.eta,
            wo.into(),
            (u_lobe, (u.x, u.y)),
            importance,
        );
        s.ok.then(|| BsdfSample {
            wi: s.wi.into(),
            weight: if s.reflect {
                self.specular * s.weight
            } else {
                self.transmittance * s.weight
            },
            pdf: s.pdf,
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
            let h = half(b.eta, wo.into(), wi.into());
            let found = Vec3::from(h.m);
            assert!(h.linked && !h.reflect, "a refraction");
            assert!((found - m).length() < 1e-5, "{found} vs {m}");
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
