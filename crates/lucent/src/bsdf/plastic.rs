//! Plastic: a diffuse base under a smooth dielectric coat of index `eta` (Mitsuba 3's
//! `plastic`; the rough coat is [`super::rough_plastic`]).
//!
//! **The coat** reflects `F(cos θo)` as a mirror.
//!
//! **The base.** Light refracts through the coat (`1 − F(θi)`), meets the diffuse base of
//! reflectance `ρ`, and what comes back either leaves (`1 − F(θo)`, its radiance spread by
//! `1/η²` as it leaves the denser coat) or is reflected back down by the coat's inside, a share
//! `F_dr` of a diffuse flux ([`fresnel::diffuse_reflectance`] at `1/η`, Mitsuba's fit). Summing
//! the bounces gives `ρ/(1 − ρ·F_dr)` (`nonlinear = true`); Mitsuba's default divides by
//! `1 − F_dr` instead, so that a white base stays energy-conserving and a textured base keeps
//! its colours. So
//! `f_d = (1 − F(θi))·(1 − F(θo))·(1/η²)·ρ / (π·(1 − F_dr))`.
//!
//! **Sampling** picks the coat with probability proportional to `F(θo)·w` against the base's
//! `(1 − F(θo))·(1 − w)`, where `w = mean(specular)/(mean(ρ) + mean(specular))` is Mitsuba's
//! `specular_sampling_weight`; the base is sampled by the cosine.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::lambert::{cosine_pdf, sample_cosine};
use super::{BsdfSample, fresnel, mirror};
use crate::Rgb;

/// The plastic's parameters, with what every call derives from them.
pub(super) struct Plastic {
    diffuse: Rgb,
    eta: f32,
    specular: Rgb,
    /// Mitsuba's `nonlinear` switch: false divides the base by `1 − F_dr` (colours preserved),
    /// true by `1 − ρ·F_dr` (the physically summed bounces, darker and more saturated).
    nonlinear: bool,
    /// Mitsuba's `specular_sampling_weight`.
    w: f32,
}

/// The channel mean, Mitsuba's `Texture::mean` for a constant colour.
fn mean(c: Rgb) -> f32 {
    (c.r + c.g + c.b) / 3.0
}

impl Plastic {
    pub fn new(diffuse: Rgb, eta: f32, specular: Rgb, nonlinear: bool) -> Self {
        let (d, s) = (mean(diffuse).max(0.0), mean(specular).max(0.0));
        Self {
            diffuse,
            eta: fresnel::sane_eta(eta),
            specular,
            nonlinear,
            w: if d + s > 0.0 { s / (d + s) } else { 0.0 },
        }
    }

    /// True when only the coat's mirror is left (a black base).
    pub fn is_delta(&self) -> bool {
        self.diffuse.is_black()
    }

    /// The probability that `sample` picks the coat's mirror.
    pub fn delta_share(&self, wo: Vec3) -> f32 {
        if wo.z <= 0.0 {
            return 0.0;
        }
        self.lobe_probabilities(self.fresnel(wo.z))
            .map_or(0.0, |(spec, _)| spec)
    }

    /// The coat's Fresnel reflectance at `cos θ` (from outside).
    fn fresnel(&self, cos: f32) -> f32 {
        fresnel::dielectric(cos, self.eta).r
    }

    /// The probabilities of sampling the coat and the base, given `F(θo)`; `None` when both
    /// vanish (nothing to scatter).
    fn lobe_probabilities(&self, f_o: f32) -> Option<(f32, f32)> {
        let spec = f_o * self.w;
        let base = (1.0 - f_o) * (1.0 - self.w);
        let sum = spec + base;
        (sum > 0.0).then(|| (spec / sum, base / sum))
    }

    /// `ρ·(1/η²)/(1 − F_dr)` (or `/(1 − ρ F_dr)`): the base's value before the two coat
    /// transmittances and the `cos/π`.
    fn base(&self) -> Rgb {
        let fdr = fresnel::diffuse_reflectance(1.0 / self.eta);
        let inv_eta2 = 1.0 / (self.eta * self.eta);
        let d = self.diffuse;
        if self.nonlinear {
            // Past an albedo of 1 the series of inner bounces diverges: held at 1.
            let ch = |c: f32| {
                let c = c.min(1.0);
                c * inv_eta2 / (1.0 - c * fdr).max(1e-6)
            };
            Rgb::new(ch(d.r), ch(d.g), ch(d.b))
        } else {
            // A huge albedo under a coat of index near 0.001 would overflow.
            (d * (inv_eta2 / (1.0 - fdr).max(1e-6))).clamp(0.0, f32::MAX)
        }
    }

