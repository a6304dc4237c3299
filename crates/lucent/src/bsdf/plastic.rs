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

use super::{BsdfSample, fresnel};
use crate::Rgb;
use crate::lanes::{Real, V3};
use crate::sampling::warp::{cosine_hemisphere, cosine_hemisphere_pdf};

/// The plastic's parameters, with what every call derives from them.
pub(crate) struct Plastic {
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

/// A plastic's value and density for `(wo, wi)` without its base's colour, written once over
/// [`Real`] ([`value_and_pdf`]).
pub(crate) struct PlasticLight<R: Real> {
    /// Both directions above the surface (else value and density are 0).
    pub front: R::Mask,
    /// `(1 − F(θo))·(1 − F(θi))·cos θi/π`: the value is the base's colour times this.
    pub factor: R,
    /// `P(base)·cos θi/π`.
    pub pdf: R,
}

/// A plastic's sample without colours ([`sampled`]).
pub(crate) struct PlasticSample<R: Real> {
    /// There is a sample: the viewer above the surface, something to scatter, a direction off
    /// the rim.
    pub ok: R::Mask,
    /// The coat's mirror (a Dirac lobe, weight `specular·factor`); else the base (weight
    /// `base·factor`).
    pub coat: R::Mask,
    pub wi: V3<R>,
    pub factor: R,
    pub pdf: R,
}

/// `F(cos θ)` of the coat (from outside), for a sane index `eta`.
#[inline(always)]
fn coat_fresnel<R: Real>(cos: R, eta: R) -> R {
    fresnel::dielectric_of(cos, eta).r
}

/// The probabilities of sampling the coat and the base given `F(θo)` and the specular
/// sampling weight `w`, and where there is anything to sample (their sum positive).
#[inline(always)]
fn lobe_probabilities<R: Real>(f_o: R, w: R) -> (R::Mask, R, R) {
    let one = R::splat(1.0);
    let spec = f_o * w;
    let base = (one - f_o) * (one - w);
    let sum = spec + base;
    (sum.gt(R::splat(0.0)), spec / sum, base / sum)
}

/// The value's factor and the density for `(wo, wi)`, for a sane index `eta` and the specular
/// sampling weight `w`.
#[inline(always)]
pub(crate) fn value_and_pdf<R: Real>(eta: R, w: R, (wo, wi): (V3<R>, V3<R>)) -> PlasticLight<R> {
    let (zero, one) = (R::splat(0.0), R::splat(1.0));
    let f_o = coat_fresnel(wo.z, eta);
    let transmit = (one - f_o) * (one - coat_fresnel(wi.z, eta));
    let (some, _, p_base) = lobe_probabilities(f_o, w);
    PlasticLight {
        front: wo.z.gt(zero) & wi.z.gt(zero),
        factor: transmit * wi.z * R::splat(FRAC_1_PI),
        pdf: R::select(some, p_base * cosine_hemisphere_pdf(wi.z), zero),
    }
}

/// The coat's mirror when `u_lobe < P(coat)`, else the base by the cosine with `u`, for a sane
/// index `eta` and the specular sampling weight `w`.
#[inline(always)]
pub(crate) fn sampled<R: Real>(
    eta: R,
    w: R,
    wo: V3<R>,
    (u_lobe, (ux, uy)): (R, (R, R)),
) -> PlasticSample<R> {
    let (zero, one) = (R::splat(0.0), R::splat(1.0));
    let f_o = coat_fresnel(wo.z, eta);
    let (some, p_spec, p_base) = lobe_probabilities(f_o, w);
    let coat = u_lobe.lt(p_spec);
    let base_wi = cosine_hemisphere(ux, uy);
    let transmit = (one - f_o) * (one - coat_fresnel(base_wi.z, eta));
    // The coat's Dirac lobe takes no part in the density of the base, so the base's weight is
    // its value over its own share.
    let mirror = V3::new(-wo.x, -wo.y, wo.z);
    PlasticSample {
        ok: wo.z.gt(zero) & some & (coat | base_wi.z.gt(zero)),
        coat,
        wi: V3::select(coat, mirror, base_wi),
        factor: R::select(coat, f_o / p_spec, transmit / p_base),
        pdf: R::select(coat, p_spec, p_base * cosine_hemisphere_pdf(base_wi.z)),
    }
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
        let (some, spec, _) = lobe_probabilities(coat_fresnel(wo.z, self.eta), self.w);
        if some { spec } else { 0.0 }
    }

    /// `ρ·(1/η²)/(1 − F_dr)` (or `/(1 − ρ F_dr)`): the base's value before the two coat
    /// transmittances and the `cos/π`.
    pub(crate) fn base(&self) -> Rgb {
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

    /// The coat's index (made sane) and the specular sampling weight.
    pub(crate) fn eta_and_weight(&self) -> (f32, f32) {
        (self.eta, self.w)
    }

    /// `f_d·cos θi` (the coat's mirror is a Dirac lobe).
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        let l = value_and_pdf(self.eta, self.w, (wo.into(), wi.into()));
        if l.front {
            self.base() * l.factor
        } else {
            Rgb::BLACK
        }
    }

    /// `P(base)·cos θi/π`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let l = value_and_pdf(self.eta, self.w, (wo.into(), wi.into()));
        if l.front { l.pdf } else { 0.0 }
    }

    /// The coat's mirror when `u_lobe < P(coat)`, else the base by the cosine.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        let s = sampled(self.eta, self.w, wo.into(), (u_lobe, (u.x, u.y)));
        s.ok.then(|| BsdfSample {
            wi: s.wi.into(),
            weight: if s.coat {
                self.specular * s.factor
            } else {
                self.base() * s.factor
            },
            pdf: s.pdf,
            delta: s.coat,
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
        let (some, ps, pb) = lobe_probabilities(f_o, b.w);
        assert!(some);
        let want = f_o * 2.0 / 3.0 / (f_o * 2.0 / 3.0 + (1.0 - f_o) / 3.0);
        assert!((ps - want).abs() < 1e-6 && (ps + pb - 1.0).abs() < 1e-6);
        let s = b.sample(wo, 0.0, Vec2::splat(0.5)).unwrap();
        let mirror = Vec3::new(-wo.x, -wo.y, wo.z);
        assert!(s.delta && s.wi == mirror && (s.weight.r - f_o / ps).abs() < 1e-5);
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
            let f_o = coat_fresnel(wo.z, b.eta);
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
