//! Fresnel reflectance: smooth dielectric boundaries (with the refracted cosine), conductors of
//! complex index, and the diffuse (hemispherically averaged) reflectance of a dielectric.

use glam::Vec3;

use crate::Rgb;
use crate::lanes::{Real, V3};

/// What a smooth dielectric boundary does to light arriving at `cos θi` ([`dielectric`]); over
/// a [`Real`] for lanes ([`dielectric_of`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DielectricFresnel<R = f32> {
    /// The unpolarised reflectance `F` in `[0, 1]`; 1 under total internal reflection.
    pub r: R,
    /// `cos θt` of the transmitted direction, signed: on the other side from `cos θi`. Zero
    /// under total internal reflection (there is no transmitted direction).
    pub cos_t: R,
    /// The relative index in the direction of travel, `η_transmitted / η_incident`.
    pub eta_it: R,
    /// Its reciprocal `η_incident / η_transmitted`: the factor Snell's law scales the
    /// tangential part of the direction by.
    pub eta_ti: R,
}

impl DielectricFresnel {
    /// True when no light is transmitted: total internal reflection, or light exactly at
    /// grazing incidence.
    pub fn is_total(&self) -> bool {
        self.cos_t == 0.0 || self.r >= 1.0
    }
}

/// A relative index of refraction that the formulas can use: non-positive or non-finite values
/// are taken as 1 (index-matched, no boundary) rather than producing NaN.
#[inline]
pub(crate) fn sane_eta(eta: f32) -> f32 {
    if eta.is_finite() && eta > 0.0 {
        eta
    } else {
        1.0
    }
}

/// The unpolarised Fresnel reflectance of a smooth boundary with relative index
/// `eta = η_inside / η_outside`, for light arriving at `cos_i = cos θi` (positive from the
/// outside, `z > 0`; negative from the inside, where the index flips to `1/eta`).
///
/// With `η = η_t/η_i` in the direction of travel, Snell's law gives
/// `cos² θt = 1 − (1 − cos² θi)/η²`; when that is negative the light is totally reflected.
/// Otherwise the amplitudes of the two polarisations are
/// `r_s = (cos θi − η cos θt)/(cos θi + η cos θt)`,
/// `r_p = (η cos θi − cos θt)/(η cos θi + cos θt)`, and the unpolarised reflectance is their
/// mean intensity `F = (r_s² + r_p²)/2`.
pub fn dielectric(cos_i: f32, eta: f32) -> DielectricFresnel {
    dielectric_of(cos_i, sane_eta(eta))
}

/// [`dielectric`] written once over [`Real`], for an index already made sane
/// ([`sane_eta`]): its branches (index-matched, total internal reflection) as lane masks.
#[inline(always)]
pub(crate) fn dielectric_of<R: Real>(cos_i: R, eta: R) -> DielectricFresnel<R> {
    let (zero, one) = (R::splat(0.0), R::splat(1.0));
    let outside = cos_i.ge(zero);
    let inverse = one / eta;
    let (eta_it, eta_ti) = (
        R::select(outside, eta, inverse),
        R::select(outside, inverse, eta),
    );
    let ci = cos_i.abs().min(one);
    let cos_t2 = one - eta_ti * eta_ti * (one - ci * ci);
    let ct = cos_t2.sqrt();
    // Both denominators are positive where there is a transmitted ray (ct > 0), so grazing
    // ci = 0 gives r_s = −1, r_p = 1 and F = 1 without a special case.
    let rs = (ci - eta_it * ct) / (ci + eta_it * ct);
    let rp = (eta_it * ci - ct) / (eta_it * ci + ct);
    let r = (R::splat(0.5) * (rs * rs + rp * rp)).max(zero).min(one);
    let cos_t = R::select(outside, -ct, ct);
    // Total internal reflection: everything reflected, nothing transmitted.
    let total = cos_t2.le(zero);
    let (r, cos_t) = (R::select(total, one, r), R::select(total, zero, cos_t));
    // Index-matched: no boundary at all, the light goes straight on.
    let matched = eta.eq(one);
    DielectricFresnel {
        r: R::select(matched, zero, r),
        cos_t: R::select(matched, -cos_i, cos_t),
        eta_it,
        eta_ti,
    }
}

/// The direction refracted from `w` (unit, pointing away from the surface on the incident side)
/// through the unit normal `m`, given `f = dielectric(w·m, eta)` (not under total internal
/// reflection). Snell's law in vector form with the already computed cosine:
/// `t = m·((w·m)·η_ti + cos θt) − η_ti·w`: the tangential part of `w` flipped and scaled by
/// `η_ti`, the normal part `cos θt`.
#[inline]
pub fn refract(w: Vec3, m: Vec3, f: &DielectricFresnel) -> Vec3 {
    refract_of(w.into(), m.into(), f).into()
}

