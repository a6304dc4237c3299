//! The wide BVH specialised for triangle meshes: leaves hold packs of eight triangles in
//! structure-of-arrays form, tested against a ray at once by a SIMD version of the watertight
//! test that performs the scalar test's arithmetic lane by lane, in the same order, so that it
//! returns the same hits bit for bit ([`crate::triangle::watertight_sheared`]).

use super::lanes::{LANES, Lanes};
#[cfg(target_arch = "x86_64")]
use super::simd::Avx;
use super::simd::{Simd, Sse};
use super::traverse::{AnyLeaf, ClosestLeaf};
use super::{Cut, EMPTY, NodeW, WIDTH, WideBvh, build_options};
use crate::triangle::{Shear, TriangleHit, edge_functions_f64};
use crate::{Aabb, Bvh, Frustum, Ray, TraversalStats};
use glam::Vec3;

/// Eight triangles: `v[vertex][axis]` lanes, and the triangles' indices (`u32::MAX` for an
/// unused lane, whose vertices are NaN and never hit). 320 bytes, aligned to cache lines so
/// that a pack spans five of them, not six.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(super) struct Pack {
    v: [[Lanes; 3]; 3],
    ids: [u32; LANES],
}

/// A wide BVH over a triangle mesh, with the triangles stored in its leaves.
#[derive(Clone, Debug, Default)]
pub struct WideTriangleBvh {
    /// Leaves refer to packs: (first pack, number of packs).
    pub(super) bvh: WideBvh,
    pub(super) packs: Vec<Pack>,
}

/// Triangles per leaf: one pack. (Measured on the bunny and teapot: leaves of 8 beat 2, 4, 6,
/// 12 and 16; the SAH counts a leaf's cost in packs, so it stops splitting at one pack.)
const LEAF_SIZE: usize = 8;

/// The pack of triangles `ids` (at most [`LANES`]), whose corners `vertices` gives.
fn pack(ids: &[u32], vertices: impl Fn(u32) -> [Vec3; 3]) -> Pack {
    let mut pack = Pack {
        v: [[Lanes::splat(f32::NAN); 3]; 3],
        ids: [u32::MAX; LANES],
    };
    for (lane, &t) in ids.iter().enumerate() {
        pack.ids[lane] = t;
        for (k, p) in vertices(t).iter().enumerate() {
            for axis in 0..3 {
                pack.v[k][axis].0[lane] = p[axis];
            }
        }
    }
    pack
}

impl WideTriangleBvh {
    /// Builds over the triangles `triangles` of `positions` (indices must be in range).
    pub fn new(positions: &[Vec3], triangles: &[[u32; 3]]) -> Self {
        Self::with_options(positions, triangles, &build_options(LEAF_SIZE))
    }

    /// [`WideTriangleBvh::new`] with the binary build's settings given.
    pub fn with_options(
        positions: &[Vec3],
        triangles: &[[u32; 3]],
        options: &crate::bvh::BuildOptions,
    ) -> Self {
        use rayon::prelude::*;
        let vertices = |t: u32| triangles[t as usize].map(|i| positions[i as usize]);
        let box_of = |t: usize| Aabb::from_points(vertices(t as u32));
        let mut bvh = WideBvh::from_binary(&Bvh::build_from(triangles.len(), box_of, options));
        // Re-point every leaf from primitive slots to packs (the root leaf, then node by node,
        // child by child), noting each pack's slots; the packs are then filled in parallel
        // straight into their place.
        let mut slots: Vec<std::ops::Range<usize>> = Vec::new();
        let mut repack = |first: u32, count: u32| -> (u32, u32) {
            let start = slots.len() as u32;
            let (first, end) = (first as usize, (first + count) as usize);
            slots.extend((first..end).step_by(LANES).map(|s| s..end.min(s + LANES)));
            (start, slots.len() as u32 - start)
        };
        if let Some((first, count)) = bvh.root_leaf {
            bvh.root_leaf = Some(repack(first, count));
        }
        for node in &mut bvh.nodes {
            for k in 0..WIDTH {
                let count = node.count[k];
                if count != 0 && count != EMPTY {
                    (node.child[k], node.count[k]) = repack(node.child[k], count);
                }
            }
        }
        let prims = &bvh.prims;
        let mut packs = Vec::new();
        slots
            .par_iter()
            .map(|s| pack(&prims[s.clone()], vertices))
            .collect_into_vec(&mut packs);
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
    ) -> Option<PackedHit> {
        self.closest_from(ray, t_max, skip, stats, &[])
    }

