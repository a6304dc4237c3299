//! The Whitted material's coefficients as lobes a path tracer can sample, so that a scene made
//! for the Whitted integrator renders with global illumination:
//! - Lambert, `f = kd/π`;
//! - a normalised Phong lobe about the mirror direction `R(wo)`, `f = ks·(n+2)/(2π)·cosⁿα`
//!   with `cos α = wi·R(wo)` (Lafortune & Willems 1994's "modified Phong"; the `(n+2)/(2π)`
//!   makes its albedo exactly `ks` at normal incidence and less elsewhere);
//! - a mirror, a Dirac lobe of weight `kr`;
//! - a refraction through relative index `eta`, a Dirac lobe of weight `kt`, which mirrors
//!   instead under total internal reflection (as the Whitted integrator gives `kt` to the
//!   reflected ray).
//!
//! The coefficients are used as given — no Fresnel — and the albedo of a bounce is at most
//! `kd + ks + kr + kt` per channel. This BSDF would add energy where they sum past one;
//! [`crate::material::Material::bsdf`] scales them down together before they reach it.
//!
//! **Lobe choice.** Sampling picks a lobe with probability proportional to the largest channel
//! of its coefficient. The two glossy lobes are then weighted by their mixture density (so
//! `weight = eval/pdf` for every non-delta sample); a Dirac lobe's weight is its coefficient
//! over its probability. The Phong lobe is sampled exactly: `cos α = u^(1/(n+1))`, `φ = 2πu'`
//! about `R(wo)`, density `(n+1)/(2π)·cosⁿα`; samples below the horizon are lost.
//!
//! **Sides.** With `kt = 0` the material is one-sided like every reflector here. With `kt > 0`
//! it must take the unflipped frame (it transmits), so the reflective lobes act on whichever
//! side `wo` is, as the Whitted integrator shades both sides of glass, and the refraction uses
//! `1/eta` from the inside. Refracted radiance is scaled by `1/η'²` ([`Transport`]).

use std::f32::consts::{FRAC_1_PI, TAU};

use glam::{Vec2, Vec3};

use super::frame::Frame;
use super::lambert::sample_cosine;
use super::{BsdfSample, Transport, fresnel, mirror};
use crate::Rgb;

/// The lobes in sampling order.
const DIFFUSE: usize = 0;
const PHONG: usize = 1;
const MIRROR: usize = 2;
const REFRACT: usize = 3;

/// The Classic material's parameters.
pub(super) struct Classic {
    kd: Rgb,
    ks: Rgb,
    /// The Phong exponent, at least 0.
    n: f32,
    kr: Rgb,
    kt: Rgb,
    eta: f32,
    /// The lobes' selection probabilities, or `None` when every coefficient is black.
    p: Option<[f32; 4]>,
}

impl Classic {
    pub fn new(kd: Rgb, ks: Rgb, shininess: f32, kr: Rgb, kt: Rgb, eta: f32) -> Self {
        let weights = [kd, ks, kr, kt].map(|c| c.max_channel().max(0.0));
        let sum: f32 = weights.iter().sum();
        Self {
            kd,
            ks,
            // NaN and negative exponents become 0, a uniform lobe.
            n: if shininess > 0.0 {
                shininess.min(1e7)
            } else {
                0.0
            },
            kr,
            kt,
            eta: fresnel::sane_eta(eta),
            p: (sum > 0.0 && sum.is_finite()).then(|| weights.map(|w| w / sum)),
        }
    }

    /// True when only the mirror and refraction lobes are left.
    pub fn is_delta(&self) -> bool {
        self.kd.is_black() && self.ks.is_black()
    }

    /// The probability that `sample` picks the mirror or the refraction lobe.
    pub fn delta_share(&self) -> f32 {
        self.p.map_or(0.0, |p| p[MIRROR] + p[REFRACT])
    }

    fn two_sided(&self) -> bool {
        !self.kt.is_black()
    }

    /// Whether the reflective lobes link `wo` and `wi`: both on the front side, or, for the
    /// two-sided (transmitting) material, both on the same side.
    fn reflects(&self, wo: Vec3, wi: Vec3) -> bool {
        if self.two_sided() {
            wo.z * wi.z > 0.0
        } else {
            wo.z > 0.0 && wi.z > 0.0
        }
    }

