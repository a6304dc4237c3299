//! Rough plastic: a diffuse base under a rough dielectric coat, as Mitsuba 3's `roughplastic`
//! computes it.
//!
//! **The coat** reflects like rough glass seen from outside, without its transmission lobe:
//! `f_s = specular·F(wo·h)·D(h)·G(wo, wi, h) / (4 cos θo cos θi)`.
//!
//! **The base.** Light that the coat transmits, a share `T(θi)`, meets the diffuse base of
//! reflectance `ρ`; of what comes back up, `T(θo)` leaves (its radiance spread by `1/η²` as it
//! leaves the denser coat) and the rest is reflected back down by the coat's inside, a share
//! `R_int` of a diffuse flux. So
//! `f_d = T(θi)·T(θo)·(1/η²)·ρ / (π·(1 − R_int))`, or with `nonlinear`, `ρ / (π·(1 − ρ·R_int))`
//! — the sum of the bounces, darker and more saturated; Mitsuba's default divides by
//! `1 − R_int` so that a textured base keeps its colours.
//!
//! `T(θ)` and `R_int` are the rough coat's own, not the smooth `1 − F`: masking makes a rough
//! coat reflect less than `F` at grazing angles and hand more to the base. Both come from the
//! rough dielectric's single-scattering lobes, integrated over its visible normals by
//! Gauss–Legendre quadrature when the material is built ([`RoughCoat::new`]):
//! - `T(θ) = ∫ (1 − F(wi·m))·G1(wt, m) dD_wi(m)` over the refracted directions `wt`, tabulated
//!   at 64 cosines from 0 to 1 and interpolated linearly, as Mitsuba does;
//! - `R_int = 2·mean over those cosines of μ·R(μ)`, with `R(μ) = ∫ F(wi·m)·G1(wr, m) dD_wi(m)`
//!   the reflectance from inside (index `1/η`, total internal reflection included) — Mitsuba's
//!   estimate of `2∫ R(μ) μ dμ`, the diffuse reflectance of the coat's inside.
//!
//! **Sampling** picks the coat with probability proportional to `(1 − T(θo))·w` against the
//! base's `T(θo)·(1 − w)`, `w = mean(specular)/(mean(ρ) + mean(specular))`; the coat by its
//! visible normals, the base by the cosine; both lobes can produce every direction, so a sample
//! is weighted by the whole value over the whole density.

use glam::{Vec2, Vec3};

use super::lambert::{cosine_pdf, sample_cosine};
use super::microfacet::Microfacet;
use super::{BsdfSample, fresnel};
use crate::Rgb;
use crate::optics::reflect;
use crate::special::gauss_legendre;

/// Cosines at which the coat's transmittance is tabulated (Mitsuba's
/// `MI_ROUGH_TRANSMITTANCE_RES`).
const TABLE: usize = 64;

/// A rough dielectric coat: its microfacets, its index, and its tabulated transmittance and
/// internal reflectance.
#[derive(Clone, Debug, PartialEq)]
pub struct RoughCoat {
    eta: f32,
    microfacet: Microfacet,
    /// `T(μ_i)` at `μ_i = i/63` (the first at 10⁻⁶).
    transmittance: [f32; TABLE],
    /// `R_int`, the coat's diffuse reflectance from inside.
    internal_reflectance: f32,
}

/// `∫ f(m) dD_wi(m)` over the visible normals of `facets` seen from `wi`: the sampling routine
/// applied to an `n × n` Gauss–Legendre grid of its unit square.
fn over_visible_normals(
    facets: Microfacet,
    wi: Vec3,
    n: usize,
    mut f: impl FnMut(Vec3) -> f64,
) -> f64 {
    let rule = gauss_legendre(n);
    let mut sum = 0.0;
    for &(x, wx) in &rule {
        for &(y, wy) in &rule {
            let u = Vec2::new((0.5 * x + 0.5) as f32, (0.5 * y + 0.5) as f32);
            let m = facets.sample_visible(wi, u);
            sum += f(m) * wx * wy;
        }
    }
    // The rule's weights sum to 2 on each axis of [−1, 1]; the unit square is a quarter of it.
    sum * 0.25
}

/// The quadrature's resolution: index ratios below 1 have total internal reflection, whose
/// edge needs more nodes (Mitsuba's 32 and 128).
fn resolution(eta: f32) -> usize {
    if eta > 1.0 { 32 } else { 128 }
}