    /// `f_d·cos θi` (the coat's mirror is a Dirac lobe).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::BLACK;
        }
        let transmit = (1.0 - self.fresnel(wo.z)) * (1.0 - self.fresnel(wi.z));
        self.base() * (transmit * wi.z * FRAC_1_PI)
    }

    /// `P(base)·cos θi/π`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let Some((_, p_base)) = self.lobe_probabilities(self.fresnel(wo.z)) else {
            return 0.0;
        };
        p_base * cosine_pdf(wi)
    }

    /// The coat's mirror when `u_lobe < P(coat)`, else the base by the cosine.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let f_o = self.fresnel(wo.z);
        let (p_spec, p_base) = self.lobe_probabilities(f_o)?;
        if u_lobe < p_spec {
            return Some(BsdfSample {
                wi: mirror(wo),
                weight: self.specular * (f_o / p_spec),
                pdf: p_spec,
                delta: true,
            });
        }
        // The coat's Dirac lobe takes no part in the density of the base, so the weight is the
        // base's value over its own share.
        let wi = sample_cosine(u)?;
        let transmit = (1.0 - f_o) * (1.0 - self.fresnel(wi.z));
        Some(BsdfSample {
            wi,
            weight: self.base() * (transmit / p_base),
            pdf: p_base * cosine_pdf(wi),
            delta: false,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_smooth_coat_mirrors_f_and_passes_the_rest_to_the_base() {
        let b = Plastic::new(Rgb::gray(0.5), 1.5, Rgb::WHITE, false);
        let wo = Vec3::new(0.0, 0.6, 0.8);
        let f_o = fresnel::dielectric(0.8, 1.5).r;
        // Mitsuba's weight: w = 1/(0.5 + 1) = 2/3.
        let (ps, pb) = b.lobe_probabilities(f_o).unwrap();
        let want = f_o * 2.0 / 3.0 / (f_o * 2.0 / 3.0 + (1.0 - f_o) / 3.0);
        assert!((ps - want).abs() < 1e-6 && (ps + pb - 1.0).abs() < 1e-6);
        let s = b.sample(wo, 0.0, Vec2::splat(0.5)).unwrap();
        assert!(s.delta && s.wi == mirror(wo) && (s.weight.r - f_o / ps).abs() < 1e-5);
        // The base: (1 − F_i)(1 − F_o)/η² · ρ/(1 − F_dr) · cos/π.
        let wi = Vec3::new(0.3, 0.0, 0.954).normalize();
        let fdr = fresnel::diffuse_reflectance(1.0 / 1.5);
        let want = (1.0 - fresnel::dielectric(wi.z, 1.5).r) * (1.0 - f_o) / 2.25 * 0.5
            / (1.0 - fdr)
            * wi.z
            * FRAC_1_PI;
        assert!((b.eval(wo, wi).g - want).abs() < 1e-6);
    }

    #[test]
    fn a_white_smooth_plastic_returns_almost_all_the_light() {
        // With ρ = 1 the base returns (1 − F_o)·(1 − F_dr,exact)/(1 − F_dr,fit) and the coat
        // F_o: 1 up to the fit's error, whatever the angle.
        let b = Plastic::new(Rgb::WHITE, 1.5, Rgb::WHITE, false);
        for deg in [0.0f32, 40.0, 70.0, 85.0] {
            let a = deg.to_radians();
            let wo = Vec3::new(a.sin(), 0.0, a.cos());
            let f_o = b.fresnel(wo.z);
            // ∫ f_d cos dωi by the midpoint rule in μ = cos θi.
            let n = 4000;
            let base: f32 = (0..n)
                .map(|i| {
                    let mu = (i as f32 + 0.5) / n as f32;
                    let wi = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
                    b.eval(wo, wi).r * std::f32::consts::TAU / n as f32
                })
                .sum();
            let total = f_o + base;
            assert!((total - 1.0).abs() < 3e-3, "{deg}°: {total}");
        }
    }

    #[test]
    fn a_black_base_leaves_only_the_coat() {
        let b = Plastic::new(Rgb::BLACK, 1.5, Rgb::WHITE, false);
        assert!(b.is_delta());
        let s = b.sample(Vec3::Z, 0.999, Vec2::splat(0.3)).unwrap();
        assert!(s.delta && (s.weight.r - 0.04).abs() < 1e-6);
        assert_eq!(b.pdf(Vec3::Z, Vec3::Z), 0.0);
    }
}
