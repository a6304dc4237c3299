//! Microfacet distributions: GGX (Trowbridge–Reitz) and Beckmann, isotropic or anisotropic,
//! with Smith masking and sampling of the visible normals for both.
//!
//! References: Walter, Marschner, Li & Torrance 2007, "Microfacet Models for Refraction through
//! Rough Surfaces" (D and G1 of both distributions, and the rational fit of Beckmann's G1 that
//! Mitsuba uses); Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based
//! BRDFs" (anisotropy by stretching, the distribution of visible normals); Heitz & d'Eon 2014,
//! "Importance Sampling Microfacet-Based BSDFs using the Distribution of Visible Normals"
//! (sampling visible slopes for α = 1, then stretching); Heitz 2018, "Sampling the GGX
//! Distribution of Visible Normals" (JCGT 7(4)), the GGX routine.
//!
//! All vectors are in the local frame: `z` is the macro-normal, `x` the tangent along which
//! the roughness is `alpha_u` and `y` the bitangent (`alpha_v`), as Mitsuba 3 defines them.
//! Microfacet normals `m` lie in the upper hemisphere.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::ggx::{Facets, Ggx};
use crate::lanes::{Real, V3};
use crate::special::{erf, erfinv};

/// The smallest roughness used: below it `D` peaks beyond what `f32` half vectors resolve
/// (Mitsuba clamps at the same 10⁻⁴; pbrt-v4 treats `α < 10⁻³` as smooth).
pub const ALPHA_MIN: f32 = 1e-4;
/// The largest roughness used; above it the surface is flat noise and stretched vectors lose
/// their `z` to rounding.
pub const ALPHA_MAX: f32 = 100.0;

/// The shape of the distribution of facet slopes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Distribution {
    /// Trowbridge–Reitz: long tails, the usual choice for real-time and glTF.
    #[default]
    Ggx,
    /// Gaussian slopes: shorter tails; Mitsuba's default.
    Beckmann,
}

impl Distribution {
    /// The name in scene files: `ggx` or `beckmann`.
    pub fn name(self) -> &'static str {
        match self {
            Distribution::Ggx => "ggx",
            Distribution::Beckmann => "beckmann",
        }
    }
}

/// A microfacet distribution of roughness `alpha_u` along the tangent and `alpha_v` along the
/// bitangent (equal for an isotropic surface).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Microfacet {
    kind: Distribution,
    alpha_u: f32,
    alpha_v: f32,
}

/// A roughness clamped to `[ALPHA_MIN, ALPHA_MAX]` (NaN becomes `ALPHA_MIN`).
fn clamp_alpha(alpha: f32) -> f32 {
    if alpha.is_nan() {
        ALPHA_MIN
    } else {
        alpha.clamp(ALPHA_MIN, ALPHA_MAX)
    }
}

impl Microfacet {
    /// A distribution of `kind` with roughness `alpha_u` (tangent) and `alpha_v` (bitangent),
    /// each clamped to `[ALPHA_MIN, ALPHA_MAX]`.
    pub fn new(kind: Distribution, alpha_u: f32, alpha_v: f32) -> Self {
        Self {
            kind,
            alpha_u: clamp_alpha(alpha_u),
            alpha_v: clamp_alpha(alpha_v),
        }
    }

    /// An isotropic distribution of `kind` and roughness `alpha`.
    pub fn isotropic(kind: Distribution, alpha: f32) -> Self {
        Self::new(kind, alpha, alpha)
    }

    /// Isotropic GGX of roughness `alpha`.
    pub fn ggx(alpha: f32) -> Self {
        Self::isotropic(Distribution::Ggx, alpha)
    }

    /// The kind of distribution.
    pub fn kind(self) -> Distribution {
        self.kind
    }

    /// The roughness along the tangent and the bitangent, after clamping.
    pub fn alphas(self) -> (f32, f32) {
        (self.alpha_u, self.alpha_v)
    }

    /// This distribution as GGX written once over [`Real`] (whatever its kind).
    #[inline(always)]
    pub fn as_ggx<R: Real>(self) -> Ggx<R> {
        Ggx {
            alpha_u: R::splat(self.alpha_u),
            alpha_v: R::splat(self.alpha_v),
        }
    }

