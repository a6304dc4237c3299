//! The one self-intersection policy: where a secondary ray starts.
//!
//! A hit point carries rounding error, so a ray started exactly there may hit the surface it
//! leaves (shadow acne, speckled reflections) or, going inwards, start on the wrong side.
//! Every secondary ray is therefore started from the hit point moved off the surface along the
//! geometric normal, to the side the ray leaves on, by a distance that scales with the point's
//! magnitude: a fixed number of units in the last place (Wächter & Binder, "A Fast and Robust
//! Method for Avoiding Self-Intersection", Ray Tracing Gems, 2019). Near the origin, where
//! units in the last place vanish, a small fixed offset is used instead.
//!
//! Together with hit points that are computed on the surface as closely as possible
//! (spheres: re-projected onto the sphere; triangles: from the barycentric weights), this lets
//! every secondary ray use `t > 0` with no epsilon at the call site.

use glam::Vec3;
use lucent_accel::Ray;

/// Below this magnitude a coordinate is offset by a fixed amount rather than in ulps.
const ORIGIN: f32 = 1.0 / 32.0;
/// The fixed offset near the origin, per unit of normal.
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
/// The offset in ulps, per unit of normal.
const INT_SCALE: f32 = 256.0;

/// `p` moved off the surface along `n` (unit, pointing to the side the new ray leaves on).
pub fn offset_origin(p: Vec3, n: Vec3) -> Vec3 {
    let offset_axis = |p: f32, n: f32| -> f32 {
        if p.abs() < ORIGIN {
            return p + FLOAT_SCALE * n;
        }
        let ulps = (INT_SCALE * n) as i32;
        // Adding to the bit pattern of a negative float moves it towards −∞, so flip the sign.
        let step = if p < 0.0 { -ulps } else { ulps };
        f32::from_bits((p.to_bits() as i32).wrapping_add(step) as u32)
    };
    Vec3::new(
        offset_axis(p.x, n.x),
        offset_axis(p.y, n.y),
        offset_axis(p.z, n.z),
    )
}

/// A ray leaving the surface at `p` (geometric unit normal `n`, either orientation) along `dir`.
pub fn spawn_ray(p: Vec3, n: Vec3, dir: Vec3) -> Ray {
    let side = if n.dot(dir) >= 0.0 { n } else { -n };
    Ray::new(offset_origin(p, side), dir)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_origin_moves_to_the_side_of_the_normal() {
        for p in [
            Vec3::new(1.0, -2.0, 3.0),
            Vec3::new(-1000.0, 0.01, 5e5),
            Vec3::ZERO,
        ] {
            for n in [Vec3::X, -Vec3::Y, Vec3::new(1.0, 1.0, -1.0).normalize()] {
                let q = offset_origin(p, n);
                assert!((q - p).dot(n) > 0.0, "p = {p}, n = {n}, q = {q}");
                // Small: well under a thousandth of the point's magnitude (or of 1).
                assert!((q - p).length() < 1e-3 * p.abs().max_element().max(1.0));
            }
        }
    }

    #[test]
    fn spawn_picks_the_side_the_ray_leaves_on() {
        let p = Vec3::new(0.0, 1.0, 0.0);
        let out = spawn_ray(p, Vec3::Y, Vec3::new(1.0, 1.0, 0.0));
        assert!(out.origin.y > 1.0);
        let inward = spawn_ray(p, Vec3::Y, Vec3::new(1.0, -1.0, 0.0));
        assert!(inward.origin.y < 1.0);
    }
}
