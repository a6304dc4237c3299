//! The 4-wide BVH specialised for triangle meshes: leaves hold packs of four triangles in
//! structure-of-arrays form, tested against a ray at once by a SIMD version of the watertight
//! test that performs the scalar test's arithmetic lane by lane, in the same order, so that it
//! returns the same hits bit for bit ([`crate::triangle::watertight_sheared`]).

use super::{WIDTH, WideBvh, build_options};
use crate::triangle::{Shear, TriangleHit, edge_functions_f64};
use crate::{Aabb, Bvh, Ray, TraversalStats};
use glam::Vec3;
use wide::f32x4;

/// Four triangles: `v[vertex][axis][lane]`, and the triangles' indices (`u32::MAX` for an
/// unused lane, whose vertices are NaN and never hit).
#[derive(Clone, Copy, Debug)]
#[repr(C, align(16))]
struct Pack {
    v: [[[f32; WIDTH]; 3]; 3],
    ids: [u32; WIDTH],
}

/// A 4-wide BVH over a triangle mesh, with the triangles stored in its leaves.
#[derive(Clone, Debug, Default)]
pub struct WideTriangleBvh {
    /// Leaves refer to packs: (first pack, number of packs).
    bvh: WideBvh,
    packs: Vec<Pack>,
}

impl WideTriangleBvh {
    /// Builds over the triangles `triangles` of `positions` (indices must be in range).
    pub fn new(positions: &[Vec3], triangles: &[[u32; 3]]) -> Self {
        let vertices = |t: u32| triangles[t as usize].map(|i| positions[i as usize]);
        let boxes: Vec<Aabb> = (0..triangles.len() as u32)
            .map(|t| Aabb::from_points(vertices(t)))
            .collect();
        let mut bvh = WideBvh::from_binary(&Bvh::build(&boxes, &build_options()));
        let mut packs = Vec::with_capacity(triangles.len().div_ceil(WIDTH));
        // Re-point every leaf from primitive slots to packs of its triangles.
        let mut repack = |first: u32, count: u32| -> (u32, u32) {
            let start = packs.len() as u32;
            for chunk in bvh.prims[first as usize..(first + count) as usize].chunks(WIDTH) {
                let mut pack = Pack {
                    v: [[[f32::NAN; WIDTH]; 3]; 3],
                    ids: [u32::MAX; WIDTH],
                };
                for (lane, &t) in chunk.iter().enumerate() {
                    pack.ids[lane] = t;
                    for (k, p) in vertices(t).iter().enumerate() {
                        for axis in 0..3 {
                            pack.v[k][axis][lane] = p[axis];
                        }
                    }
                }
                packs.push(pack);
            }
            (start, packs.len() as u32 - start)
        };
        if let Some((first, count)) = bvh.root_leaf {
            bvh.root_leaf = Some(repack(first, count));
        }
        for n in 0..bvh.nodes.len() {
            for k in 0..WIDTH {
                let count = bvh.nodes[n].count[k];
                if count != 0 && count != super::EMPTY {
                    let (first, packs) = repack(bvh.nodes[n].child[k], count);
                    bvh.nodes[n].child[k] = first;
                    bvh.nodes[n].count[k] = packs;
                }
            }
        }
        bvh.prims = Vec::new();
        Self { bvh, packs }
    }

    /// Nodes, depth and bytes (nodes plus triangle packs).
    pub fn info(&self) -> (usize, usize, usize) {
        (
            self.bvh.nodes.len(),
            self.bvh.depth(),
            self.bvh.memory_bytes() + self.packs.len() * size_of::<Pack>(),
        )
    }

    /// The nearest triangle hit in `(0, t_max]` (inclusive, so that the caller can judge ties),
    /// the lower triangle index winning a tie, leaving out triangle `skip`; `t` and weights
    /// exactly as [`crate::triangle::watertight`] computes them.
    pub fn closest_hit(
        &self,
        ray: &Ray,
        t_max: f32,
        skip: Option<u32>,
        stats: &mut TraversalStats,
    ) -> Option<(u32, TriangleHit)> {
        let shear = Shear::new(ray);
        let pre = PackRay::new(ray, &shear);
        let mut best: Option<(u32, TriangleHit)> = None;
        let visit = |first: u32, count: u32, t_max: &mut f32, stats: &mut TraversalStats| {
            let mut found = false;
            for pack in &self.packs[first as usize..(first + count) as usize] {
                stats.primitives_tested += WIDTH as u64;
                let (mut mask, t, bary) = pre.test(pack, *t_max);
                while mask != 0 {
                    let lane = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    let id = pack.ids[lane];
                    if skip == Some(id) {
                        continue;
                    }
                    let better =
                        t[lane] < *t_max || best.is_none_or(|(b, h)| t[lane] == h.t && id < b);
                    if better {
                        *t_max = t[lane];
                        best = Some((
                            id,
                            TriangleHit {
                                t: t[lane],
                                bary: [bary[0][lane], bary[1][lane], bary[2][lane]],
                            },
                        ));
                        found = true;
                    }
                }
            }
            found
        };
        if ray.has_parallel_axis() {
            self.bvh.closest_walk::<true, _>(ray, t_max, stats, visit);
        } else {
            self.bvh.closest_walk::<false, _>(ray, t_max, stats, visit);
        }
        best
    }