    /// The mean of the two roughnesses, for what needs one number (the Whitted integrator's
    /// Phong exponent).
    pub fn mean_alpha(self) -> f32 {
        0.5 * (self.alpha_u + self.alpha_v)
    }

    /// `(m_x/α_u)² + (m_y/α_v)²`: the squared slope of `m` in the stretched configuration, times
    /// `m_z²`.
    fn stretched_xy(self, m: Vec3) -> f32 {
        let (x, y) = (m.x / self.alpha_u, m.y / self.alpha_v);
        x * x + y * y
    }

    /// The density of microfacet normals per unit solid angle, normalised so that the facets'
    /// projected area is the macro-surface's, `∫ D(m) cos θm dωm = 1`. With
    /// `s² = (m_x/α_u)² + (m_y/α_v)²`:
    /// - GGX: `D = 1 / (π α_u α_v (s² + m_z²)²)`, free of `tan` at grazing `m`;
    /// - Beckmann: `D = exp(−s²/m_z²) / (π α_u α_v m_z⁴)`.
    ///
    /// Zero for `m.z ≤ 0`.
    pub fn d(self, m: Vec3) -> f32 {
        if self.kind == Distribution::Ggx {
            return self.as_ggx().d(m.into());
        }
        if m.z <= 0.0 {
            return 0.0;
        }
        let s2 = self.stretched_xy(m);
        let norm = PI * self.alpha_u * self.alpha_v;
        let z2 = m.z * m.z;
        let d = (-s2 / z2).exp() / (norm * z2 * z2);
        if d.is_finite() { d } else { 0.0 }
    }

    /// `α²(v)·tan²θv·cos²θv = (α_u v_x)² + (α_v v_y)²`: the projected roughness of direction
    /// `v`, times its squared sine.
    fn projected(self, v: Vec3) -> f32 {
        let (x, y) = (self.alpha_u * v.x, self.alpha_v * v.y);
        x * x + y * y
    }

    /// Smith's masking of direction `v` (either side) for facets of normal `m`, zero when `v`
    /// sees the back of the facet (`(v·m)` and `v_z` of opposite signs):
    /// - GGX: `G1 = 2 / (1 + √(1 + α² tan²θv))`;
    /// - Beckmann: with `a = 1/(α tan θv)`, `G1 = 1/(1 + Λ(a))`,
    ///   `Λ(a) = (erf(a) − 1)/2 + e^(−a²)/(2a√π)`. Mitsuba uses Walter et al.'s rational fit
    ///   of it (within 0.35%); the exact function keeps the density of the visible normals,
    ///   which is sampled exactly, normalised, as multiple importance sampling needs.
    pub fn g1(self, v: Vec3, m: Vec3) -> f32 {
        self.g1_over_cos(v, m) * v.z.abs()
    }

    /// `G1(v, m) / |cos θv|`, which stays finite as `v` becomes grazing, where `G1` and
    /// `cos θv` both vanish: for GGX `2 / (|v_z| + √(v_z² + (α_u v_x)² + (α_v v_y)²))`.
    pub fn g1_over_cos(self, v: Vec3, m: Vec3) -> f32 {
        if self.kind == Distribution::Ggx {
            return self.as_ggx().g1_over_cos(v.into(), m.into());
        }
        if v.dot(m) * v.z <= 0.0 {
            return 0.0;
        }
        let p = self.projected(v);
        let z = v.z.abs();
        if p <= 0.0 {
            return 1.0 / z;
        }
        // Beckmann: G1/z = 2/(z(1 + erf a) + z·e^(−a²)/(a√π)), and z/a = √p.
        let root = p.sqrt();
        let a = z / root;
        let tail = root * (-a * a).exp() * std::f32::consts::FRAC_2_SQRT_PI * 0.5;
        2.0 / (z * (1.0 + erf(a)) + tail)
    }

    /// The separable shadowing-masking term `G = G1(wo, m)·G1(wi, m)`, as Mitsuba uses.
    pub fn g(self, wo: Vec3, wi: Vec3, m: Vec3) -> f32 {
        self.g1(wo, m) * self.g1(wi, m)
    }

