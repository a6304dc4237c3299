//! Warps from the unit square `[0, 1)²` to the shapes that sampling needs, each with its
//! density.
//!
//! Directions are in a local frame with `z` up (the normal, or the axis of a cone); a
//! direction's density is per unit solid angle, a disk's per unit area, and so on, as each
//! function says. Every warp is continuous and area-preserving up to its density, so
//! stratified input (see [`super::sobol`]) stays stratified on the output.

use std::f32::consts::{FRAC_1_PI, FRAC_PI_4, TAU};

use glam::{Vec2, Vec3};

use crate::lanes::{Real, V3, sin_cos_quarter};

/// The point of the unit disk for `u` by Shirley and Chiu's concentric map: squares around the
/// centre of `[0, 1)²` go to circles around the centre of the disk, so nearby points stay
/// nearby and strata keep their shape. Uniform over the disk: density
/// [`concentric_disk_pdf`] per unit area.
pub fn square_to_concentric_disk(u: Vec2) -> Vec2 {
    let (x, y) = concentric_disk(u.x, u.y);
    Vec2::new(x, y)
}

/// [`square_to_concentric_disk`] for any [`Real`], written once for one path and for lanes.
#[inline(always)]
pub fn concentric_disk<R: Real>(ux: R, uy: R) -> (R, R) {
    // To [-1, 1)², then each quarter between the diagonals to a quarter of the disk:
    // r = the larger coordinate, the angle proportional to the ratio of the coordinates.
    let (one, two) = (R::splat(1.0), R::splat(2.0));
    let (ox, oy) = (two * ux - one, two * uy - one);
    let centre = ox.eq(R::splat(0.0)) & oy.eq(R::splat(0.0));
    // The left and right quarters: r = ox at angle φ = π/4·(oy/ox). The top and bottom ones:
    // r = oy at angle π/2 − φ, φ = π/4·(ox/oy), whose sine and cosine are φ's cosine and sine.
    let sideways = ox.abs().gt(oy.abs());
    let (r, ratio) = (
        R::select(sideways, ox, oy),
        R::select(sideways, oy / ox, ox / oy),
    );
    let (sin, cos) = sin_cos_quarter(R::splat(FRAC_PI_4) * ratio);
    let x = r * R::select(sideways, cos, sin);
    let y = r * R::select(sideways, sin, cos);
    let zero = R::splat(0.0);
    (R::select(centre, zero, x), R::select(centre, zero, y))
}

/// The density of [`square_to_concentric_disk`] per unit area of the disk: `1/π`.
pub fn concentric_disk_pdf() -> f32 {
    FRAC_1_PI
}

/// A unit direction in the hemisphere `z ≥ 0` with density proportional to `cos θ = z`
/// (Malley's method: a uniform point of the concentric disk lifted onto the hemisphere). Its
/// density per unit solid angle is [`cosine_hemisphere_pdf`]`(z)`.
pub fn square_to_cosine_hemisphere(u: Vec2) -> Vec3 {
    cosine_hemisphere(u.x, u.y).into()
}

/// [`square_to_cosine_hemisphere`] for any [`Real`].
#[inline(always)]
pub fn cosine_hemisphere<R: Real>(ux: R, uy: R) -> V3<R> {
    let (x, y) = concentric_disk(ux, uy);
    let z = (R::splat(1.0) - (x * x + y * y)).max(R::splat(0.0)).sqrt();
    V3::new(x, y, z)
}

/// The density per unit solid angle of [`square_to_cosine_hemisphere`] for a direction with
/// `cos θ = cos_theta`: `cos θ / π`, and 0 below the horizon.
pub fn cosine_hemisphere_pdf<R: Real>(cos_theta: R) -> R {
    cos_theta.max(R::splat(0.0)) * R::splat(FRAC_1_PI)
}

/// The unit vector at height `z` and azimuth `phi`.
#[inline]
fn direction(z: f32, phi: f32) -> Vec3 {
    let r = (1.0 - z * z).max(0.0).sqrt();
    let (sin, cos) = phi.sin_cos();
    Vec3::new(r * cos, r * sin, z)
}

/// A unit direction uniform over the sphere (Archimedes: `z` uniform in `[-1, 1]`, the azimuth
/// uniform). Density [`uniform_sphere_pdf`] per unit solid angle.
pub fn square_to_uniform_sphere(u: Vec2) -> Vec3 {
    direction(1.0 - 2.0 * u.x, TAU * u.y)
}

/// The density of [`square_to_uniform_sphere`] per unit solid angle: `1 / 4π`.
pub fn uniform_sphere_pdf() -> f32 {
    0.25 * FRAC_1_PI
}