/// [`refract`] over a [`Real`].
#[inline(always)]
pub(crate) fn refract_of<R: Real>(w: V3<R>, m: V3<R>, f: &DielectricFresnel<R>) -> V3<R> {
    m * (w.dot(m) * f.eta_ti + f.cos_t) - w * f.eta_ti
}

/// The largest `eta` and `k` of a conductor: far above every measured metal, and far below
/// where the exact Fresnel term overflows in single precision (`(η² − k²)²` passes `f32::MAX`
/// near 4·10⁹, and the reflectance comes out NaN). Scene files are held to it, and textured
/// values clamped to it.
pub const MAX_CONDUCTOR_INDEX: f32 = 1000.0;

/// The unpolarised Fresnel reflectance of a conductor of complex relative index `η + i·k`, per
/// channel, for light arriving from the outside at `cos_i ≥ 0` (negative values are clamped:
/// light does not come out of a metal).
pub fn conductor(cos_i: f32, eta: Rgb, k: Rgb) -> Rgb {
    Rgb::new(
        conductor_channel(cos_i, eta.r, k.r),
        conductor_channel(cos_i, eta.g, k.g),
        conductor_channel(cos_i, eta.b, k.b),
    )
}

/// One channel of [`conductor`], the exact formula (e.g. Born & Wolf; Moeller, "Optics").
/// With `c = cos θi`, `s² = 1 − c²`, `t = η² − k² − s²`:
/// `a² + b² = √(t² + 4η²k²)`, `a = √((a² + b² + t)/2)`,
/// `R_s = (a² + b² + c² − 2ac)/(a² + b² + c² + 2ac)`,
/// `R_p = R_s·(c²(a² + b²) + s⁴ − 2ac·s²)/(c²(a² + b²) + s⁴ + 2ac·s²)`,
/// `F = (R_s + R_p)/2`.
fn conductor_channel(cos_i: f32, eta: f32, k: f32) -> f32 {
    // Textured indices can leave the range a scene file's constants are held to.
    let (eta, k) = (
        eta.clamp(0.0, MAX_CONDUCTOR_INDEX),
        k.clamp(0.0, MAX_CONDUCTOR_INDEX),
    );
    let c = cos_i.clamp(0.0, 1.0);
    let c2 = c * c;
    let s2 = 1.0 - c2;
    let t = eta * eta - k * k - s2;
    let a2b2 = (t * t + 4.0 * eta * eta * k * k).max(0.0).sqrt();
    let a = (0.5 * (a2b2 + t)).max(0.0).sqrt();
    let rs_num = a2b2 + c2 - 2.0 * a * c;
    let rs_den = a2b2 + c2 + 2.0 * a * c;
    let rp_num = c2 * a2b2 + s2 * s2 - 2.0 * a * c * s2;
    let rp_den = c2 * a2b2 + s2 * s2 + 2.0 * a * c * s2;
    // Vanishing denominators only for an index of 0 + 0i at grazing light: call it a mirror.
    let rs = if rs_den > 0.0 { rs_num / rs_den } else { 1.0 };
    let rp = if rp_den > 0.0 {
        rs * rp_num / rp_den
    } else {
        rs
    };
    (0.5 * (rs + rp)).clamp(0.0, 1.0)
}