    /// A microfacet normal drawn from the normals visible from `v` (unit, `v.z ≥ 0`: a caller
    /// arriving from below passes `−v`), with density [`Microfacet::visible_pdf`]: stretch `v`
    /// to the configuration where `α = 1`, sample there, and unstretch the normal.
    pub fn sample_visible(self, v: Vec3, u: Vec2) -> Vec3 {
        debug_assert!(
            v.z >= 0.0,
            "sample_visible wants v in the upper hemisphere, got {v}"
        );
        if self.kind == Distribution::Ggx {
            return self.as_ggx().sample_visible(v.into(), (u.x, u.y)).into();
        }
        let (au, av) = (self.alpha_u, self.alpha_v);
        let vh = Vec3::new(au * v.x, av * v.y, v.z.max(0.0)).normalize_or(Vec3::Z);
        // Beckmann: slopes of the unit configuration, seen from vh's azimuth, then rotated to
        // it and unstretched: m = (−x̃, −ỹ, 1)/|…|.
        let slope = beckmann_visible_slope_11(vh.z, u);
        let len = (vh.x * vh.x + vh.y * vh.y).sqrt();
        let (cos_phi, sin_phi) = if len > 0.0 {
            (vh.x / len, vh.y / len)
        } else {
            (1.0, 0.0)
        };
        let sx = (cos_phi * slope.x - sin_phi * slope.y) * au;
        let sy = (sin_phi * slope.x + cos_phi * slope.y) * av;
        Vec3::new(-sx, -sy, 1.0).normalize_or(Vec3::Z)
    }

    /// The density of [`Microfacet::sample_visible`] per unit solid angle of `m`, the
    /// distribution of visible normals `D_v(m) = G1(v, m)·max(0, v·m)·D(m) / cos θv`
    /// (Heitz 2014), for `v.z ≥ 0`.
    pub fn visible_pdf(self, v: Vec3, m: Vec3) -> f32 {
        Facets::visible_pdf(self, v.into(), m.into())
    }
}

/// A slope `(x̃, ỹ)` of the visible normals of the Beckmann distribution of roughness 1 seen
/// from a direction at `cos θ` (azimuth 0, tilted towards `+x`), after Heitz & d'Eon 2014.
///
/// A facet of slope `(x̃, ỹ)` is seen in proportion to `max(0, cot θ − x̃)`, so `ỹ` keeps its
/// Gaussian (`ỹ = erfinv(2u₂ − 1)`) and `x̃` has the density `∝ e^(−x̃²)·(cot θ − x̃)` on
/// `x̃ < cot θ`. In the variable `y = erf(x̃)` its cumulative distribution, times `2 tan θ`, is
/// `C(y) = 1 + y + tan θ·e^(−x̃²)/√π`, with `dC/dy = 1 − x̃ tan θ`. `C(y) = u₁·C(erf(cot θ))` is
/// solved by Newton's method kept inside a shrinking bracket (C rises monotonically).
fn beckmann_visible_slope_11(cos_theta: f32, u: Vec2) -> Vec2 {
    const INV_SQRT_PI: f32 = 0.564_189_6;
    let cos_theta = cos_theta.clamp(1e-6, 1.0);
    let sin_theta = (1.0 - cos_theta * cos_theta).max(0.0).sqrt();
    let tan_theta = sin_theta / cos_theta;
    let u = u.clamp(Vec2::splat(1e-6), Vec2::splat(1.0 - 1e-6));
    let y_max = if tan_theta > 0.0 {
        erf(cos_theta / sin_theta)
    } else {
        1.0
    };
    let c = |y: f32, x: f32| 1.0 + y + tan_theta * INV_SQRT_PI * (-x * x).exp();
    let c_max = if tan_theta > 0.0 {
        let cot = cos_theta / sin_theta;
        1.0 + y_max + tan_theta * INV_SQRT_PI * (-cot * cot).exp()
    } else {
        2.0
    };
    let target = u.x * c_max;
    let (mut lo, mut hi) = (-1.0f32, y_max);
    // Start from the analytic solution at grazing incidence, the most nonlinear case.
    let mut y = (y_max - (y_max + 1.0) * erf((-u.x.ln()).sqrt())).clamp(lo, hi);
    for _ in 0..12 {
        let x = erfinv(y);
        let value = c(y, x) - target;
        let derivative = 1.0 - x * tan_theta;
        let step = value / derivative;
        // Converged: the step is below what the variable resolves.
        if derivative > 0.0 && step.abs() <= 1e-7 {
            break;
        }
        if value > 0.0 {
            hi = y;
        } else {
            lo = y;
        }
        let next = y - step;
        y = if derivative > 0.0 && next > lo && next < hi {
            next
        } else {
            0.5 * (lo + hi)
        };
    }
    Vec2::new(erfinv(y), erfinv(2.0 * u.y - 1.0))
}

