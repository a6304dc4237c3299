//! Plastic: a diffuse base under a dielectric coat of index `eta`. A smooth coat (`alpha = 0`)
//! is Mitsuba 3's `plastic` with `nonlinear = false`; a rough coat (`alpha > 0`) follows its
//! `roughplastic`, with one approximation (below).
//!
//! **The coat** reflects `F(cos θo)` specularly: a mirror when smooth, the rough-conductor form
//! with the dielectric's Fresnel when rough,
//! `f_s = specular·F(wo·h)·D(h)·G1(wo, h)·G1(wi, h) / (4 cos θo cos θi)`.
//!
//! **The base.** Light refracts through the coat (`1 − F(θi)`), meets the diffuse base of
//! reflectance `ρ`, and what comes back either leaves (`1 − F(θo)`, its radiance spread by
//! `1/η²` as it leaves the denser coat) or is reflected back down by the coat's inside, a share
//! `F_dr` of a diffuse flux ([`fresnel::diffuse_reflectance`] at `1/η`, Mitsuba's fit). Summing
//! the bounces gives `ρ/(1 − ρ·F_dr)`; Mitsuba's default (`nonlinear = false`) divides by
//! `1 − F_dr` instead, so that a white base stays energy-conserving and a textured base keeps
//! its colours. So
//! `f_d = (1 − F(θi))·(1 − F(θo))·(1/η²)·ρ / (π·(1 − F_dr))`.
//!
//! **Sampling** picks the coat with probability proportional to `F(θo)·w` against the base's
//! `(1 − F(θo))·(1 − w)`, where `w = mean(specular)/(mean(ρ) + mean(specular))` is Mitsuba's
//! `specular_sampling_weight`; the base is sampled by the cosine.
//!
//! **The rough coat's approximation.** Mitsuba's `roughplastic` uses, in place of
//! `1 − F(θ)`, the transmittance of the *rough* coat tabulated by numerical integration per
//! (α, η), and a rough internal reflectance in place of `F_dr`. Here the smooth `1 − F(θ)` and
//! `F_dr` are used for any α: exact as α → 0 and close to Mitsuba for small α. For rough coats
//! the difference is at grazing angles: there masking makes the rough coat reflect less than
//! `F(θ)`, and Mitsuba hands that light to the base while this model does not, so rough
//! plastic's rims come out darker than Mitsuba's. It never creates energy: a white base and
//! coat return at most `1 + 0.2%` (the `F_dr` fit's error), measured by the energy test in
//! `bsdf/tests.rs`; at α = 1 they return 0.97 head-on, falling towards grazing angles.

use std::f32::consts::FRAC_1_PI;

use glam::{Vec2, Vec3};

use super::lambert::{cosine_pdf, sample_cosine};
use super::microfacet::Ggx;
use super::{BsdfSample, fresnel, mirror};
use crate::Rgb;
use crate::optics::reflect;

/// Mitsuba's `nonlinear` switch: false divides the base by `1 − F_dr` (colours preserved),
/// true by `1 − ρ·F_dr` (the physically summed bounces, darker and more saturated).
const NONLINEAR: bool = false;

/// The plastic's parameters, with what every call derives from them.
pub(super) struct Plastic {
    diffuse: Rgb,
    eta: f32,
    specular: Rgb,
    /// `None` for the smooth coat.
    ggx: Option<Ggx>,
    /// Mitsuba's `specular_sampling_weight`.
    w: f32,
}

/// The channel mean, Mitsuba's `Texture::mean` for a constant colour.
fn mean(c: Rgb) -> f32 {
    (c.r + c.g + c.b) / 3.0
}

impl Plastic {
    pub fn new(diffuse: Rgb, eta: f32, specular: Rgb, alpha: f32) -> Self {
        let (d, s) = (mean(diffuse).max(0.0), mean(specular).max(0.0));
        Self {
            diffuse,
            eta: fresnel::sane_eta(eta),
            specular,
            // alpha ≤ 0 (or NaN) is the smooth coat.
            ggx: (alpha > 0.0).then(|| Ggx::new(alpha)),
            w: if d + s > 0.0 { s / (d + s) } else { 0.0 },
        }
    }

