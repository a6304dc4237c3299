//! Phase functions: how a medium scatters light, the volume's counterpart of a BSDF.
//!
//! Directions follow the path tracer's convention: `wo` points back along the arriving ray
//! (towards where the light goes), `wi` the way the path goes on (where the light comes
//! from). The scattering angle `θ` is the turn from the ray's direction, `−wo`, to `wi`:
//! `cos θ = −wo·wi`, so a forward-scattering medium keeps the path going its way. A phase
//! function is a density over the sphere: it integrates to 1, and its sample's weight (value
//! over density) is 1.

use crate::bsdf::frame::Frame;
use glam::{Vec2, Vec3};
use std::f32::consts::PI;

/// The Henyey–Greenstein phase function,
/// `p(θ) = (1 − g²) / (4π·(1 + g² − 2g·cos θ)^{3/2})`:
/// `g = 0` is isotropic, `g > 0` scatters forward, `g < 0` back; `g` is the mean cosine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HenyeyGreenstein {
    /// The mean cosine of the scattering angle, in `(−1, 1)`.
    pub g: f32,
}

/// The largest `|g|`: at ±1 the function is a delta, which the density would not describe.
pub const MAX_G: f32 = 0.999;

impl HenyeyGreenstein {
    /// The phase function with mean cosine `g`, clamped to `±MAX_G`.
    pub fn new(g: f32) -> Self {
        Self {
            g: g.clamp(-MAX_G, MAX_G),
        }
    }

    /// The density for light arriving from `wi` and leaving towards `wo` (both unit, pointing
    /// away from the scattering point).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> f32 {
        hg(self.g, -wo.dot(wi))
    }

    /// A direction `wi` drawn in proportion to the density, with `u` uniform in `[0, 1)²`; and
    /// its density.
    pub fn sample(&self, wo: Vec3, u: Vec2) -> (Vec3, f32) {
        let g = self.g;
        // The inverse of the cumulative distribution of cos θ (θ from the direction of travel).
        let cos_theta = if g.abs() < 1e-3 {
            1.0 - 2.0 * u.x
        } else {
            let s = (1.0 - g * g) / (1.0 + g - 2.0 * g * u.x);
            ((1.0 + g * g - s * s) / (2.0 * g)).clamp(-1.0, 1.0)
        };
        let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
        let phi = 2.0 * PI * u.y;
        let wi = Frame::from_normal(-wo).to_world(Vec3::new(
            sin_theta * phi.cos(),
            sin_theta * phi.sin(),
            cos_theta,
        ));
        (wi, hg(g, cos_theta))
    }
}

/// The HG density at `cos θ`, `θ` the scattering angle.
fn hg(g: f32, cos_theta: f32) -> f32 {
    let denom = 1.0 + g * g - 2.0 * g * cos_theta;
    (1.0 - g * g) / (4.0 * PI * denom * denom.max(0.0).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Fibonacci-sphere quadrature of `f` over all directions.
    fn integrate(f: impl Fn(Vec3) -> f32) -> f32 {
        let n = 200_000;
        let golden = PI * (3.0 - 5f32.sqrt());
        let mut sum = 0.0f64;
        for i in 0..n {
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
            let r = (1.0 - z * z).sqrt();
            let phi = golden * i as f32;
            sum += f64::from(f(Vec3::new(r * phi.cos(), r * phi.sin(), z)));
        }
        (sum * 4.0 * std::f64::consts::PI / f64::from(n)) as f32
    }

    #[test]
    fn integrates_to_one_and_its_mean_cosine_is_g() {
        let wo = Vec3::new(0.3, -0.5, 0.8).normalize();
        for g in [-0.7, -0.2, 0.0, 0.4, 0.8] {
            let p = HenyeyGreenstein::new(g);
            let total = integrate(|wi| p.eval(wo, wi));
            assert!((total - 1.0).abs() < 2e-3, "g {g}: ∫p = {total}");
            let mean_cos = integrate(|wi| p.eval(wo, wi) * -wo.dot(wi));
            assert!((mean_cos - g).abs() < 3e-3, "g {g}: mean cos {mean_cos}");
        }
    }

    #[test]
    fn forward_scattering_keeps_light_going_the_same_way() {
        // A ray travelling along +z (so wo = −z) goes on along +z far more often than back.
        let p = HenyeyGreenstein::new(0.9);
        assert!(p.eval(-Vec3::Z, Vec3::Z) > 10.0 * p.eval(-Vec3::Z, -Vec3::Z));
        let (wi, _) = p.sample(-Vec3::Z, Vec2::new(0.5, 0.3));
        assert!(wi.z > 0.9, "{wi}");
    }

    #[test]
    fn samples_follow_the_density() {
        // The histogram of sampled cosines against the density's integral over each bin.
        let wo = Vec3::new(-0.2, 0.9, 0.1).normalize();
        for g in [-0.6, 0.0, 0.5, 0.95] {
            let p = HenyeyGreenstein::new(g);
            let bins = 20;
            let mut counts = vec![0u32; bins];
            let n = 200_000u32;
            for i in 0..n {
                // A 2D low-discrepancy set (Hammersley).
                let u = Vec2::new(
                    (i as f32 + 0.5) / n as f32,
                    (i.reverse_bits() as f32) / 4294967296.0,
                );
                let (wi, pdf) = p.sample(wo, u);
                assert!((wi.length() - 1.0).abs() < 1e-4);
                assert!((pdf - p.eval(wo, wi)).abs() <= 1e-3 * pdf.max(1.0), "g {g}");
                let c = -wo.dot(wi);
                let b = (((c + 1.0) / 2.0 * bins as f32) as usize).min(bins - 1);
                counts[b] += 1;
            }
            for (b, &count) in counts.iter().enumerate() {
                // ∫ over the band of cosines [c0, c1]: 2π ∫ p dc.
                let (c0, c1) = (
                    b as f32 / bins as f32 * 2.0 - 1.0,
                    (b + 1) as f32 / bins as f32 * 2.0 - 1.0,
                );
                let steps = 200;
                let expected: f32 = (0..steps)
                    .map(|k| {
                        let c = c0 + (k as f32 + 0.5) / steps as f32 * (c1 - c0);
                        2.0 * PI * hg(p.g, c) * (c1 - c0) / steps as f32
                    })
                    .sum();
                let got = count as f32 / n as f32;
                assert!(
                    (got - expected).abs() < 2e-3 + 0.01 * expected,
                    "g {g} bin {b}: {got} vs {expected}"
                );
            }
        }
    }
}
