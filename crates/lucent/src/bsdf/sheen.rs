//! Sheen: the soft rim of cloth and dust, glTF's `KHR_materials_sheen` layer — Estevez &
//! Kulla's "Charlie" distribution of fibres (2017, "Production Friendly Microfacet Sheen
//! BRDF") with Neubelt & Pettineo's visibility (2013):
//! `f = color·D(h)·V`, `D = (2 + 1/α)·sin^(1/α)θh / 2π`, `V = 1/(4(N·L + N·V − N·L·N·V))`,
//! `α = roughness²`. Sampled by the cosine.
//!
//! The layer below the sheen keeps `1 − max(color)·E(μ)` of its light ([`SheenAlbedo`], the
//! specification's albedo scaling, taken at the viewer's angle).

use std::f32::consts::TAU;

use glam::{Vec2, Vec3};

use super::BsdfSample;
use super::lambert::{cosine_pdf, sample_cosine};
use crate::Rgb;

/// The smallest sheen roughness: the distribution's exponent `1/α` grows without bound.
const ALPHA_MIN: f32 = 1e-3;

/// The sheen lobe at a surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sheen {
    /// The sheen colour.
    pub color: Rgb,
    /// The perceptual sheen roughness (`α = roughness²`).
    pub roughness: f32,
}

/// `D·V·cos θL` of white sheen of roughness `roughness`.
fn lobe(roughness: f32, v: Vec3, l: Vec3) -> f32 {
    if v.z <= 0.0 || l.z <= 0.0 {
        return 0.0;
    }
    let Some(h) = (v + l).try_normalize() else {
        return 0.0;
    };
    let alpha = (roughness * roughness).max(ALPHA_MIN);
    let inv = 1.0 / alpha;
    let sin2 = (1.0 - h.z * h.z).max(0.0);
    let d = (2.0 + inv) * sin2.powf(0.5 * inv) / TAU;
    let vis = 1.0 / (4.0 * (l.z + v.z - l.z * v.z));
    let f = d * vis * l.z;
    if f.is_finite() { f } else { 0.0 }
}

impl Sheen {
    /// `f(V, L)·cos θL`.
    pub fn eval(&self, v: Vec3, l: Vec3) -> Rgb {
        self.color * lobe(self.roughness, v, l)
    }

    /// The cosine density.
    pub fn pdf(&self, v: Vec3, l: Vec3) -> f32 {
        if v.z <= 0.0 || l.z <= 0.0 {
            0.0
        } else {
            cosine_pdf(l)
        }
    }

    /// A cosine-distributed direction.
    pub fn sample(&self, v: Vec3, u: Vec2) -> Option<BsdfSample> {
        if v.z <= 0.0 {
            return None;
        }
        let l = sample_cosine(u)?;
        BsdfSample::of_mixture(l, self.eval(v, l), self.pdf(v, l))
    }
}

/// Cosines and roughnesses the albedo is tabulated at.
const N: usize = 32;

/// The directional albedo `E(μ, r) = ∫ D·V·cos θL dωL` of white sheen, tabulated at 32 cosines
/// and 32 roughnesses from 0 to 1 by the midpoint rule (the specification's lookup table,
/// computed rather than copied).
#[derive(Clone, Debug, PartialEq)]
pub struct SheenAlbedo {
    table: Vec<f32>,
}

impl Default for SheenAlbedo {
    fn default() -> Self {
        Self::new()
    }
}

impl SheenAlbedo {
    /// The table, integrated now (a few milliseconds).
    pub fn new() -> Self {
        let steps = 48;
        let mut table = Vec::with_capacity(N * N);
        for ri in 0..N {
            let r = ri as f32 / (N - 1) as f32;
            for mi in 0..N {
                let mu = (mi as f32 / (N - 1) as f32).max(1e-3);
                let v = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
                // ∫ f cos dω = ∫∫ lobe(θ, φ) sin θ dθ dφ, in (cos θ, φ): ∫₀¹∫₀^2π lobe dφ dcos.
                let mut sum = 0.0f64;
                for a in 0..steps {
                    let c = (a as f32 + 0.5) / steps as f32;
                    let s = (1.0 - c * c).sqrt();
                    for b in 0..2 * steps {
                        let phi = (b as f32 + 0.5) / (2 * steps) as f32 * TAU;
                        let l = Vec3::new(s * phi.cos(), s * phi.sin(), c);
                        sum += f64::from(lobe(r, v, l));
                    }
                }
                let e = sum * f64::from(TAU) / (steps * 2 * steps) as f64;
                table.push((e as f32).min(1.0));
            }
        }
        Self { table }
    }

    /// `E(μ, r)`, bilinearly interpolated.
    pub fn albedo(&self, cos: f32, roughness: f32) -> f32 {
        let x = cos.clamp(0.0, 1.0) * (N - 1) as f32;
        let y = roughness.clamp(0.0, 1.0) * (N - 1) as f32;
        let (i, j) = ((x as usize).min(N - 2), (y as usize).min(N - 2));
        let (fx, fy) = (x - i as f32, y - j as f32);
        let at = |j: usize, i: usize| self.table[j * N + i];
        let a = at(j, i) * (1.0 - fx) + at(j, i + 1) * fx;
        let b = at(j + 1, i) * (1.0 - fx) + at(j + 1, i + 1) * fx;
        a * (1.0 - fy) + b * fy
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_albedo_is_below_one_and_rises_towards_grazing() {
        let e = SheenAlbedo::new();
        for r in [0.2f32, 0.5, 1.0] {
            let (head, grazing) = (e.albedo(1.0, r), e.albedo(0.1, r));
            assert!(
                head > 0.0 && head < 1.0 && grazing < 1.0,
                "{r}: {head} {grazing}"
            );
        }
        // Against a direct Monte Carlo estimate by cosine sampling.
        let sheen = Sheen {
            color: Rgb::WHITE,
            roughness: 0.5,
        };
        let v = Vec3::new(0.6, 0.0, 0.8);
        let n = 200_000u64;
        let mut sum = 0.0f64;
        for i in 0..n {
            let u = Vec2::new(
                (i as f32 + 0.5) / n as f32,
                ((i * 7919) % n) as f32 / n as f32,
            );
            if let Some(s) = sheen.sample(v, u) {
                sum += f64::from(s.weight.r);
            }
        }
        let mc = (sum / n as f64) as f32;
        assert!(
            (mc - e.albedo(0.8, 0.5)).abs() < 0.01,
            "{mc} vs {}",
            e.albedo(0.8, 0.5)
        );
    }
}
