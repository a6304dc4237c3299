//! The GGX (Trowbridge–Reitz) microfacet distribution, isotropic: normal distribution `D`,
//! Smith masking `G1` and `G`, and sampling of the visible normals.
//!
//! References: Walter, Marschner, Li & Torrance 2007, "Microfacet Models for Refraction through
//! Rough Surfaces" (D and G1 of GGX); Heitz 2014, "Understanding the Masking-Shadowing Function
//! in Microfacet-Based BRDFs" (the distribution of visible normals); Heitz 2018, "Sampling the
//! GGX Distribution of Visible Normals" (JCGT 7(4)), the sampling routine.
//!
//! All vectors are in the local frame (macro-normal `z`); microfacet normals `m` lie in the
//! upper hemisphere.

use std::f32::consts::{PI, TAU};

use glam::{Vec2, Vec3};

/// The smallest roughness used: below it `D` peaks beyond what `f32` half vectors resolve
/// (pbrt-v4 treats `α < 10⁻³` as smooth; this keeps a glossy lobe a little further down).
pub const ALPHA_MIN: f32 = 1e-4;
/// The largest roughness used; above it the surface is flat noise and stretched vectors lose
/// their `z` to rounding.
pub const ALPHA_MAX: f32 = 100.0;

/// An isotropic GGX distribution of roughness `α`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx {
    alpha: f32,
}

impl Ggx {
    /// GGX of roughness `alpha`, clamped to `[ALPHA_MIN, ALPHA_MAX]` (NaN becomes `ALPHA_MIN`).
    pub fn new(alpha: f32) -> Self {
        let alpha = if alpha.is_nan() {
            ALPHA_MIN
        } else {
            alpha.clamp(ALPHA_MIN, ALPHA_MAX)
        };
        Self { alpha }
    }

    /// The roughness in use (after clamping).
    pub fn alpha(self) -> f32 {
        self.alpha
    }

    /// The density of microfacet normals per unit solid angle, normalised so that the facets'
    /// projected area is the macro-surface's, `∫ D(m) cos θm dωm = 1`:
    /// `D(m) = 1 / (π α² cos⁴θm (1 + tan²θm/α²)²) = 1 / (π α² ((m_x² + m_y²)/α² + m_z²)²)`,
    /// the second form free of `tan` at grazing `m`. Zero for `m.z ≤ 0`.
    pub fn d(self, m: Vec3) -> f32 {
        if m.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let t = (m.x * m.x + m.y * m.y) / a2 + m.z * m.z;
        1.0 / (PI * a2 * t * t)
    }

    /// Smith's masking of direction `v` (either side) for facets of normal `m`:
    /// `G1 = 2 / (1 + √(1 + α² tan²θv)) = 2|v_z| / (|v_z| + √(v_z² + α²(v_x² + v_y²)))`,
    /// and zero when `v` sees the back of the facet (`(v·m)` and `v_z` of opposite signs).
    pub fn g1(self, v: Vec3, m: Vec3) -> f32 {
        self.g1_over_cos(v, m) * v.z.abs()
    }

    /// `G1(v, m) / |cos θv|`, which stays finite (at most `2/α`) as `v` becomes grazing, where
    /// `G1` and `cos θv` both vanish: `2 / (|v_z| + √(v_z² + α²(v_x² + v_y²)))`.
    pub fn g1_over_cos(self, v: Vec3, m: Vec3) -> f32 {
        if v.dot(m) * v.z <= 0.0 {
            return 0.0;
        }
        let a2 = self.alpha * self.alpha;
        let root = (v.z * v.z + a2 * (v.x * v.x + v.y * v.y)).sqrt();
        2.0 / (v.z.abs() + root)
    }

    /// The separable shadowing-masking term `G = G1(wo, m)·G1(wi, m)`, as Mitsuba uses.
    pub fn g(self, wo: Vec3, wi: Vec3, m: Vec3) -> f32 {
        self.g1(wo, m) * self.g1(wi, m)
    }