    /// The closest-hit traversal from `entry` (empty: the root), on the widest SIMD the
    /// processor has.
    #[inline]
    fn closest_from(
        &self,
        ray: &Ray,
        t_max: f32,
        skip: Option<u32>,
        stats: &mut TraversalStats,
        entry: &[NodeW],
    ) -> Option<PackedHit> {
        if !ray.is_traceable() {
            return None;
        }
        #[cfg(target_arch = "x86_64")]
        if let Some(avx) = Avx::detect() {
            // SAFETY: `closest_avx2` is compiled for AVX2, which the processor has.
            #[allow(unsafe_code)]
            return unsafe { self.closest_avx2(avx, ray, t_max, skip, stats, entry) };
        }
        self.closest(Sse, ray, t_max, skip, stats, entry)
    }

    /// Where the rays of beam `frustum` start in this tree (see [`WideBvh::cut`]).
    pub fn cut(&self, frustum: &Frustum) -> Cut {
        self.bvh.cut(frustum)
    }

    /// [`WideTriangleBvh::cut`] with at most `budget` entries (see [`WideBvh::cut_within`]).
    pub fn cut_within(&self, frustum: &Frustum, budget: usize) -> Cut {
        self.bvh.cut_within(frustum, budget)
    }

    /// [`WideTriangleBvh::closest_hit`] for a ray of the beam that `cut` was made for: the
    /// same hit, from fewer nodes.
    pub fn closest_hit_in(
        &self,
        cut: &Cut,
        ray: &Ray,
        t_max: f32,
        skip: Option<u32>,
        stats: &mut TraversalStats,
    ) -> Option<PackedHit> {
        if cut.misses {
            return None;
        }
        self.closest_from(ray, t_max, skip, stats, &cut.nodes)
    }

    /// Calls `leaf(triangle)` for triangles hit in `(0, t_max)` until it returns `true`;
    /// returns whether it did.
    pub fn any_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, leaf: F) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        self.any_from(ray, t_max, stats, leaf, &[])
    }

    /// The any-hit traversal from `entry` (empty: the root), on the widest SIMD the processor
    /// has.
    #[inline]
    fn any_from<F>(
        &self,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        leaf: F,
        entry: &[NodeW],
    ) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        if !ray.is_traceable() {
            return false;
        }
        #[cfg(target_arch = "x86_64")]
        if let Some(avx) = Avx::detect() {
            // SAFETY: `any_avx2` is compiled for AVX2, which the processor has.
            #[allow(unsafe_code)]
            return unsafe { self.any_avx2(avx, ray, t_max, stats, leaf, entry) };
        }
        self.any(Sse, ray, t_max, stats, leaf, entry)
    }

    /// [`WideTriangleBvh::any_hit`] for a ray of the beam that `cut` was made for (a shadow
    /// beam, see [`Frustum::from_point_over`]): the same answer, and the same triangles
    /// offered to `leaf` when it never says stop, though in another order.
    pub fn any_hit_in<F>(
        &self,
        cut: &Cut,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        leaf: F,
    ) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        !cut.misses && self.any_from(ray, t_max, stats, leaf, &cut.nodes)
    }

    /// [`WideTriangleBvh::closest_hit`] on the baseline instruction set (two SSE registers per
    /// eight lanes) even where AVX2 is available: for tests that hold both paths to the same
    /// answers.
    #[doc(hidden)]
    pub fn closest_hit_baseline(
        &self,
        ray: &Ray,
        t_max: f32,
        skip: Option<u32>,
        stats: &mut TraversalStats,
    ) -> Option<PackedHit> {
        self.closest(Sse, ray, t_max, skip, stats, &[])
    }

    /// [`WideTriangleBvh::any_hit`] on the baseline instruction set (see `closest_hit_baseline`).
    #[doc(hidden)]
    pub fn any_hit_baseline<F: FnMut(u32) -> bool>(
        &self,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        leaf: F,
    ) -> bool {
        self.any(Sse, ray, t_max, stats, leaf, &[])
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn closest_avx2(
        &self,
        s: Avx,
        ray: &Ray,
        t_max: f32,
        skip: Option<u32>,
        stats: &mut TraversalStats,
        entry: &[NodeW],
    ) -> Option<PackedHit> {
        self.closest(s, ray, t_max, skip, stats, entry)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn any_avx2<F>(
        &self,
        s: Avx,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        leaf: F,
        entry: &[NodeW],
    ) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        self.any(s, ray, t_max, stats, leaf, entry)
    }

    #[inline(always)]
    fn closest<S: Simd>(
        &self,
        s: S,
        ray: &Ray,
        t_max: f32,
        skip: Option<u32>,
        stats: &mut TraversalStats,
        entry: &[NodeW],
    ) -> Option<PackedHit> {
        if !ray.is_traceable() {
            return None;
        }
        let mut leaves = NearestInPacks {
            s,
            packs: &self.packs,
            pre: PackRay::new(ray),
            skip,
            best: None,
        };
        self.bvh
            .closest_walk(s, ray, t_max, stats, &mut leaves, entry);
        leaves.best
    }

    #[inline(always)]
    fn any<S: Simd, F>(
        &self,
        s: S,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        leaf: F,
        entry: &[NodeW],
    ) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        if !ray.is_traceable() {
            return false;
        }
        // The pack test keeps t ≤ its limit; one ulp below t_max makes it t < t_max.
        let mut leaves = BlockersInPacks {
            s,
            packs: &self.packs,
            pre: PackRay::new(ray),
            limit: t_max.next_down(),
            leaf,
        };
        self.bvh.any_walk(s, ray, t_max, stats, &mut leaves, entry)
    }
}

