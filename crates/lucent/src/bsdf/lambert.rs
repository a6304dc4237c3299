//! Lambert: ideal diffuse reflection, `f = albedo/π` (Mitsuba 3 `diffuse`), and the
//! cosine-weighted hemisphere sampling that other diffuse lobes share.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::BsdfSample;
use crate::Rgb;
use crate::sampling::warp::{cosine_hemisphere_pdf, square_to_cosine_hemisphere};

/// The Lambert variant's parameters.
pub(super) struct Lambert {
    pub albedo: Rgb,
}

impl Lambert {
    /// `f·cos θi = albedo·cos θi/π` on the front side, zero elsewhere.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wo.z > 0.0 && wi.z > 0.0 {
            self.albedo * (wi.z * FRAC_1_PI)
        } else {
            Rgb::BLACK
        }
    }

    /// `cos θi/π`, the density of [`sample_cosine`], on the front side.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z > 0.0 { cosine_pdf(wi) } else { 0.0 }
    }

    /// A cosine-weighted direction; the weight `f·cos/pdf` is then exactly the albedo.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 || self.albedo.is_black() {
            return None;
        }
        let wi = sample_cosine(u)?;
        Some(BsdfSample {
            wi,
            weight: self.albedo,
            pdf: cosine_pdf(wi),
            delta: false,
        })
    }
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
