//! The one self-intersection policy: where a secondary ray starts, and what it may hit.
//!
//! A hit point carries rounding error, so a ray started exactly there may hit the surface it
//! leaves (shadow acne, speckled reflections) or, going inwards, start on the wrong side.
//! Three measures, together, make every secondary ray safe with `t > 0` and no epsilon at
//! any call site:
//!
//! 1. **Accurate hit points with error bounds.** Sphere hits are re-projected onto the sphere,
//!    triangle hits interpolated from their barycentric weights, plane hits have their
//!    distance from the plane removed; each carries a bound on its remaining error
//!    ([`SurfaceHit::error`], pbrt's `pError`).
//! 2. **An offset off the surface.** The origin moves along the geometric normal, to the side
//!    the ray leaves on, by the error bound projected on the normal, and then by 256 units in
//!    the last place of each coordinate (Wächter & Binder, "A Fast and Robust Method for
//!    Avoiding Self-Intersection", Ray Tracing Gems, 2019), or a small fixed amount near the
//!    origin where ulps vanish.
//! 3. **The surface left is known.** A plane or triangle cannot be met again by a ray leaving
//!    it; a sphere cannot be met again by a ray leaving it outwards, and one going inwards
//!    meets it only at its far side. [`Leaving`] tells the scene queries so.

use crate::shape::{SurfaceHit, SurfaceId};
use glam::Vec3;
use lucent_accel::Ray;

/// Below this magnitude a coordinate is offset by a fixed amount rather than in ulps.
const ORIGIN: f32 = 1.0 / 32.0;
/// The fixed offset near the origin, per unit of normal.
const FLOAT_SCALE: f32 = 1.0 / 65536.0;
/// The offset in ulps, per unit of normal.
const INT_SCALE: f32 = 256.0;

/// `p` moved off the surface along `n` (unit, pointing to the side the new ray leaves on) by
/// the error bound `error` projected on `n`, then by a few ulps.
#[inline]
pub fn offset_origin(p: Vec3, n: Vec3, error: Vec3) -> Vec3 {
    let p = p + n.abs().dot(error) * n;
    let offset_axis = |p: f32, n: f32| -> f32 {
        if p.abs() < ORIGIN {
            return p + FLOAT_SCALE * n;
        }
        let ulps = (INT_SCALE * n) as i32;
        // Adding to the bit pattern of a negative float moves it towards −∞, so flip the sign.
        let step = if p < 0.0 { ulps.wrapping_neg() } else { ulps };
        f32::from_bits((p.to_bits() as i32).wrapping_add(step) as u32)
    };
    Vec3::new(
        offset_axis(p.x, n.x),
        offset_axis(p.y, n.y),
        offset_axis(p.z, n.z),
    )
}

/// The surface a secondary ray leaves, for the scene queries to leave out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Leaving {
    /// The surface.
    pub surface: SurfaceId,
    /// True when the ray leaves on the side the geometric normal points to (for a sphere:
    /// outwards).
    pub outward: bool,
}

/// A ray leaving the surface of `hit` along `dir` (unit), and what it leaves.
#[inline]
pub fn spawn_ray(hit: &SurfaceHit, dir: Vec3) -> (Ray, Leaving) {
    let outward = hit.normal.dot(dir) >= 0.0;
    let side = if outward { hit.normal } else { -hit.normal };
    let ray = Ray::new(offset_origin(hit.point, side, hit.error), dir);
    (
        ray,
        Leaving {
            surface: hit.surface,
            outward,
        },
    )
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
                let q = offset_origin(p, n, Vec3::ZERO);
                assert!((q - p).dot(n) > 0.0, "p = {p}, n = {n}, q = {q}");
                // Small: well under a thousandth of the point's magnitude (or of 1).
                assert!((q - p).length() < 1e-3 * p.abs().max_element().max(1.0));
            }
        }
    }

    #[test]
    fn the_error_bound_adds_to_the_offset() {
        let p = Vec3::new(0.5, 0.0, 0.5);
        let plain = offset_origin(p, Vec3::Y, Vec3::ZERO);
        let wider = offset_origin(p, Vec3::Y, Vec3::new(0.0, 1e-3, 0.0));
        assert!(wider.y - plain.y >= 0.99e-3);
    }

    #[test]
    fn spawn_picks_the_side_the_ray_leaves_on() {
        let hit = SurfaceHit {
            t: 1.0,
            point: Vec3::new(0.0, 1.0, 0.0),
            normal: Vec3::Y,
            texture_coords: Vec3::ZERO,
            shading_normal: Vec3::Y,
            uv: crate::shape::Uv::At(glam::Vec2::ZERO),
            color: crate::Rgb::WHITE,
            material: 0,
            object: 0,
            surface: SurfaceId::Sphere(3),
            bary: [0.0; 3],
            error: Vec3::ZERO,
            dpdu: Vec3::X,
            dpdv: Vec3::Z,
            tangent: None,
        };
        let (out, leaving) = spawn_ray(&hit, Vec3::new(1.0, 1.0, 0.0).normalize());
        assert!(out.origin.y > 1.0 && leaving.outward);
        let (inward, leaving) = spawn_ray(&hit, Vec3::new(1.0, -1.0, 0.0).normalize());
        assert!(inward.origin.y < 1.0 && !leaving.outward);
        assert_eq!(leaving.surface, SurfaceId::Sphere(3));
    }
}
