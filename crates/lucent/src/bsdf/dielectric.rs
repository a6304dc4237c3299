//! Smooth glass: a boundary between two dielectrics that mirrors a share `F` of the light and
//! refracts the rest by Snell's law, with total internal reflection (Mitsuba 3 `dielectric`).
//!
//! Both lobes are Dirac deltas. Sampling picks reflection with probability `F` and refraction
//! with `1 − F`, so the Fresnel factor cancels from the weights: the mirror's weight is
//! `specular`, the refraction's `transmittance`, times `1/η'²` when carrying radiance (η' the
//! index being entered over the index being left, `1/eta_ti²`).

use glam::Vec3;

use super::{BsdfSample, Transport, fresnel, mirror};
use crate::Rgb;

/// The smooth dielectric's parameters.
pub(super) struct Dielectric {
    eta: f32,
    specular: Rgb,
    transmittance: Rgb,
}

impl Dielectric {
    pub fn new(eta: f32, specular: Rgb, transmittance: Rgb) -> Self {
        Self {
            eta: fresnel::sane_eta(eta),
            specular,
            transmittance,
        }
    }

    /// Reflect when `u_lobe < F`, refract otherwise; `wo.z < 0` is inside, where the relative
    /// index is `1/eta`.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, mode: Transport) -> Option<BsdfSample> {
        if wo.z == 0.0 {
            return None;
        }
        let f = fresnel::dielectric(wo.z, self.eta);
        // Strictly less: F = 0 (index-matched) must never reflect with probability 0.
        if u_lobe < f.r {
            return Some(BsdfSample {
                wi: mirror(wo),
                weight: self.specular,
                pdf: f.r,
                delta: true,
            });
        }
        let scale = match mode {
            Transport::Radiance => f.eta_ti * f.eta_ti,
            Transport::Importance => 1.0,
        };
        Some(BsdfSample {
            wi: fresnel::refract(wo, Vec3::Z, &f).normalize(),
            weight: self.transmittance * scale,
            pdf: 1.0 - f.r,
            delta: true,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glass() -> Dielectric {
        Dielectric::new(1.5, Rgb::WHITE, Rgb::WHITE)
    }

    fn at(deg: f32, inside: bool) -> Vec3 {
        let a = deg.to_radians();
        let z = if inside { -a.cos() } else { a.cos() };
        Vec3::new(a.sin(), 0.0, z)
    }

    #[test]
    fn from_inside_at_45_degrees_everything_is_reflected() {
        // 45° > asin(1/1.5) = 41.8°: total internal reflection, whatever u_lobe says.
        let wo = at(45.0, true);
        for u in [0.0, 0.5, 0.999_999] {
            let s = glass().sample(wo, u, Transport::Radiance).unwrap();
            assert_eq!(s.wi, mirror(wo));
            assert!(s.pdf == 1.0 && s.weight == Rgb::WHITE && s.delta);
        }
    }

    #[test]
    fn the_split_between_reflection_and_refraction_is_f() {
        for (deg, inside) in [(0.0, false), (60.0, false), (85.0, false), (30.0, true)] {
            let wo = at(deg, inside);
            let f = fresnel::dielectric(wo.z, 1.5).r;
            // u_lobe just below F reflects, just above refracts; the pdfs are F and 1 − F.
            let r = glass().sample(wo, f * 0.999, Transport::Radiance).unwrap();
            let t = glass()
                .sample(wo, f * 1.001 + 1e-6, Transport::Radiance)
                .unwrap();
            assert!(r.wi.z * wo.z > 0.0 && (r.pdf - f).abs() < 1e-7);
            assert!(t.wi.z * wo.z < 0.0 && (t.pdf - (1.0 - f)).abs() < 1e-7);
            // The share that reflects among many evenly spread u_lobe is F.
            let n = 100_000;
            let reflected = (0..n)
                .filter(|&i| {
                    let u = (i as f32 + 0.5) / n as f32;
                    glass().sample(wo, u, Transport::Radiance).unwrap().wi.z * wo.z > 0.0
                })
                .count();
            assert!((reflected as f32 / n as f32 - f).abs() < 2e-5, "{deg}°");
        }
        // At normal incidence glass reflects 4%.
        assert!((fresnel::dielectric(1.0, 1.5).r - 0.04).abs() < 1e-6);
    }

    #[test]
    fn the_refracted_direction_obeys_snell() {
        for (deg, inside) in [(10.0, false), (45.0, false), (80.0, false), (30.0, true)] {
            let wo = at(deg, inside);
            let t = glass().sample(wo, 0.999, Transport::Radiance).unwrap();
            let (eta_o, eta_i) = if inside { (1.5, 1.0) } else { (1.0, 1.5) };
            let sin_o = (wo.x * wo.x + wo.y * wo.y).sqrt();
            let sin_i = (t.wi.x * t.wi.x + t.wi.y * t.wi.y).sqrt();
            assert!(
                (eta_o * sin_o - eta_i * sin_i).abs() < 1e-5,
                "{deg}° inside {inside}"
            );
            assert!((t.wi.length() - 1.0).abs() < 1e-6 && t.wi.x < 0.0);
        }
    }

    #[test]
    fn radiance_and_importance_differ_by_eta_squared_on_refraction() {
        for (wo, eta2) in [
            (at(30.0, false), 1.5f32 * 1.5),
            (at(20.0, true), 1.0 / (1.5 * 1.5)),
        ] {
            let r = glass().sample(wo, 0.99, Transport::Radiance).unwrap();
            let i = glass().sample(wo, 0.99, Transport::Importance).unwrap();
            assert_eq!(r.wi, i.wi);
            assert!((i.weight.r / r.weight.r - eta2).abs() < 1e-5);
            // Reflection does not depend on the mode.
            let r = glass().sample(wo, 0.0, Transport::Radiance).unwrap();
            let i = glass().sample(wo, 0.0, Transport::Importance).unwrap();
            assert_eq!(r, i);
        }
    }

    #[test]
    fn index_matched_glass_lets_everything_through_unbent() {
        let b = Dielectric::new(1.0, Rgb::WHITE, Rgb::WHITE);
        let wo = at(50.0, false);
        let s = b.sample(wo, 0.0, Transport::Radiance).unwrap();
        assert!((s.wi + wo).length() < 1e-6 && s.pdf == 1.0 && s.weight == Rgb::WHITE);
    }
}