    /// A microfacet normal drawn from the normals visible from `v` (unit, `v.z ≥ 0`: a caller
    /// arriving from below passes `−v`), with density [`Ggx::visible_pdf`], by Heitz 2018:
    /// stretch `v` to the configuration where `α = 1` (the facets become a hemisphere), sample
    /// the hemisphere's projected disc seen from there — a disc whose far half is squashed by
    /// `(1 + cos θ)/2` — lift the point onto the hemisphere and unstretch the normal.
    pub fn sample_visible(self, v: Vec3, u: Vec2) -> Vec3 {
        debug_assert!(
            v.z >= 0.0,
            "sample_visible wants v in the upper hemisphere, got {v}"
        );
        let a = self.alpha;
        let vh = Vec3::new(a * v.x, a * v.y, v.z.max(0.0)).normalize_or(Vec3::Z);
        // A basis around vh: t1 horizontal (undefined at normal incidence, where any will do).
        let len2 = vh.x * vh.x + vh.y * vh.y;
        let t1 = if len2 > 0.0 {
            Vec3::new(-vh.y, vh.x, 0.0) / len2.sqrt()
        } else {
            Vec3::X
        };
        let t2 = vh.cross(t1);
        // A uniform point on the unit disc, its far half squashed towards the horizon.
        let r = u.x.sqrt();
        let (sin_phi, cos_phi) = (TAU * u.y).sin_cos();
        let p1 = r * cos_phi;
        let s = 0.5 * (1.0 + vh.z);
        let p2 = (1.0 - s) * (1.0 - p1 * p1).max(0.0).sqrt() + s * r * sin_phi;
        let nh = t1 * p1 + t2 * p2 + vh * (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
        Vec3::new(a * nh.x, a * nh.y, nh.z.max(0.0)).normalize_or(Vec3::Z)
    }

    /// The density of [`Ggx::sample_visible`] per unit solid angle of `m`, the distribution of
    /// visible normals `D_v(m) = G1(v, m)·max(0, v·m)·D(m) / cos θv` (Heitz 2014), for `v.z ≥ 0`.
    pub fn visible_pdf(self, v: Vec3, m: Vec3) -> f32 {
        let cos_vm = v.dot(m);
        if cos_vm <= 0.0 {
            return 0.0;
        }
        self.g1_over_cos(v, m) * cos_vm * self.d(m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALPHAS: [f32; 5] = [0.05, 0.2, 0.6, 1.0, 2.0];

    /// `∫ D(m) cos θm dωm` over the hemisphere: `2π ∫₀¹ D(μ) μ dμ`, with `μ = 1 − x²` to
    /// put points where a sharp `D` peaks (μ near 1).
    fn projected_area(g: Ggx) -> f64 {
        let n = 200_000;
        let mut sum = 0.0f64;
        for i in 0..n {
            let x = (i as f64 + 0.5) / n as f64;
            let mu = 1.0 - x * x;
            let m = Vec3::new((1.0 - mu * mu).sqrt() as f32, 0.0, mu as f32);
            sum += g.d(m) as f64 * mu * 2.0 * x / n as f64;
        }
        sum * std::f64::consts::TAU
    }

    #[test]
    fn the_facets_project_to_the_macro_surface() {
        for alpha in ALPHAS {
            let area = projected_area(Ggx::new(alpha));
            assert!((area - 1.0).abs() < 1e-3, "α {alpha}: ∫D cos = {area}");
        }
    }

    #[test]
    fn the_visible_normals_are_a_distribution() {
        // ∫ D_v(m) dm = 1: Smith's G1 is exactly the share of facets v sees.
        for alpha in [0.2f32, 0.6, 1.0] {
            let g = Ggx::new(alpha);
            for deg in [0.0f32, 45.0, 80.0, 89.0] {
                let a = deg.to_radians();
                let v = Vec3::new(a.sin(), 0.0, a.cos());
                let (nu, np) = (1000, 360);
                let mut sum = 0.0f64;
                for i in 0..nu {
                    let x = (i as f64 + 0.5) / nu as f64;
                    let mu = 1.0 - x * x;
                    let r = (1.0 - mu * mu).sqrt();
                    for j in 0..np {
                        let phi = (j as f64 + 0.5) / np as f64 * std::f64::consts::TAU;
                        let m =
                            Vec3::new((r * phi.cos()) as f32, (r * phi.sin()) as f32, mu as f32);
                        sum += g.visible_pdf(v, m) as f64 * 2.0 * x;
                    }
                }
                let total = sum / (nu * np) as f64 * std::f64::consts::TAU;
                assert!((total - 1.0).abs() < 2e-3, "α {alpha}, θv {deg}°: {total}");
            }
        }
    }

    #[test]
    fn masking_is_one_head_on_and_vanishes_at_grazing() {
        for alpha in ALPHAS {
            let g = Ggx::new(alpha);
            assert!((g.g1(Vec3::Z, Vec3::Z) - 1.0).abs() < 1e-6);
            let grazing = Vec3::new(1.0, 0.0, 1e-7).normalize();
            assert!(g.g1(grazing, Vec3::Z) < 1e-5);
            assert!(g.g1_over_cos(grazing, Vec3::Z) <= 2.0 / alpha + 1e-3);
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
            let g = Ggx::new(alpha);
            for deg in [0.0f32, 30.0, 89.9, 90.0] {
                let a = deg.to_radians();
                let v = Vec3::new(a.sin(), 0.0, a.cos().max(0.0));
                for _ in 0..1000 {
                    let m = g.sample_visible(v, Vec2::new(next(), next()));
                    assert!(m.is_finite() && (m.length() - 1.0).abs() < 1e-4, "{m}");
                    assert!(m.z >= 0.0 && v.dot(m) >= -1e-6, "α {alpha} v {v}: m {m}");
                }
            }
        }
    }
}