/// The shared BSDF code over one path's numbers: either distribution.
impl Facets<f32> for Microfacet {
    #[inline(always)]
    fn d(self, m: V3<f32>) -> f32 {
        Microfacet::d(self, m.into())
    }

    #[inline(always)]
    fn g1_over_cos(self, v: V3<f32>, m: V3<f32>) -> f32 {
        Microfacet::g1_over_cos(self, v.into(), m.into())
    }

    #[inline(always)]
    fn sample_visible(self, v: V3<f32>, (u1, u2): (f32, f32)) -> V3<f32> {
        Microfacet::sample_visible(self, v.into(), Vec2::new(u1, u2)).into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALPHAS: [f32; 5] = [0.05, 0.2, 0.6, 1.0, 2.0];

    fn all(alpha_u: f32, alpha_v: f32) -> [Microfacet; 2] {
        [
            Microfacet::new(Distribution::Ggx, alpha_u, alpha_v),
            Microfacet::new(Distribution::Beckmann, alpha_u, alpha_v),
        ]
    }

    /// `∫ f(m) dωm` over the hemisphere by the midpoint rule in `μ = 1 − x²` (points where a
    /// sharp lobe peaks, μ near 1) and φ.
    fn hemisphere(f: impl Fn(Vec3) -> f64) -> f64 {
        let (nu, np) = (2000, 256);
        let mut sum = 0.0f64;
        for i in 0..nu {
            let x = (i as f64 + 0.5) / nu as f64;
            let mu = 1.0 - x * x;
            let r = (1.0 - mu * mu).max(0.0).sqrt();
            for j in 0..np {
                let phi = (j as f64 + 0.5) / np as f64 * std::f64::consts::TAU;
                let m = Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, mu as f32);
                sum += f(m) * 2.0 * x;
            }
        }
        sum / (nu * np) as f64 * std::f64::consts::TAU
    }

    #[test]
    fn the_facets_project_to_the_macro_surface() {
        for alpha in ALPHAS {
            for (au, av) in [(alpha, alpha), (alpha, alpha * 0.25)] {
                for g in all(au, av) {
                    let area = hemisphere(|m| g.d(m) as f64 * f64::from(m.z));
                    assert!((area - 1.0).abs() < 2e-3, "{g:?}: ∫D cos = {area}");
                }
            }
        }
    }

    #[test]
    fn the_visible_normals_are_a_distribution() {
        // ∫ D_v(m) dm = 1: Smith's G1 is the share of facets v sees.
        for (au, av) in [(0.2f32, 0.2f32), (0.6, 0.6), (1.0, 1.0), (0.1, 0.5)] {
            for g in all(au, av) {
                let tol = 2e-3;
                for deg in [0.0f32, 45.0, 80.0, 89.0] {
                    let a = deg.to_radians();
                    for phi in [0.3f32, 1.9] {
                        let v = Vec3::new(a.sin() * phi.cos(), a.sin() * phi.sin(), a.cos());
                        let total = hemisphere(|m| g.visible_pdf(v, m) as f64);
                        assert!((total - 1.0).abs() < tol, "{g:?}, θv {deg}°: {total}");
                    }
                }
            }
        }
    }