    /// `cos α = wi·R(wo)` (clamped to 1 against rounding), where `R(wo)` mirrors `wo` about `z`
    /// and so lies on `wo`'s side whichever that is.
    fn cos_alpha(wo: Vec3, wi: Vec3) -> f32 {
        wi.dot(mirror(wo)).min(1.0)
    }

    /// `(kd/π + ks·(n+2)/(2π)·cosⁿα)·|cos θi|`, on the reflecting side.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if !self.reflects(wo, wi) {
            return Rgb::BLACK;
        }
        let cos_i = wi.z.abs();
        let mut f = self.kd * (cos_i * FRAC_1_PI);
        let c = Self::cos_alpha(wo, wi);
        if c > 0.0 && !self.ks.is_black() {
            f += self.ks * ((self.n + 2.0) / TAU * c.powf(self.n) * cos_i);
        }
        f
    }

    /// `P(diffuse)·|cos θi|/π + P(Phong)·(n+1)/(2π)·cosⁿα`, on the reflecting side.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        let Some(p) = self.p else {
            return 0.0;
        };
        if !self.reflects(wo, wi) {
            return 0.0;
        }
        let mut pdf = p[DIFFUSE] * wi.z.abs() * FRAC_1_PI;
        let c = Self::cos_alpha(wo, wi);
        if c > 0.0 && p[PHONG] > 0.0 {
            pdf += p[PHONG] * (self.n + 1.0) / TAU * c.powf(self.n);
        }
        pdf
    }

    /// The lobe `u_lobe` falls in; the last lobe with a share catches rounding at the top.
    fn pick(p: &[f32; 4], u_lobe: f32) -> usize {
        let mut acc = 0.0;
        let mut last = 0;
        for (i, &pi) in p.iter().enumerate() {
            if pi <= 0.0 {
                continue;
            }
            acc += pi;
            last = i;
            if u_lobe < acc {
                return i;
            }
        }
        last
    }

    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2, mode: Transport) -> Option<BsdfSample> {
        let p = self.p?;
        if wo.z == 0.0 || (!self.two_sided() && wo.z < 0.0) {
            return None;
        }
        let side = wo.z.signum();
        let lobe = Self::pick(&p, u_lobe);
        let delta = |wi: Vec3, weight: Rgb| BsdfSample {
            wi,
            weight: weight * (1.0 / p[lobe]),
            pdf: p[lobe],
            delta: true,
        };
        let wi = match lobe {
            DIFFUSE => {
                let w = sample_cosine(u)?;
                Vec3::new(w.x, w.y, w.z * side)
            }
            PHONG => {
                let cos_a = u.x.powf(1.0 / (self.n + 1.0));
                let sin_a = (1.0 - cos_a * cos_a).max(0.0).sqrt();
                let (sin_phi, cos_phi) = (TAU * u.y).sin_cos();
                let local = Vec3::new(sin_a * cos_phi, sin_a * sin_phi, cos_a);
                Frame::from_normal(mirror(wo)).to_world(local).normalize()
            }
            MIRROR => return Some(delta(mirror(wo), self.kr)),
            _ => {
                debug_assert_eq!(lobe, REFRACT);
                let f = fresnel::dielectric(wo.z, self.eta);
                if f.is_total() {
                    // Total internal reflection: the transmitted share is mirrored.
                    return Some(delta(mirror(wo), self.kt));
                }
                let scale = match mode {
                    Transport::Radiance => f.eta_ti * f.eta_ti,
                    Transport::Importance => 1.0,
                };
                let wi = fresnel::refract(wo, Vec3::Z, &f).normalize();
                return Some(delta(wi, self.kt * scale));
            }
        };
        if !self.reflects(wo, wi) {
            return None;
        }
        BsdfSample::of_mixture(wi, self.eval(wo, wi), self.pdf(wo, wi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn glass(kt: Rgb, kr: Rgb) -> Classic {
        Classic::new(Rgb::BLACK, Rgb::BLACK, 0.0, kr, kt, 1.5)
    }

    #[test]
    fn lobes_are_picked_by_their_largest_channel() {
        let b = Classic::new(
            Rgb::new(0.1, 0.4, 0.2),
            Rgb::gray(0.2),
            10.0,
            Rgb::new(0.0, 0.0, 0.2),
            Rgb::new(0.2, 0.0, 0.0),
            1.5,
        );
        let p = b.p.unwrap();
        assert!((p[DIFFUSE] - 0.4).abs() < 1e-6 && (p[PHONG] - 0.2).abs() < 1e-6);
        assert_eq!(Classic::pick(&p, 0.0), DIFFUSE);
        assert_eq!(Classic::pick(&p, 0.5), PHONG);
        assert_eq!(Classic::pick(&p, 0.7), MIRROR);
        assert_eq!(Classic::pick(&p, 0.999_999_9), REFRACT);
        // A mirror sample's weight is its coefficient over its probability.
        let s = b
            .sample(Vec3::Z, 0.7, Vec2::ZERO, Transport::Radiance)
            .unwrap();
        assert!(s.delta && s.wi == Vec3::Z && (s.weight.b - 1.0).abs() < 1e-6);
    }

    #[test]
    fn the_phong_lobe_returns_ks_at_normal_incidence() {
        // ∫ (n+2)/(2π) cosⁿθ cos θ dω = 1 when the lobe is centred on the normal.
        for n in [0.0f32, 1.0, 10.0, 100.0] {
            let b = Classic::new(Rgb::BLACK, Rgb::gray(0.7), n, Rgb::BLACK, Rgb::BLACK, 1.0);
            let steps = 20_000;
            let albedo: f32 = (0..steps)
                .map(|i| {
                    let mu = (i as f32 + 0.5) / steps as f32;
                    let wi = Vec3::new((1.0 - mu * mu).sqrt(), 0.0, mu);
                    b.eval(Vec3::Z, wi).r * TAU / steps as f32
                })
                .sum();
            assert!((albedo - 0.7).abs() < 2e-3, "n {n}: {albedo}");
        }
    }

    #[test]
    fn refraction_obeys_snell_and_total_internal_reflection_mirrors_kt() {
        let b = glass(Rgb::gray(0.9), Rgb::BLACK);
        let a = 30f32.to_radians();
        let wo = Vec3::new(a.sin(), 0.0, a.cos());
        let s = b
            .sample(wo, 0.5, Vec2::ZERO, Transport::Importance)
            .unwrap();
        assert!(s.delta && s.wi.z < 0.0);
        assert!((a.sin() - 1.5 * s.wi.x.abs()).abs() < 1e-5);
        assert!((s.weight.r - 0.9).abs() < 1e-6, "importance is not scaled");
        let r = b.sample(wo, 0.5, Vec2::ZERO, Transport::Radiance).unwrap();
        assert!(
            (r.weight.r - 0.9 / 2.25).abs() < 1e-6,
            "radiance is, by 1/η²"
        );
        // From inside at 45°, beyond the critical 41.8°: mirrored, weight kt.
        let a = 45f32.to_radians();
        let wo = Vec3::new(a.sin(), 0.0, -a.cos());
        let s = b.sample(wo, 0.5, Vec2::ZERO, Transport::Radiance).unwrap();
        assert!(s.wi == mirror(wo) && (s.weight.r - 0.9).abs() < 1e-6);
    }

    #[test]
    fn without_kt_it_is_one_sided_and_with_kt_two_sided() {
        let opaque = Classic::new(Rgb::gray(0.5), Rgb::BLACK, 0.0, Rgb::BLACK, Rgb::BLACK, 1.5);
        let clear = Classic::new(
            Rgb::gray(0.5),
            Rgb::BLACK,
            0.0,
            Rgb::BLACK,
            Rgb::gray(0.5),
            1.5,
        );
        let (wo, wi) = (Vec3::new(0.0, 0.6, -0.8), Vec3::new(0.6, 0.0, -0.8));
        assert!(opaque.eval(wo, wi).is_black() && opaque.pdf(wo, wi) == 0.0);
        assert!(
            opaque
                .sample(wo, 0.1, Vec2::splat(0.4), Transport::Radiance)
                .is_none()
        );
        assert!(!clear.eval(wo, wi).is_black() && clear.pdf(wo, wi) > 0.0);
        let s = clear
            .sample(wo, 0.1, Vec2::splat(0.4), Transport::Radiance)
            .unwrap();
        assert!(s.wi.z < 0.0 && !s.delta);
    }
}
