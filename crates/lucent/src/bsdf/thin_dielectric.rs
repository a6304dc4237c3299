//! A thin dielectric sheet (a window pane, a soap film without interference): light reflects
//! off both of its faces and passes straight through, unbent, because the two refractions undo
//! each other (Mitsuba 3 `thindielectric`).
//!
//! With `R = F(cos θ)` the reflectance of one face and `T = 1 − R`, the light bouncing inside
//! the sheet sums to a reflectance `R' = R + T²R + T²R³ + … = R + T²R/(1 − R²) = 2R/(1 + R)`
//! and a transmittance `1 − R'`. Both lobes are Dirac deltas: sampling reflects with
//! probability `R'`, so the weights are `specular` and `transmittance`; no solid angle is
//! compressed, so radiance and importance are carried alike. The sheet is the same from both
//! sides.

use glam::Vec3;

use super::{BsdfSample, fresnel, mirror};
use crate::Rgb;

/// The thin sheet's parameters.
pub(super) struct ThinDielectric {
    eta: f32,
    specular: Rgb,
    transmittance: Rgb,
}

impl ThinDielectric {
    pub fn new(eta: f32, specular: Rgb, transmittance: Rgb) -> Self {
        Self {
            eta: fresnel::sane_eta(eta),
            specular,
            transmittance,
        }
    }

    /// `R'` at `cos θ` (either side).
    fn reflectance(&self, cos: f32) -> f32 {
        let r = fresnel::dielectric(cos.abs(), self.eta).r;
        2.0 * r / (1.0 + r)
    }

    /// Reflect when `u_lobe < R'`, else pass straight through.
    pub fn sample(&self, wo: Vec3, u_lobe: f32) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let r = self.reflectance(wo.z);
        if u_lobe < r {
            return Some(BsdfSample {
                wi: mirror(wo),
                weight: self.specular,
                pdf: r,
                delta: true,
            });
        }
        Some(BsdfSample {
            wi: -wo,
            weight: self.transmittance,
            pdf: 1.0 - r,
            delta: true,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pane_reflects_both_faces_and_lets_the_rest_through_unbent() {
        let pane = ThinDielectric::new(1.5, Rgb::WHITE, Rgb::WHITE);
        // Head on, each face reflects 4%: the pane 2·0.04/1.04 = 7.69%.
        assert!((pane.reflectance(1.0) - 0.08 / 1.04).abs() < 1e-6);
        let wo = Vec3::new(0.6, 0.0, -0.8);
        let through = pane.sample(wo, 0.99).unwrap();
        assert!(through.delta && through.wi == -wo && through.weight == Rgb::WHITE);
        let back = pane.sample(wo, 0.0).unwrap();
        assert_eq!(back.wi, mirror(wo));
        assert!((back.pdf - pane.reflectance(0.8)).abs() < 1e-6);
        assert!((through.pdf + back.pdf - 1.0).abs() < 1e-6);
    }
}