/// The share of light arriving at `wi` that the coat of index `eta` transmits into the base.
fn transmittance(facets: Microfacet, wi: Vec3, eta: f32) -> f32 {
    over_visible_normals(facets, wi, resolution(eta), |m| {
        let f = fresnel::dielectric(wi.dot(m), eta);
        if f.is_total() {
            return 0.0;
        }
        let wt = fresnel::refract(wi, m, &f);
        if wt.z * wi.z >= 0.0 {
            return 0.0;
        }
        f64::from(facets.g1(wt, m) * (1.0 - f.r))
    }) as f32
}

/// The share of light arriving at `wi` that the coat of index `eta` reflects (single
/// scattering).
fn reflectance(facets: Microfacet, wi: Vec3, eta: f32) -> f32 {
    over_visible_normals(facets, wi, resolution(eta), |m| {
        let wr = reflect(-wi, m);
        if wr.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        f64::from(facets.g1(wr, m) * fresnel::dielectric(wi.dot(m), eta).r)
    }) as f32
}

impl RoughCoat {
    /// The coat of relative index `eta` (coat over outside) with microfacets `microfacet`,
    /// its tables integrated now (about 10⁶ facet samples: a few tens of milliseconds).
    pub fn new(microfacet: Microfacet, eta: f32) -> Self {
        let eta = fresnel::sane_eta(eta);
        let cosines = (0..TABLE).map(|i| (i as f32 / (TABLE - 1) as f32).max(1e-6));
        let direction = |mu: f32| Vec3::new((1.0 - mu * mu).max(0.0).sqrt(), 0.0, mu);
        let mut table = [0.0; TABLE];
        let mut internal = 0.0;
        for (i, mu) in cosines.enumerate() {
            table[i] = transmittance(microfacet, direction(mu), eta);
            internal += reflectance(microfacet, direction(mu), 1.0 / eta) * mu;
        }
        Self {
            eta,
            microfacet,
            transmittance: table,
            internal_reflectance: 2.0 * internal / TABLE as f32,
        }
    }

    /// The coat's index relative to the outside.
    pub fn eta(&self) -> f32 {
        self.eta
    }

    /// The coat's microfacets.
    pub fn microfacet(&self) -> Microfacet {
        self.microfacet
    }

    /// The coat's diffuse reflectance from inside, `R_int`.
    pub fn internal_reflectance(&self) -> f32 {
        self.internal_reflectance
    }

    /// `T(cos θ)` from the table, linearly interpolated (Mitsuba's `lerp_gather`).
    pub fn transmittance(&self, cos: f32) -> f32 {
        let x = cos.clamp(0.0, 1.0) * (TABLE - 1) as f32;
        let i = (x as usize).min(TABLE - 2);
        let w = x - i as f32;
        self.transmittance[i] * (1.0 - w) + self.transmittance[i + 1] * w
    }
}

/// The rough plastic at a surface point.
pub(super) struct RoughPlastic<'a> {
    diffuse: Rgb,
    specular: Rgb,
    nonlinear: bool,
    coat: &'a RoughCoat,
    /// Mitsuba's `specular_sampling_weight`.
    w: f32,
}

/// The channel mean, Mitsuba's `Texture::mean` for a constant colour.
fn mean(c: Rgb) -> f32 {
    (c.r + c.g + c.b) / 3.0
}

impl<'a> RoughPlastic<'a> {
    pub fn new(diffuse: Rgb, specular: Rgb, nonlinear: bool, coat: &'a RoughCoat) -> Self {
        let (d, s) = (mean(diffuse).max(0.0), mean(specular).max(0.0));
        Self {
            diffuse,
            specular,
            nonlinear,
            coat,
            w: if d + s > 0.0 { s / (d + s) } else { 0.0 },
        }
    }

    /// The probability of sampling the coat given `T(θo)`.
    fn p_coat(&self, t_o: f32) -> Option<f32> {
        let spec = (1.0 - t_o) * self.w;
        let base = t_o * (1.0 - self.w);
        let sum = spec + base;
        (sum > 0.0).then(|| spec / sum)
    }

