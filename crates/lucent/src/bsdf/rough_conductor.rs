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

use super::ggx::Facets;
use super::microfacet::Microfacet;
use super::{BsdfSample, fresnel};
use crate::Rgb;
use crate::lanes::{Real, V3};

/// The rough conductor's parameters.
pub(super) struct RoughConductor {
    eta: Rgb,
    k: Rgb,
    specular: Rgb,
    facets: Microfacet,
}

/// What a rough conductor's value for `(wo, wi)` is without its colours, written once for one
/// path and for lanes ([`reflection`]).
pub(crate) struct Reflection<R: Real> {
    /// Both directions above the surface (else value and density are zero).
    pub front: R::Mask,
    /// `D(h)·G1(wi, h)·[G1(wo, h)/cos θo] / 4`: `f·cos θi` without `specular·F`.
    pub value: R,
    /// `D(h)·[G1(wo, h)/cos θo] / 4`, the density of sampling `wi`.
    pub pdf: R,
    /// `wo·h`, the Fresnel reflectance's cosine.
    pub cos: R,
}

/// A rough conductor's sample without its colours ([`mirrored`]).
pub(crate) struct Mirrored<R: Real> {
    /// `wi` is above the surface (`wo` must be: the caller checks it first).
    pub above: R::Mask,
    /// `wo` mirrored about a visible normal `m`.
    pub wi: V3<R>,
    /// `wo·m`, the Fresnel reflectance's cosine.
    pub cos: R,
    /// `G1(wi, m)`: the weight without `specular·F`.
    pub g1: R,
    /// The density, `D(m)·[G1(wo, m)/cos θo] / 4`.
    pub pdf: R,
}

/// The colourless terms of the value and density for `(wo, wi)`, with the half vector
/// `h = (wo + wi)/|wo + wi|` (meaningful where both are above the surface: `front`).
#[inline(always)]
pub(crate) fn reflection<R: Real>(facets: impl Facets<R>, wo: V3<R>, wi: V3<R>) -> Reflection<R> {
    let zero = R::splat(0.0);
    let h = (wo + wi).normalize();
    let d = facets.d(h);
    // The bracket G1(wo, h)/cos θo kept whole, so that grazing wo stays finite.
    let over_cos = facets.g1_over_cos(wo, h);
    let quarter = R::splat(0.25);
    Reflection {
        front: wo.z.gt(zero) & wi.z.gt(zero),
        value: d * facets.g1(wi, h) * over_cos * quarter,
        pdf: d * over_cos * quarter,
        cos: wo.dot(h),
    }
}

/// A visible normal drawn from `wo` (above the surface) with `u`, and `wo` mirrored about it.
#[inline(always)]
pub(crate) fn mirrored<R: Real>(facets: impl Facets<R>, wo: V3<R>, u: (R, R)) -> Mirrored<R> {
    let m = facets.sample_visible(wo, u);
    let wi = (-wo).reflect(m);
    Mirrored {
        above: wi.z.gt(R::splat(0.0)),
        wi,
        cos: wo.dot(m),
        g1: facets.g1(wi, m),
        pdf: facets.d(m) * facets.g1_over_cos(wo, m) * R::splat(0.25),
    }
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

    /// `specular·F(wo·h)·D(h)·G1(wi, h)·[G1(wo, h)/cos θo] / 4`; black on the back side.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        let r = reflection(self.facets, wo.into(), wi.into());
        if !r.front || r.value <= 0.0 {
            return Rgb::BLACK;
        }
        self.specular * fresnel::conductor(r.cos, self.eta, self.k) * r.value
    }

    /// `D(h)·[G1(wo, h)/cos θo] / 4`; zero on the back side.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let r = reflection(self.facets, wo.into(), wi.into());
        if r.front { r.pdf } else { 0.0 }
    }

    /// A visible normal, and `wo` mirrored about it; `None` when that goes below the horizon.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let s = mirrored(self.facets, wo.into(), (u.x, u.y));
        if !s.above {
            return None;
        }
        Some(BsdfSample {
            wi: s.wi.into(),
            weight: self.specular * fresnel::conductor(s.cos, self.eta, self.k) * s.g1,
            pdf: s.pdf,
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