/// A unit direction uniform over the hemisphere `z ≥ 0` (`z` uniform in `[0, 1]`). Density
/// [`uniform_hemisphere_pdf`] per unit solid angle.
pub fn square_to_uniform_hemisphere(u: Vec2) -> Vec3 {
    direction(1.0 - u.x, TAU * u.y)
}

/// The density of [`square_to_uniform_hemisphere`] per unit solid angle: `1 / 2π`.
pub fn uniform_hemisphere_pdf() -> f32 {
    0.5 * FRAC_1_PI
}

/// A unit direction uniform over the cone of directions within angle `θ_max` of `+z`, given
/// `cos_max = cos θ_max` in `[-1, 1]` (`cos θ` uniform in `[cos_max, 1]`). Density
/// [`uniform_cone_pdf`]`(cos_max)` per unit solid angle.
///
/// `1 − cos θ` is computed directly rather than as a difference near 1, so narrow cones (a
/// small, distant light) keep their precision.
pub fn square_to_uniform_cone(u: Vec2, cos_max: f32) -> Vec3 {
    let one_minus_cos = u.x * (1.0 - cos_max);
    let z = 1.0 - one_minus_cos;
    // sin²θ = 1 − cos²θ = (1 − cos θ)(1 + cos θ)
    let r = (one_minus_cos * (2.0 - one_minus_cos)).max(0.0).sqrt();
    let (sin, cos) = (TAU * u.y).sin_cos();
    Vec3::new(r * cos, r * sin, z)
}

/// The density of [`square_to_uniform_cone`] per unit solid angle: one over the cone's solid
/// angle `2π(1 − cos_max)`; infinite for a cone of zero width.
pub fn uniform_cone_pdf(cos_max: f32) -> f32 {
    0.5 * FRAC_1_PI / (1.0 - cos_max)
}

/// Barycentric coordinates `(b0, b1)` (with `b2 = 1 − b0 − b1`) of a point uniform over a
/// triangle's area: density `1 / area` on the triangle.
///
/// Heitz's low-distortion map (2019): the square is cut along its diagonal and each half
/// squeezed linearly onto the triangle, which keeps strata compact, unlike the square-root
/// method.
pub fn square_to_uniform_triangle(u: Vec2) -> (f32, f32) {
    uniform_triangle(u.x, u.y)
}

/// [`square_to_uniform_triangle`] for any [`Real`].
#[inline(always)]
pub fn uniform_triangle<R: Real>(ux: R, uy: R) -> (R, R) {
    // Each half of the square maps linearly with Jacobian 1/2 onto the triangle
    // {b0, b1 ≥ 0, b0 + b1 ≤ 1} of area 1/2: uniform.
    let half = R::splat(0.5);
    let below = ux.lt(uy);
    let (b0, b1) = (half * ux, half * uy);
    (R::select(below, b0, ux - b1), R::select(below, uy - b0, b1))
}

/// χ² goodness-of-fit tests for the sampling tests of this crate.
#[cfg(test)]
pub(crate) mod chi2 {
    /// The 1% critical value of the χ² distribution with `dof` degrees of freedom
    /// (Wilson–Hilferty: `(χ²/k)^(1/3)` is nearly normal with mean `1 − 2/9k`, variance `2/9k`).
    pub(crate) fn critical_value(dof: usize) -> f64 {
        let k = dof as f64;
        let z = 2.326_348; // the 99% quantile of the standard normal
        let v = 2.0 / (9.0 * k);
        k * (1.0 - v + z * v.sqrt()).powi(3)
    }

    /// The χ² statistic of `observed` counts against `expected` ones and its degrees of
    /// freedom, pooling cells expected to hold fewer than 5 (the statistic is unreliable for
    /// those). `Err` when a cell expected to be empty is not.
    pub(crate) fn statistic(observed: &[f64], expected: &[f64]) -> Result<(f64, usize), String> {
        assert_eq!(observed.len(), expected.len());
        let total: f64 = expected.iter().sum();
        let mut cells: Vec<(f64, f64)> = Vec::new();
        let (mut pool_o, mut pool_e) = (0.0, 0.0);
        for (i, (&o, &e)) in observed.iter().zip(expected).enumerate() {
            if e <= 1e-9 * total {
                if o > 0.0 {
                    return Err(format!("cell {i}: {o} samples where none are expected"));
                }
                continue;
            }
            if e < 5.0 {
                pool_o += o;
                pool_e += e;
                if pool_e >= 5.0 {
                    cells.push((pool_o, pool_e));
                    (pool_o, pool_e) = (0.0, 0.0);
                }
            } else {
                cells.push((o, e));
            }
        }
        if pool_e > 0.0 {
            match cells.last_mut() {
                Some(last) => {
                    last.0 += pool_o;
                    last.1 += pool_e;
                }
                None => cells.push((pool_o, pool_e)),
            }
        }
        let stat = cells.iter().map(|&(o, e)| (o - e) * (o - e) / e).sum();
        Ok((stat, cells.len().saturating_sub(1)))
    }

