//! A rough conductor: microfacets (GGX or Beckmann, isotropic or anisotropic), each a mirror
//! with the conductor's Fresnel reflectance (Mitsuba 3 `roughconductor`, `sample_visible =
//! true`).
//!
//! The Torrance–Sparrow form with the half vector `h = (wo + wi)/|wo + wi|`:
//! `f(wo, wi) = specular·F(wo·h)·D(h)·G1(wo, h)·G1(wi, h) / (4 cos θo cos θi)`.
//! Sampling draws `h` from the normals visible from `wo` and reflects `wo` about it; the
//! reflection's Jacobian `dωh/dωi = 1/(4 wo·h)` makes the density
//! `pdf = D_wo(h)/(4 wo·h) = G1(wo, h)·D(h)/(4 cos θo)` and leaves the weight
//! `f·cos θi/pdf = specular·F(wo·h)·G1(wi, h)`.

use glam::{Vec2, Vec3};

use super::microfacet::Microfacet;
use super::{BsdfSample, fresnel};
use crate::Rgb;
use crate::optics::reflect;

/// The rough conductor's parameters.
pub(super) struct RoughConductor {
    eta: Rgb,
    k: Rgb,
    specular: Rgb,
    facets: Microfacet,
}

impl RoughConductor {
    pub fn new(eta: Rgb, k: Rgb, specular: Rgb, microfacet: Microfacet) -> Self {
        Self {
            eta,
            k,
            specular,
            facets: microfacet,
        }
    }

    /// The half vector of two front-side directions; `None` on the back side.
    fn half(wo: Vec3, wi: Vec3) -> Option<Vec3> {
        // Both z > 0, so wo + wi has z > 0 and never vanishes.
        (wo.z > 0.0 && wi.z > 0.0).then(|| (wo + wi).normalize())
    }

    /// `f·cos θi = specular·F(wo·h)·D(h)·G1(wi, h)·[G1(wo, h)/cos θo] / 4`, the bracket kept
    /// whole so that grazing `wo` stays finite.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        let Some(h) = Self::half(wo, wi) else {
            return Rgb::BLACK;
        };
        let g = self.facets;
        let scalar = g.d(h) * g.g1(wi, h) * g.g1_over_cos(wo, h) * 0.25;
        if scalar <= 0.0 {
            return Rgb::BLACK;
        }
        self.specular * fresnel::conductor(wo.dot(h), self.eta, self.k) * scalar
    }

    /// `D(h)·[G1(wo, h)/cos θo] / 4`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some(h) = Self::half(wo, wi) else {
            return 0.0;
        };
        self.facets.d(h) * self.facets.g1_over_cos(wo, h) * 0.25
    }

    /// A visible normal, and `wo` mirrored about it; `None` when that goes below the horizon.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let m = self.facets.sample_visible(wo, u);
        let wi = reflect(-wo, m);
        if wi.z <= 0.0 {
            return None;
        }
        let weight =
            self.specular * fresnel::conductor(wo.dot(m), self.eta, self.k) * self.facets.g1(wi, m);
        Some(BsdfSample {
            wi,
            weight,
            pdf: self.facets.d(m) * self.facets.g1_over_cos(wo, m) * 0.25,
            delta: false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn head_on_light_at_the_mirror_direction_peaks_at_d_over_4() {
        // wo = wi = n: h = n, G1 = 1, so f·cos θi = F·D(n)/4 = F/(4πα²).
        let alpha = 0.3;
        let b = RoughConductor::new(
            Rgb::gray(1.5),
            Rgb::gray(3.0),
            Rgb::WHITE,
            Microfacet::ggx(alpha),
        );
        let f = b.eval(Vec3::Z, Vec3::Z);
        let fresnel = fresnel::conductor(1.0, Rgb::gray(1.5), Rgb::gray(3.0)).r;
        let want = fresnel / (4.0 * std::f32::consts::PI * alpha * alpha);
        assert!((f.r - want).abs() < 1e-5 * want, "{} vs {want}", f.r);
        assert!(b.eval(Vec3::Z, -Vec3::Z).is_black() && b.pdf(-Vec3::Z, Vec3::Z) == 0.0);
    }
}
