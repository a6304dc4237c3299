//! The watertight ray–triangle test (Woop, Benthin & Wald, "Watertight Ray/Triangle
//! Intersection", JCGT 2013), in the form every triangle query of lucent uses.
//!
//! It lives in this crate, beside the wide BVH's four-at-a-time version of it
//! ([`crate::wide_bvh`]), so that both are written from the same per-ray [`Shear`] and
//! perform the same arithmetic in the same order: their answers agree bit for bit.

use crate::Ray;
use glam::Vec3;

/// Where a ray meets a triangle `(A, B, C)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// Barycentric weights `(a1, a2, a3)` of `A`, `B`, `C`: the point is `a1·A + a2·B + a3·C`.
    pub bary: [f32; 3],
}

impl TriangleHit {
    /// The hit point from the barycentric weights: more accurate than `o + t·d`, because it
    /// does not carry the error of a long ray.
    pub fn point(&self, [a, b, c]: [Vec3; 3]) -> Vec3 {
        self.bary[0] * a + self.bary[1] * b + self.bary[2] * c
    }
}

/// The per-ray part of the test: the axes permuted so that z is the direction's largest
/// component (x and y swapped when it is negative, to keep the frame's handedness), and the
/// shear that maps the direction onto +z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shear {
    /// Axis that becomes x.
    pub kx: usize,
    /// Axis that becomes y.
    pub ky: usize,
    /// Axis that becomes z (the direction's largest component).
    pub kz: usize,
    /// `d[kx] / d[kz]`.
    pub sx: f32,
    /// `d[ky] / d[kz]`.
    pub sy: f32,
    /// `1 / d[kz]`.
    pub sz: f32,
}

impl Shear {
    /// The shear of `ray`'s direction. Written without branches: for incoherent rays the
    /// largest axis and the sign are a coin toss, and mispredicted branches here were a few
    /// percent of a closest-hit query.
    #[inline]
    pub fn new(ray: &Ray) -> Self {
        let d = ray.dir.to_array();
        let a = ray.dir.abs().to_array();
        // The first of the largest components (as `Vec3::max_position`).
        let y_over_x = usize::from(a[1] > a[0]);
        let largest = if y_over_x == 1 { a[1] } else { a[0] };
        let kz = if a[2] > largest { 2 } else { y_over_x };
        // (kz + 1) % 3 and (kz + 2) % 3, swapped when d[kz] < 0 to keep the winding.
        const NEXT: [usize; 3] = [1, 2, 0];
        const AFTER: [usize; 3] = [2, 0, 1];
        let (kx, ky) = if d[kz] < 0.0 {
            (AFTER[kz], NEXT[kz])
        } else {
            (NEXT[kz], AFTER[kz])
        };
        Self::with_axes(d, [kx, ky, kz])
    }

    /// The shear of direction `d` onto +z once its axes are chosen.
    #[inline(always)]
    fn with_axes(d: [f32; 3], [kx, ky, kz]: [usize; 3]) -> Self {
        let sz = 1.0 / d[kz];
        Self {
            kx,
            ky,
            kz,
            sx: d[kx] * sz,
            sy: d[ky] * sz,
            sz,
        }
    }
}

/// The watertight test.
///
/// The vertices are moved into a frame where the ray starts at the origin and runs along +z
/// (translate, permute, shear), so the test becomes a 2D edge-function test at the origin. Two
/// triangles sharing an edge evaluate that edge's function from the same two transformed
/// vertices, so their values are exact negatives of each other and the ray cannot slip between
/// them; when an edge function rounds to exactly zero, all three are recomputed in double
/// precision so that their signs are right. Hits in `(0, t_max)` count.
#[inline]
pub fn watertight(ray: &Ray, [p0, p1, p2]: [Vec3; 3], t_max: f32) -> Option<TriangleHit> {
    watertight_sheared(ray, &Shear::new(ray), [p0, p1, p2], t_max)
}

/// [`watertight`] with the ray's shear computed once by the caller.
#[inline]
pub fn watertight_sheared(
    ray: &Ray,
    s: &Shear,
    [p0, p1, p2]: [Vec3; 3],
    t_max: f32,
) -> Option<TriangleHit> {
    let (kx, ky, kz) = (s.kx, s.ky, s.kz);
    let (a, b, c) = (p0 - ray.origin, p1 - ray.origin, p2 - ray.origin);
    let (ax, ay) = (a[kx] - s.sx * a[kz], a[ky] - s.sy * a[kz]);
    let (bx, by) = (b[kx] - s.sx * b[kz], b[ky] - s.sy * b[kz]);
    let (cx, cy) = (c[kx] - s.sx * c[kz], c[ky] - s.sy * c[kz]);

    let mut u = cx * by - cy * bx;
    let mut v = ax * cy - ay * cx;
    let mut w = bx * ay - by * ax;
    if u == 0.0 || v == 0.0 || w == 0.0 {
        [u, v, w] = edge_functions_f64([ax, ay], [bx, by], [cx, cy]);
    }
    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 {
        return None;
    }
    let (az, bz, cz) = (s.sz * a[kz], s.sz * b[kz], s.sz * c[kz]);
    let inv = 1.0 / det;
    let t = (u * az + v * bz + w * cz) * inv;
    (t > 0.0 && t < t_max).then_some(TriangleHit {
        t,
        bary: [u * inv, v * inv, w * inv],
    })
}

/// The three edge functions in double precision, rounded back: exact signs where single
/// precision rounded to zero.
#[inline(never)]
pub fn edge_functions_f64([ax, ay]: [f32; 2], [bx, by]: [f32; 2], [cx, cy]: [f32; 2]) -> [f32; 3] {
    let e = |px: f32, py: f32, qx: f32, qy: f32| {
        (f64::from(px) * f64::from(qy) - f64::from(py) * f64::from(qx)) as f32
    };
    [e(cx, cy, bx, by), e(ax, ay, cx, cy), e(bx, by, ax, ay)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// The shear as first written, with branches: `max_position`, then the swap.
    fn shear_by_branches(ray: &Ray) -> Shear {
        let d = ray.dir;
        let kz = d.abs().max_position();
        let (mut kx, mut ky) = ((kz + 1) % 3, (kz + 2) % 3);
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        Shear::with_axes(d.to_array(), [kx, ky, kz])
    }

    #[test]
    fn the_branchless_shear_is_the_shear_with_branches() {
        let values = [0.0, -0.0, 1.0, -1.0, 0.5, -0.5, 2.0, -2.0, 1e-30, f32::NAN];
        let mut tried = 0;
        for &x in &values {
            for &y in &values {
                for &z in &values {
                    let ray = Ray::new(Vec3::ZERO, Vec3::new(x, y, z));
                    let (a, b) = (Shear::new(&ray), shear_by_branches(&ray));
                    assert_eq!((a.kx, a.ky, a.kz), (b.kx, b.ky, b.kz), "{:?}", ray.dir);
                    for (p, q) in [(a.sx, b.sx), (a.sy, b.sy), (a.sz, b.sz)] {
                        assert!(p.to_bits() == q.to_bits() || p.is_nan() && q.is_nan());
                    }
                    tried += 1;
                }
            }
        }
        assert_eq!(tried, 1000);
    }
}
