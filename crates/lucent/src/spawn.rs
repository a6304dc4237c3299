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
//!    the ray leaves on, by the error bound projected on the normal, and each coordinate is
//!    then rounded one float further away (pbrt-v4's `OffsetRayOrigin`). Nothing is fixed in
//!    size: a scene 1e5 from the origin, or scaled by 1e-6, is offset in proportion. (Wächter
//!    & Binder's 256 ulps on top of the bound moved origins by 2 units at 1e5, over a unit
//!    sphere's shadow; their fixed 1.5e-5 near the origin was larger than a scene at 1e-6.)
//! 3. **The surface left is known.** A plane or triangle cannot be met again by a ray leaving
//!    it; a sphere cannot be met again by a ray leaving it outwards, and one going inwards
//!    meets it only at its far side. [`Leaving`] tells the scene queries so.

use crate::shape::{SurfaceHit, SurfaceId};
use glam::Vec3;
use lucent_accel::Ray;

/// `p` moved off the surface along `n` (unit, pointing to the side the new ray leaves on) by
/// the error bound `error` projected on `n`, each coordinate then moved one float further to
/// the normal's side (pbrt-v4's `OffsetRayOrigin`): the sum itself rounds, possibly back
/// towards the surface. The move scales with the hit's own error, so it is as small relative to the scene
/// 1e5 from the origin as at it, and at a scale of 1e-6 as at 1.
#[inline]
pub fn offset_origin(p: Vec3, n: Vec3, error: Vec3) -> Vec3 {
    let offset = n.abs().dot(error) * n;
    let moved = p + offset;
    // By the normal's signs, not the offset's: with no error the origin still leaves.
    let away = |v: f32, n: f32| -> f32 {
        if n > 0.0 {
            v.next_up()
        } else if n < 0.0 {
            v.next_down()
        } else {
            v
        }
    };
    Vec3::new(away(moved.x, n.x), away(moved.y, n.y), away(moved.z, n.z))
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

/// A ray leaving the surface of `hit` along `dir` (unit), and what it leaves. (Always inlined:
/// once the lane group's scatter grew with more materials, the compiler stopped inlining it
/// there, and the Cornell box's paths took 5% longer.)
#[inline(always)]
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