    #[test]
    fn beckmann_masking_is_within_mitsubas_fit() {
        // Walter et al.'s rational fit, which Mitsuba evaluates, is within 0.35% of Smith's
        // exact 1/(1 + Λ(a)) that lucent evaluates.
        let g = Microfacet::isotropic(Distribution::Beckmann, 0.5);
        for deg in [10.0f32, 40.0, 60.0, 75.0, 85.0, 89.0] {
            let t = deg.to_radians();
            let v = Vec3::new(t.sin(), 0.0, t.cos());
            let a = 1.0 / (0.5 * t.tan());
            let fit = if a >= 1.6 {
                1.0
            } else {
                (3.535 * a + 2.181 * a * a) / (1.0 + 2.276 * a + 2.577 * a * a)
            };
            let exact = g.g1(v, Vec3::Z);
            assert!((fit / exact - 1.0).abs() < 4e-3, "{deg}°: {fit} vs {exact}");
        }
        // At a = 1: Λ = (erf(1) − 1)/2 + e^(−1)/(2√π) ≈ 0.0247.
        let v = Vec3::new(0.5f32.atan().sin(), 0.0, 0.5f32.atan().cos());
        let lambda = (erf(1.0) - 1.0) / 2.0 + (-1.0f32).exp() / (2.0 * PI.sqrt());
        assert!(
            (Microfacet::isotropic(Distribution::Beckmann, 2.0).g1(v, Vec3::Z)
                - 1.0 / (1.0 + lambda))
                .abs()
                < 1e-5
        );
    }

    #[test]
    fn masking_is_one_head_on_and_vanishes_at_grazing() {
        for alpha in ALPHAS {
            for g in all(alpha, alpha) {
                assert!((g.g1(Vec3::Z, Vec3::Z) - 1.0).abs() < 1e-6);
                let grazing = Vec3::new(1.0, 0.0, 1e-7).normalize();
                assert!(g.g1(grazing, Vec3::Z) < 1e-5);
                assert!(g.g1_over_cos(grazing, Vec3::Z).is_finite());
                // The back of a facet is never seen.
                let m = Vec3::new(0.8, 0.0, 0.6);
                assert_eq!(g.g1(Vec3::new(-0.8, 0.0, 0.6).normalize(), m), 0.0);
                for deg in [10.0f32, 50.0, 85.0] {
                    let a = deg.to_radians();
                    let v = Vec3::new(a.sin(), 0.0, a.cos());
                    let g1 = g.g1(v, Vec3::Z);
                    assert!(g1 > 0.0 && g1 <= 1.0, "{g1}");
                }
            }
        }
    }

    #[test]
    fn anisotropy_stretches_along_the_tangent() {
        // Rougher along x: a facet tilted towards x is more likely than one tilted as far
        // towards y, and light grazing along x is masked more.
        for g in all(0.5, 0.1) {
            let tilt_x = Vec3::new(0.2, 0.0, 1.0).normalize();
            let tilt_y = Vec3::new(0.0, 0.2, 1.0).normalize();
            assert!(g.d(tilt_x) > 10.0 * g.d(tilt_y), "{g:?}");
            let along_x = Vec3::new(0.9, 0.0, 0.436).normalize();
            let along_y = Vec3::new(0.0, 0.9, 0.436).normalize();
            assert!(g.g1(along_x, Vec3::Z) < g.g1(along_y, Vec3::Z));
        }
    }

    #[test]
    fn visible_normals_face_the_viewer() {
        let mut state = 7u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        for alpha in [ALPHA_MIN, 0.05, 0.5, 1.0, ALPHA_MAX] {
            for g in all(alpha, alpha).into_iter().chain(all(alpha, 0.3)) {
                for deg in [0.0f32, 30.0, 89.9, 90.0] {
                    let a = deg.to_radians();
                    let v = Vec3::new(a.sin(), 0.0, a.cos().max(0.0));
                    for _ in 0..1000 {
                        let m = g.sample_visible(v, Vec2::new(next(), next()));
                        assert!(m.is_finite() && (m.length() - 1.0).abs() < 1e-4, "{m}");
                        assert!(m.z >= 0.0 && v.dot(m) >= -1e-5, "{g:?} v {v}: m {m}");
                    }
                }
            }
        }
    }
}