    /// `f_d·cos θi + f_s·cos θi`.
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Rgb {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return Rgb::BLACK;
        }
        let c = self.coat;
        let g = c.microfacet;
        let h = (wo + wi).normalize();
        let f = fresnel::dielectric(wo.dot(h), c.eta).r;
        let coat = self.specular * (f * g.d(h) * g.g1_over_cos(wo, h) * g.g1(wi, h) * 0.25);
        let inv_eta2 = 1.0 / (c.eta * c.eta);
        let scale = c.transmittance(wo.z)
            * c.transmittance(wi.z)
            * inv_eta2
            * wi.z
            * std::f32::consts::FRAC_1_PI;
        let r = c.internal_reflectance;
        let d = self.diffuse;
        let base = if self.nonlinear {
            // Past an albedo of 1 the series of inner bounces diverges: held at 1.
            let ch = |x: f32| {
                let x = x.min(1.0);
                x / (1.0 - x * r).max(1e-6)
            };
            Rgb::new(ch(d.r), ch(d.g), ch(d.b))
        } else {
            d * (1.0 / (1.0 - r).max(1e-6))
        };
        coat + base * scale
    }

    /// `P(coat)·D(h)·G1(wo, h)/(4 cos θo) + P(base)·cos θi/π`.
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        if wo.z <= 0.0 || wi.z <= 0.0 {
            return 0.0;
        }
        let Some(p) = self.p_coat(self.coat.transmittance(wo.z)) else {
            return 0.0;
        };
        let g = self.coat.microfacet;
        let h = (wo + wi).normalize();
        p * g.d(h) * g.g1_over_cos(wo, h) * 0.25 + (1.0 - p) * cosine_pdf(wi)
    }

    /// The coat's visible facet when `u_lobe < P(coat)`, else the base by the cosine.
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let p = self.p_coat(self.coat.transmittance(wo.z))?;
        let wi = if u_lobe < p {
            reflect(-wo, self.coat.microfacet.sample_visible(wo, u))
        } else {
            sample_cosine(u)?
        };
        if wi.z <= 0.0 {
            return None;
        }
        BsdfSample::of_mixture(wi, self.eval(wo, wi), self.pdf(wo, wi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::microfacet::Distribution;

    #[test]
    fn a_nearly_smooth_coat_transmits_one_minus_fresnel() {
        let coat = RoughCoat::new(Microfacet::ggx(1e-3), 1.5);
        for cos in [1.0f32, 0.8, 0.5, 0.2] {
            let want = 1.0 - fresnel::dielectric(cos, 1.5).r;
            let got = coat.transmittance(cos);
            assert!((got - want).abs() < 3e-3, "cos {cos}: {got} vs {want}");
        }
        // The smooth coat's inside reflects its diffuse reflectance F_dr(1/η) (to the coarse
        // 64-point rule's error).
        let want = fresnel::diffuse_reflectance(1.0 / 1.5);
        let got = coat.internal_reflectance();
        assert!((got - want).abs() < 0.02, "{got} vs {want}");
    }

    #[test]
    fn the_table_is_the_rough_dielectrics_transmitted_share() {
        // T(θ) is what rough glass of the same facets refracts from θ, in importance mode (no
        // 1/η² on radiance): the mean weight of its refracted samples, by its own sampler.
        use crate::bsdf::{Bsdf, Transport};
        for kind in [Distribution::Ggx, Distribution::Beckmann] {
            for alpha in [0.1f32, 0.4] {
                let facets = Microfacet::isotropic(kind, alpha);
                let coat = RoughCoat::new(facets, 1.5);
                let glass = Bsdf::RoughDielectric {
                    eta: 1.5,
                    specular: Rgb::WHITE,
                    transmittance: Rgb::WHITE,
                    microfacet: facets,
                };
                for cos in [0.95f32, 0.6, 0.3] {
                    let wo = Vec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
                    let n = 100_000u64;
                    let mut sum = 0.0f64;
                    for i in 0..n {
                        let u = Vec2::new(
                            (i as f32 + 0.5) / n as f32,
                            ((i * 7919) % n) as f32 / n as f32,
                        );
                        let u_lobe = ((i * 104_729) % n) as f32 / n as f32;
                        if let Some(s) = glass.sample(wo, u_lobe, u, Transport::Importance)
                            && s.wi.z < 0.0
                        {
                            sum += f64::from(s.weight.g);
                        }
                    }
                    let mc = (sum / n as f64) as f32;
                    let t = coat.transmittance(cos);
                    assert!(
                        (t - mc).abs() < 0.01,
                        "{kind:?} α {alpha} cos {cos}: {t} vs {mc}"
                    );
                }
            }
        }
    }

    #[test]
    fn nonlinear_darkens_and_saturates_the_base() {
        let coat = RoughCoat::new(Microfacet::isotropic(Distribution::Beckmann, 0.2), 1.49);
        let base = Rgb::new(0.8, 0.4, 0.1);
        let linear = RoughPlastic::new(base, Rgb::WHITE, false, &coat);
        let nonlinear = RoughPlastic::new(base, Rgb::WHITE, true, &coat);
        let (wo, wi) = (Vec3::new(0.3, 0.0, 0.95).normalize(), Vec3::Z);
        let (a, b) = (linear.eval(wo, wi), nonlinear.eval(wo, wi));
        assert!(b.r < a.r && b.g < a.g && b.b < a.b);
        assert!(b.r / b.b > a.r / a.b, "more saturated");
    }
}