    /// Panics unless `observed` fits `expected` at the 1% significance level.
    pub(crate) fn assert_fits(name: &str, observed: &[f64], expected: &[f64]) {
        let (stat, dof) = statistic(observed, expected).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(dof > 0, "{name}: too few cells for a χ² test");
        let limit = critical_value(dof);
        assert!(
            stat < limit,
            "{name}: χ² = {stat:.1} with {dof} degrees of freedom (1% limit {limit:.1})"
        );
    }

    #[test]
    fn critical_values_match_the_tables() {
        // From a table of the χ² distribution at 1%.
        for (dof, table) in [(10, 23.209), (50, 76.154), (99, 134.642), (1000, 1106.969)] {
            let v = critical_value(dof);
            assert!((v - table).abs() / table < 0.005, "{dof}: {v} vs {table}");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::uniform;
    use std::f64::consts::PI;

    const SAMPLES: u32 = 200_000;

    /// The `i`-th independent uniform point of test `seed`.
    fn point(seed: u64, i: u32) -> Vec2 {
        Vec2::new(uniform(seed, 0, i, 0), uniform(seed, 0, i, 1))
    }

    /// Points including the corners and edges of the square.
    fn edge_points() -> Vec<Vec2> {
        let below_one = 1.0 - f32::EPSILON / 2.0;
        let vs = [0.0, 1e-7, 0.25, 0.5, 0.75, 1.0 - 1e-6, below_one];
        let mut out = Vec::new();
        for &x in &vs {
            for &y in &vs {
                out.push(Vec2::new(x, y));
            }
        }
        out
    }

    /// Simpson's rule for `f` on `[a, b]` with `n` (even) intervals.
    fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
        let h = (b - a) / n as f64;
        let mut s = f(a) + f(b);
        for i in 1..n {
            s += f(a + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
        }
        s * h / 3.0
    }

    /// χ² test of a warp to directions within `theta_max` of `+z` against its density per
    /// unit solid angle, on a grid of equal steps in θ and φ; the expected count of each cell
    /// is the density integrated numerically over it (`dω = sin θ dθ dφ`).
    fn check_directions(
        name: &str,
        warp: impl Fn(Vec2) -> Vec3,
        pdf: impl Fn(Vec3) -> f64,
        theta_max: f64,
    ) {
        let (nt, np) = (20, 40);
        let mut observed = vec![0.0; nt * np];
        let cell = |t: f64, p: f64| {
            let i = ((t / theta_max * nt as f64) as usize).min(nt - 1);
            let j = (((p + PI) / (2.0 * PI) * np as f64) as usize).min(np - 1);
            i * np + j
        };
        for s in 0..SAMPLES {
            let v = warp(point(17, s));
            assert!((v.length() - 1.0).abs() < 1e-5, "{name}: {v} is not unit");
            let v = v.as_dvec3();
            let theta = v.z.clamp(-1.0, 1.0).acos();
            assert!(theta <= theta_max + 1e-5, "{name}: {v} outside the domain");
            observed[cell(theta, v.y.atan2(v.x))] += 1.0;
        }
        let mut expected = vec![0.0; nt * np];
        let (dt, dp) = (theta_max / nt as f64, 2.0 * PI / np as f64);
        for i in 0..nt {
            for j in 0..np {
                let p0 = -PI + j as f64 * dp;
                let mass = simpson(
                    |t| {
                        simpson(
                            |p| {
                                let (st, ct) = t.sin_cos();
                                let d = Vec3::new(
                                    (st * p.cos()) as f32,
                                    (st * p.sin()) as f32,
                                    ct as f32,
                                );
                                pdf(d) * st
                            },
                            p0,
                            p0 + dp,
                            8,
                        )
                    },
                    i as f64 * dt,
                    (i + 1) as f64 * dt,
                    8,
                );
                expected[i * np + j] = mass * f64::from(SAMPLES);
            }
        }
        let total: f64 = expected.iter().sum();
        assert!(
            (total / f64::from(SAMPLES) - 1.0).abs() < 1e-4,
            "{name}: the pdf integrates to {}",
            total / f64::from(SAMPLES)
        );
        chi2::assert_fits(name, &observed, &expected);
        for u in edge_points() {
            let v = warp(u);
            assert!(
                v.is_finite() && (v.length() - 1.0).abs() < 1e-5,
                "{name}: {u} → {v}"
            );
        }
    }

    #[test]
    fn uniform_sphere_fits_its_pdf() {
        check_directions(
            "uniform sphere",
            square_to_uniform_sphere,
            |_| f64::from(uniform_sphere_pdf()),
            PI,
        );
    }

    #[test]
    fn uniform_hemisphere_fits_its_pdf() {
        check_directions(
            "uniform hemisphere",
            square_to_uniform_hemisphere,
            |_| f64::from(uniform_hemisphere_pdf()),
            PI / 2.0,
        );
    }

    #[test]
    fn cosine_hemisphere_fits_its_pdf() {
        check_directions(
            "cosine hemisphere",
            square_to_cosine_hemisphere,
            |v| f64::from(cosine_hemisphere_pdf(v.z)),
            PI / 2.0,
        );
        assert_eq!(cosine_hemisphere_pdf(-0.5), 0.0);
    }

    #[test]
    fn uniform_cones_fit_their_pdf() {
        for cos_max in [0.95f32, 0.3, -0.6] {
            check_directions(
                &format!("uniform cone, cos θmax = {cos_max}"),
                |u| square_to_uniform_cone(u, cos_max),
                |_| f64::from(uniform_cone_pdf(cos_max)),
                f64::from(cos_max).acos(),
            );
        }
        // A cone the width of the sun seen from the earth keeps its directions unit and
        // inside it.
        let cos_max = (0.0047f32).cos();
        for s in 0..1000 {
            let v = square_to_uniform_cone(point(3, s), cos_max);
            assert!((v.length() - 1.0).abs() < 1e-6 && v.z >= cos_max);
        }
        // The full sphere as a cone.
        assert!((uniform_cone_pdf(-1.0) - uniform_sphere_pdf()).abs() < 1e-8);
    }

    #[test]
    fn concentric_disk_is_uniform() {
        // Rings of equal width and sectors of equal angle: a cell between radii r0 and r1
        // holds (r1² − r0²)/2 · Δφ / π of the samples.
        let (nr, np) = (10, 24);
        let mut observed = vec![0.0; nr * np];
        for s in 0..SAMPLES {
            let d = square_to_concentric_disk(point(5, s)).as_dvec2();
            let r = d.length();
            assert!(r <= 1.0 + 1e-6, "{d} outside the disk");
            let i = ((r * nr as f64) as usize).min(nr - 1);
            let j = (((d.y.atan2(d.x) + PI) / (2.0 * PI) * np as f64) as usize).min(np - 1);
            observed[i * np + j] += 1.0;
        }
        let mut expected = vec![0.0; nr * np];
        for i in 0..nr {
            let (r0, r1) = (i as f64 / nr as f64, (i + 1) as f64 / nr as f64);
            let mass = (r1 * r1 - r0 * r0) / 2.0
                * (2.0 * PI / np as f64)
                * f64::from(concentric_disk_pdf());
            for j in 0..np {
                expected[i * np + j] = mass * f64::from(SAMPLES);
            }
        }
        chi2::assert_fits("concentric disk", &observed, &expected);
        for u in edge_points() {
            assert!(square_to_concentric_disk(u).length() <= 1.0 + 1e-6);
        }
        assert_eq!(square_to_concentric_disk(Vec2::splat(0.5)), Vec2::ZERO);
    }

    #[test]
    fn triangle_is_uniform() {
        // An n × n grid over (b0, b1): cells below the diagonal hold 2/n² of the samples,
        // cells the diagonal cuts through their corners half that, cells above none.
        let n = 20;
        let mut observed = vec![0.0; n * n];
        for s in 0..SAMPLES {
            let (b0, b1) = square_to_uniform_triangle(point(9, s));
            assert!(b0 >= 0.0 && b1 >= 0.0 && b0 + b1 <= 1.0, "({b0}, {b1})");
            let i = ((b0 * n as f32) as usize).min(n - 1);
            let j = ((b1 * n as f32) as usize).min(n - 1);
            observed[i * n + j] += 1.0;
        }
        let mut expected = vec![0.0; n * n];
        let full = 2.0 / (n * n) as f64 * f64::from(SAMPLES);
        for i in 0..n {
            for j in 0..n {
                expected[i * n + j] = match (i + j + 1).cmp(&n) {
                    std::cmp::Ordering::Less => full,
                    std::cmp::Ordering::Equal => full / 2.0,
                    std::cmp::Ordering::Greater => 0.0,
                };
            }
        }
        chi2::assert_fits("triangle", &observed, &expected);
        for u in edge_points() {
            let (b0, b1) = square_to_uniform_triangle(u);
            assert!(
                b0 >= 0.0 && b1 >= 0.0 && b0 + b1 <= 1.0,
                "{u} → ({b0}, {b1})"
            );
        }
    }
}
