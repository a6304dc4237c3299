//! Lambert: ideal diffuse reflection, `f = albedo/π` (Mitsuba 3 `diffuse`), and the
//! cosine-weighted hemisphere sampling that other diffuse lobes share.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::BsdfSample;
use crate::Rgb;
use crate::lanes::{Real, V3};
use crate::sampling::warp::{
    cosine_hemisphere, cosine_hemisphere_pdf, square_to_cosine_hemisphere,
};

/// The Lambert variant's parameters.
pub(super) struct Lambert {
    pub albedo: Rgb,
}

impl Lambert {
    /// `f·cos θi = albedo·cos θi/π` on the front side, zero elsewhere.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        let (front, cos_over_pi) = lambert_eval(wo.into(), wi.into());
        if front {
            self.albedo * cos_over_pi
        } else {
            Rgb::BLACK
        }
    }

    /// `cos θi/π`, the density of [`sample_cosine`], on the front side.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        lambert_pdf(wo.into(), wi.into())
    }

    /// A cosine-weighted direction; the weight `f·cos/pdf` is then exactly the albedo.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if self.albedo.is_black() {
            return None;
        }
        let (ok, wi, pdf) = lambert_sample(wo.into(), u.x, u.y);
        ok.then(|| BsdfSample {
            wi: wi.into(),
            weight: self.albedo,
            pdf,
            delta: false,
        })
    }
}

/// Lambert's value without its albedo, for any [`Real`] (written once for one path and for
/// lanes): where both directions are above the surface (the mask), `cos θi/π`.
#[inline(always)]
pub fn lambert_eval<R: Real>(wo: V3<R>, wi: V3<R>) -> (R::Mask, R) {
    let zero = R::splat(0.0);
    (wo.z.gt(zero) & wi.z.gt(zero), wi.z * R::splat(FRAC_1_PI))
}

/// Lambert's density for any [`Real`]: `cos θi/π` when `wo` is above the surface, else 0.
#[inline(always)]
pub fn lambert_pdf<R: Real>(wo: V3<R>, wi: V3<R>) -> R {
    R::select(
        wo.z.gt(R::splat(0.0)),
        cosine_hemisphere_pdf(wi.z),
        R::splat(0.0),
    )
}

/// Lambert's sample for any [`Real`]: where the mask holds, a cosine-weighted direction and
/// its density (the weight is the albedo); not where `wo` is below the surface, or the
/// direction fell on the rim ([`sample_cosine`]).
#[inline(always)]
pub fn lambert_sample<R: Real>(wo: V3<R>, ux: R, uy: R) -> (R::Mask, V3<R>, R) {
    let wi = cosine_hemisphere(ux, uy);
    let zero = R::splat(0.0);
    (
        wo.z.gt(zero) & wi.z.gt(zero),
        wi,
        cosine_hemisphere_pdf(wi.z),
    )
}

/// A direction in the upper hemisphere with density `cos θ/π`
/// ([`square_to_cosine_hemisphere`]: Malley's method over the concentric disc); `None` for the
/// measure-zero points on the rim, where `z = 0` and the density vanishes.
pub(super) fn sample_cosine(u: Vec2) -> Option<Vec3> {
    let w = square_to_cosine_hemisphere(u);
    (w.z > 0.0).then_some(w)
}

/// The density of [`sample_cosine`]: `max(cos θ, 0)/π`.
#[inline]
pub(super) fn cosine_pdf(w: Vec3) -> f32 {
    cosine_hemisphere_pdf(w.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_value_is_albedo_over_pi_times_the_cosine() {
        let b = Lambert {
            albedo: Rgb::new(0.2, 0.5, 0.9),
        };
        let wo = Vec3::new(0.3, 0.1, 0.9).normalize();
        let wi = Vec3::new(-0.5, 0.2, 0.6).normalize();
        let f = b.eval(wo, wi);
        assert!((f.g - 0.5 * wi.z / std::f32::consts::PI).abs() < 1e-7);
        // One-sided: nothing from or towards the back.
        assert!(b.eval(-wo, wi).is_black() && b.eval(wo, -wi).is_black());
        assert!(b.sample(-wo, Vec2::splat(0.5)).is_none());
    }

    #[test]
    fn a_white_lambertian_returns_everything_in_every_sample() {
        let b = Lambert { albedo: Rgb::WHITE };
        let wo = Vec3::new(0.6, 0.0, 0.8);
        for i in 0..64 {
            for j in 0..64 {
                let u = Vec2::new(i as f32 / 64.0, j as f32 / 64.0);
                if let Some(s) = b.sample(wo, u) {
                    assert_eq!(s.weight, Rgb::WHITE);
                    assert!(s.wi.z > 0.0 && (s.wi.length() - 1.0).abs() < 1e-5);
                }
            }
        }
    }
}