/// A triangle hit by [`WideTriangleBvh::closest_hit`]: its index, the hit, its vertices.
pub type PackedHit = (u32, TriangleHit, [Vec3; 3]);

/// The closest-hit leaf test: the nearest hit over packs, ties to the lower triangle index.
pub(super) struct NearestInPacks<'a, S> {
    pub(super) s: S,
    pub(super) packs: &'a [Pack],
    pub(super) pre: PackRay,
    pub(super) skip: Option<u32>,
    pub(super) best: Option<PackedHit>,
}

impl<S: Simd> ClosestLeaf for NearestInPacks<'_, S> {
    const AT_ONCE: bool = true;

    #[inline(always)]
    fn visit(
        &mut self,
        first: u32,
        count: u32,
        t_max: &mut f32,
        stats: &mut TraversalStats,
    ) -> bool {
        let mut found = false;
        for pack in &self.packs[first as usize..(first + count) as usize] {
            stats.primitives_tested += LANES as u64;
            let (mut mask, t, bary) = self.pre.test(self.s, pack, *t_max);
            while mask != 0 {
                let lane = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                let id = pack.ids[lane];
                if self.skip == Some(id) {
                    continue;
                }
                let better = t.0[lane] < *t_max
                    || self.best.is_none_or(|(b, h, _)| t.0[lane] == h.t && id < b);
                if better {
                    *t_max = t.0[lane];
                    let bary = [bary[0].0[lane], bary[1].0[lane], bary[2].0[lane]];
                    let v = |k: usize| {
                        Vec3::new(
                            pack.v[k][0].0[lane],
                            pack.v[k][1].0[lane],
                            pack.v[k][2].0[lane],
                        )
                    };
                    self.best = Some((id, TriangleHit { t: t.0[lane], bary }, [v(0), v(1), v(2)]));
                    found = true;
                }
            }
        }
        found
    }
}

/// The any-hit leaf test: every triangle hit before `limit`, to `leaf`, until it says stop.
struct BlockersInPacks<'a, S, F> {
    s: S,
    packs: &'a [Pack],
    pre: PackRay,
    limit: f32,
    leaf: F,
}

impl<S: Simd, F: FnMut(u32) -> bool> AnyLeaf for BlockersInPacks<'_, S, F> {
    #[inline(always)]
    fn visit(&mut self, first: u32, count: u32, stats: &mut TraversalStats) -> bool {
        for pack in &self.packs[first as usize..(first + count) as usize] {
            stats.primitives_tested += LANES as u64;
            let (mut mask, _, _) = self.pre.test(self.s, pack, self.limit);
            while mask != 0 {
                let lane = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                if (self.leaf)(pack.ids[lane]) {
                    return true;
                }
            }
        }
        false
    }
}