    /// True when only the smooth coat's mirror is left (a black base).
    pub fn is_delta(&self) -> bool {
        self.ggx.is_none() && self.diffuse.is_black()
    }

    /// The probability that `sample` picks the smooth coat's mirror (0 for a rough coat, whose
    /// lobe is not a Dirac delta).
    pub fn delta_share(&self, wo: Vec3) -> f32 {
        if self.ggx.is_some() || wo.z <= 0.0 {
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
        if NONLINEAR {
            let ch = |c: f32| c * inv_eta2 / (1.0 - c * fdr).max(1e-6);
            Rgb::new(ch(d.r), ch(d.g), ch(d.b))
        } else {
            d * (inv_eta2 / (1.0 - fdr).max(1e-6))
        }
    }

    /// The rough coat's `f_s·cos θi` and its sampling density for the half vector of `wo, wi`
    /// (both on the front side).
    fn coat(&self, g: Ggx, wo: Vec3, wi: Vec3) -> (Rgb, f32) {
        let h = (wo + wi).normalize();
        let d_g1o = g.d(h) * g.g1_over_cos(wo, h) * 0.25;
        let value = self.specular * (self.fresnel(wo.dot(h)) * d_g1o * g.g1(wi, h));
        (value, d_g1o)
    }

    /// `f_d·cos θi` plus, for the rough coat, `f_s·cos θi`.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::BLACK;
        }
        let transmit = (1.0 - self.fresnel(wo.z)) * (1.0 - self.fresnel(wi.z));
        let diffuse = self.base() * (transmit * wi.z * FRAC_1_PI);
        match self.ggx {
            Some(g) => diffuse + self.coat(g, wo, wi).0,
            None => diffuse,
        }
    }

    /// `P(base)·cos θi/π`, plus `P(coat)·D(h)·G1(wo, h)/(4 cos θo)` for the rough coat.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let Some((p_spec, p_base)) = self.lobe_probabilities(self.fresnel(wo.z)) else {
            return 0.0;
        };
        let base = p_base * cosine_pdf(wi);
        match self.ggx {
            Some(g) => base + p_spec * self.coat(g, wo, wi).1,
            None => base,
        }
    }

    /// The coat (mirror or visible facet) when `u_lobe < P(coat)`, else the base by the cosine.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let f_o = self.fresnel(wo.z);
        let (p_spec, p_base) = self.lobe_probabilities(f_o)?;
        let pick_coat = u_lobe < p_spec;
        let Some(g) = self.ggx else {
            if pick_coat {
                return Some(BsdfSample {
                    wi: mirror(wo),
                    weight: self.specular * (f_o / p_spec),
                    pdf: p_spec,
                    delta: true,
                });
            }
            // The smooth coat's Dirac lobe takes no part in the density of the base, so the
            // weight is the base's value over its own share.
            let wi = sample_cosine(u)?;
            let transmit = (1.0 - f_o) * (1.0 - self.fresnel(wi.z));
            return Some(BsdfSample {
                wi,
                weight: self.base() * (transmit / p_base),
                pdf: p_base * cosine_pdf(wi),
                delta: false,
            });
        };
        let wi = if pick_coat {
            reflect(-wo, g.sample_visible(wo, u))
        } else {
            sample_cosine(u)?
        };
        if wi.z <= 0.0 {
            return None;
        }
        // Both lobes can produce every direction: weight by the mixture (one-sample MIS).
        BsdfSample::of_mixture(wi, self.eval(wo, wi), self.pdf(wo, wi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_smooth_coat_mirrors_f_and_passes_the_rest_to_the_base() {
        let b = Plastic::new(Rgb::gray(0.5), 1.5, Rgb::WHITE, 0.0);
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
        let b = Plastic::new(Rgb::WHITE, 1.5, Rgb::WHITE, 0.0);
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
        let b = Plastic::new(Rgb::BLACK, 1.5, Rgb::WHITE, 0.0);
        assert!(b.is_delta());
        let s = b.sample(Vec3::Z, 0.999, Vec2::splat(0.3)).unwrap();
        assert!(s.delta && (s.weight.r - 0.04).abs() < 1e-6);
        assert_eq!(b.pdf(Vec3::Z, Vec3::Z), 0.0);
    }
}