    /// Calls `leaf(triangle)` for triangles hit in `(0, t_max)` until it returns `true`;
    /// returns whether it did.
    pub fn any_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, mut leaf: F) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        let shear = Shear::new(ray);
        let pre = PackRay::new(ray, &shear);
        // The pack test keeps t ≤ its limit; one ulp below t_max makes it t < t_max.
        let limit = t_max.next_down();
        let visit = |first: u32, count: u32, stats: &mut TraversalStats| {
            for pack in &self.packs[first as usize..(first + count) as usize] {
                stats.primitives_tested += WIDTH as u64;
                let (mut mask, _, _) = pre.test(pack, limit);
                while mask != 0 {
                    let lane = mask.trailing_zeros() as usize;
                    mask &= mask - 1;
                    if leaf(pack.ids[lane]) {
                        return true;
                    }
                }
            }
            false
        };
        if ray.has_parallel_axis() {
            self.bvh.any_walk::<true, _>(ray, t_max, stats, visit)
        } else {
            self.bvh.any_walk::<false, _>(ray, t_max, stats, visit)
        }
    }
}

/// The ray's origin and shear, spread over four lanes.
struct PackRay {
    origin: [f32x4; 3],
    sx: f32x4,
    sy: f32x4,
    sz: f32x4,
    axes: [usize; 3],
}

impl PackRay {
    fn new(ray: &Ray, s: &Shear) -> Self {
        let o = ray.origin;
        Self {
            origin: [f32x4::splat(o.x), f32x4::splat(o.y), f32x4::splat(o.z)],
            sx: f32x4::splat(s.sx),
            sy: f32x4::splat(s.sy),
            sz: f32x4::splat(s.sz),
            axes: [s.kx, s.ky, s.kz],
        }
    }

    /// The watertight test on four triangles: the mask of lanes hit in `(0, t_max]`, and each
    /// lane's `t` and barycentric weights.
    #[inline(always)]
    fn test(&self, pack: &Pack, t_max: f32) -> (u32, [f32; WIDTH], [[f32; WIDTH]; 3]) {
        let [kx, ky, kz] = self.axes;
        // Vertex k relative to the origin, per axis: the scalar test's `p − o`.
        let rel = |k: usize, axis: usize| f32x4::from(pack.v[k][axis]) - self.origin[axis];
        let (a, b, c) = (
            [rel(0, 0), rel(0, 1), rel(0, 2)],
            [rel(1, 0), rel(1, 1), rel(1, 2)],
            [rel(2, 0), rel(2, 1), rel(2, 2)],
        );
        let (ax, ay) = (a[kx] - self.sx * a[kz], a[ky] - self.sy * a[kz]);
        let (bx, by) = (b[kx] - self.sx * b[kz], b[ky] - self.sy * b[kz]);
        let (cx, cy) = (c[kx] - self.sx * c[kz], c[ky] - self.sy * c[kz]);
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        let zero = f32x4::splat(0.0);
        let exact_zero = (u.simd_eq(zero) | v.simd_eq(zero) | w.simd_eq(zero)).to_bitmask();
        if exact_zero != 0 {
            // Rare: redo those lanes' edge functions in double precision, as the scalar test does.
            let (mut ua, mut va, mut wa) = (u.to_array(), v.to_array(), w.to_array());
            let (axa, aya, bxa, bya, cxa, cya) = (
                ax.to_array(),
                ay.to_array(),
                bx.to_array(),
                by.to_array(),
                cx.to_array(),
                cy.to_array(),
            );
            let mut m = exact_zero;
            while m != 0 {
                let l = m.trailing_zeros() as usize;
                m &= m - 1;
                [ua[l], va[l], wa[l]] =
                    edge_functions_f64([axa[l], aya[l]], [bxa[l], bya[l]], [cxa[l], cya[l]]);
            }
            (u, v, w) = (f32x4::from(ua), f32x4::from(va), f32x4::from(wa));
        }
        let negative = u.simd_lt(zero) | v.simd_lt(zero) | w.simd_lt(zero);
        let positive = u.simd_gt(zero) | v.simd_gt(zero) | w.simd_gt(zero);
        let det = u + v + w;
        let (az, bz, cz) = (self.sz * a[kz], self.sz * b[kz], self.sz * c[kz]);
        let inv = f32x4::splat(1.0) / det;
        let t = (u * az + v * bz + w * cz) * inv;
        let outside = (negative & positive).to_bitmask();
        let hit = (t.simd_gt(zero) & t.simd_le(f32x4::splat(t_max))).to_bitmask()
            & !(det.simd_eq(zero).to_bitmask());
        let mask = hit & !outside & 0b1111;
        (
            mask,
            t.to_array(),
            [
                (u * inv).to_array(),
                (v * inv).to_array(),
                (w * inv).to_array(),
            ],
        )
    }
}