/// The diffuse Fresnel reflectance `F_dr(η) = ∫ F(cos θ, η)·2 cos θ d(cos θ)`: the share of
/// light arriving uniformly (cosine-weighted) from all directions that a smooth boundary of
/// relative index `eta` (in the direction of travel) reflects.
///
/// A fit, the same one Mitsuba 3 uses, so that coated materials match its images: for `η < 1`
/// (light leaving a denser medium) Egan & Hilgeman 1973,
/// `F_dr = −1.4399η² + 0.7099η + 0.6681 + 0.0636/η`; for `η ≥ 1`, d'Eon & Irving 2011,
/// `F_dr = 0.919317 − 3.4793/η + 6.75335/η² − 7.80989/η³ + 4.98554/η⁴ − 1.36881/η⁵`. The tests
/// hold both to the integral (within 1% over 1 ≤ 1/η, η ≤ 2).
pub fn diffuse_reflectance(eta: f32) -> f32 {
    let eta = sane_eta(eta);
    let f = if eta < 1.0 {
        -1.4399 * eta * eta + 0.7099 * eta + 0.6681 + 0.0636 / eta
    } else {
        let i = 1.0 / eta;
        0.919_317 + i * (-3.4793 + i * (6.75335 + i * (-7.80989 + i * (4.98554 - 1.36881 * i))))
    };
    f.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f32, b: f32, tol: f32) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn glass_reflects_four_percent_at_normal_incidence_from_either_side() {
        // ((η − 1)/(η + 1))² = (0.5/2.5)² = 0.04.
        let out = dielectric(1.0, 1.5);
        let inside = dielectric(-1.0, 1.5);
        assert!(close(out.r, 0.04, 1e-6), "{out:?}");
        assert!(close(inside.r, 0.04, 1e-6), "{inside:?}");
        assert!(close(out.cos_t, -1.0, 1e-6) && close(inside.cos_t, 1.0, 1e-6));
        assert_eq!((out.eta_it, inside.eta_it), (1.5, 1.0 / 1.5));
    }

    #[test]
    fn total_internal_reflection_beyond_the_critical_angle() {
        // From inside glass the critical angle is asin(1/1.5) = 41.8°.
        let below = dielectric(-(41.0f32.to_radians().cos()), 1.5);
        assert!(below.r < 1.0 && !below.is_total(), "{below:?}");
        for deg in [42.0f32, 45.0, 60.0, 89.0] {
            let f = dielectric(-(deg.to_radians().cos()), 1.5);
            assert!(f.r == 1.0 && f.is_total(), "{deg}°: {f:?}");
        }
    }

    #[test]
    fn the_same_ray_reversed_reflects_the_same_share() {
        // Stokes: F(θi) entering equals F(θt) leaving, for the refracted θt.
        for deg in [0.0f32, 20.0, 45.0, 70.0, 85.0] {
            let f = dielectric(deg.to_radians().cos(), 1.5);
            let back = dielectric(f.cos_t, 1.5);
            assert!(close(f.r, back.r, 1e-5), "{deg}°: {} vs {}", f.r, back.r);
        }
    }

    #[test]
    fn the_refracted_direction_obeys_snell() {
        for deg in [0.0f32, 10.0, 30.0, 60.0, 89.0] {
            let a = deg.to_radians();
            let w = Vec3::new(a.sin(), 0.0, a.cos());
            let f = dielectric(w.z, 1.5);
            let t = refract(w, Vec3::Z, &f);
            assert!(close(t.length(), 1.0, 1e-5));
            // sin θi = η sin θt, and t goes to the other side, away from w's tangent.
            let sin_t = (t.x * t.x + t.y * t.y).sqrt();
            assert!(close(a.sin(), 1.5 * sin_t, 1e-5), "{deg}°");
            assert!(t.z < 0.0 && t.x <= 0.0);
            // Reversed, the light that came out along t goes back out along w.
            let back = refract(t, Vec3::Z, &dielectric(t.z, 1.5));
            assert!((back - w).length() < 1e-4, "{deg}°: {back} vs {w}");
        }
    }

    #[test]
    fn index_matched_and_degenerate_indices_do_not_reflect() {
        for eta in [1.0, 0.0, -2.0, f32::NAN, f32::INFINITY] {
            for c in [-1.0, -0.3, 0.0, 0.5, 1.0] {
                let f = dielectric(c, eta);
                assert!(f.r == 0.0 && f.cos_t == -c, "η {eta}, cos {c}: {f:?}");
            }
        }
    }

    #[test]
    fn gold_at_normal_incidence_matches_the_closed_form() {
        // Gold, roughly at 650/550/450 nm.
        let eta = Rgb::new(0.143, 0.374, 1.442);
        let k = Rgb::new(3.983, 2.385, 1.603);
        let f = conductor(1.0, eta, k);
        for ((n, k), got) in eta
            .to_array()
            .into_iter()
            .zip(k.to_array())
            .zip(f.to_array())
        {
            let want = ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k);
            assert!(close(got, want, 1e-5), "n {n} k {k}: {got} vs {want}");
        }
        // And every metal is a mirror at grazing incidence.
        assert!(
            conductor(0.0, eta, k)
                .to_array()
                .iter()
                .all(|&r| close(r, 1.0, 1e-6))
        );
    }

    #[test]
    fn a_conductor_without_absorption_is_a_dielectric() {
        for deg in [0.0f32, 30.0, 60.0, 80.0, 89.0] {
            let c = deg.to_radians().cos();
            let want = dielectric(c, 1.5).r;
            let got = conductor_channel(c, 1.5, 0.0);
            assert!(close(got, want, 1e-5), "{deg}°: {got} vs {want}");
        }
    }

    /// `∫ F(μ, η) 2μ dμ` by the midpoint rule on many intervals.
    fn diffuse_reflectance_integral(eta: f32) -> f32 {
        let n = 20_000;
        let sum: f64 = (0..n)
            .map(|i| {
                let mu = (i as f64 + 0.5) / n as f64;
                dielectric(mu as f32, eta).r as f64 * 2.0 * mu
            })
            .sum();
        (sum / n as f64) as f32
    }

    #[test]
    fn the_diffuse_reflectance_fit_matches_the_integral() {
        for eta in [1.1f32, 1.33, 1.5, 1.7, 2.0] {
            for e in [eta, 1.0 / eta] {
                let (fit, exact) = (diffuse_reflectance(e), diffuse_reflectance_integral(e));
                assert!(
                    (fit - exact).abs() <= 0.01 * exact.max(0.01),
                    "η {e}: fit {fit}, integral {exact}"
                );
            }
        }
        // Light leaving glass is mostly trapped: about 60% of a diffuse flux comes back.
        assert!(close(diffuse_reflectance(1.0 / 1.5), 0.596, 0.01));
    }
}