/// The ray's origin and shear.
pub(super) struct PackRay {
    origin: [f32; 3],
    shear: Shear,
}

impl PackRay {
    pub(super) fn new(ray: &Ray) -> Self {
        Self {
            origin: ray.origin.to_array(),
            shear: Shear::new(ray),
        }
    }

    /// The watertight test on eight triangles: the mask of lanes hit in `(0, t_max]`, and each
    /// lane's `t` and barycentric weights.
    #[inline(always)]
    fn test<S: Simd>(&self, s: S, pack: &Pack, t_max: f32) -> (u32, Lanes, [Lanes; 3]) {
        let sh = &self.shear;
        let (kx, ky, kz) = (sh.kx, sh.ky, sh.kz);
        let (sx, sy, sz) = (s.splat(sh.sx), s.splat(sh.sy), s.splat(sh.sz));
        // Vertex k relative to the origin along an axis: the scalar test's `p − o`.
        let rel =
            |k: usize, axis: usize| s.sub(s.load(&pack.v[k][axis]), s.splat(self.origin[axis]));
        let (a, b, c) = (
            [rel(0, kx), rel(0, ky), rel(0, kz)],
            [rel(1, kx), rel(1, ky), rel(1, kz)],
            [rel(2, kx), rel(2, ky), rel(2, kz)],
        );
        let shear2 = |p: [S::V; 3]| (s.sub(p[0], s.mul(sx, p[2])), s.sub(p[1], s.mul(sy, p[2])));
        let ((ax, ay), (bx, by), (cx, cy)) = (shear2(a), shear2(b), shear2(c));
        let cross = |px: S::V, py: S::V, qx: S::V, qy: S::V| s.sub(s.mul(px, qy), s.mul(py, qx));
        let (mut u, mut v, mut w) = (
            cross(cx, cy, bx, by),
            cross(ax, ay, cx, cy),
            cross(bx, by, ax, ay),
        );
        let zero = s.splat(0.0);
        let mut exact_zero = s.eq(u, zero) | s.eq(v, zero) | s.eq(w, zero);
        if exact_zero != 0 {
            // Rare: redo those lanes' edge functions in double precision, as the scalar test does.
            let (mut ul, mut vl, mut wl) = (s.store(u), s.store(v), s.store(w));
            let e = [
                s.store(ax),
                s.store(ay),
                s.store(bx),
                s.store(by),
                s.store(cx),
                s.store(cy),
            ];
            while exact_zero != 0 {
                let l = exact_zero.trailing_zeros() as usize;
                exact_zero &= exact_zero - 1;
                [ul.0[l], vl.0[l], wl.0[l]] = edge_functions_f64(
                    [e[0].0[l], e[1].0[l]],
                    [e[2].0[l], e[3].0[l]],
                    [e[4].0[l], e[5].0[l]],
                );
            }
            (u, v, w) = (s.load(&ul), s.load(&vl), s.load(&wl));
        }
        let negative = s.lt(u, zero) | s.lt(v, zero) | s.lt(w, zero);
        let positive = s.lt(zero, u) | s.lt(zero, v) | s.lt(zero, w);
        // Unused lanes hold NaN vertices: their edge functions are NaN, neither sign.
        let inside = !(negative & positive) & s.eq(u, u);
        if inside == 0 {
            // The ray passes beside all eight: skip the division (most packs, for most rays).
            let none = Lanes::splat(0.0);
            return (0, none, [none; 3]);
        }
        let det = s.add(s.add(u, v), w);
        let (az, bz, cz) = (s.mul(sz, a[2]), s.mul(sz, b[2]), s.mul(sz, c[2]));
        let inv = s.div(s.splat(1.0), det);
        let t = s.mul(s.add(s.add(s.mul(u, az), s.mul(v, bz)), s.mul(w, cz)), inv);
        let in_range = s.lt(zero, t) & s.le(t, s.splat(t_max));
        let mask = in_range & inside & !s.eq(det, zero);
        (
            mask,
            s.store(t),
            [
                s.store(s.mul(u, inv)),
                s.store(s.mul(v, inv)),
                s.store(s.mul(w, inv)),
            ],
        )
    }
}
