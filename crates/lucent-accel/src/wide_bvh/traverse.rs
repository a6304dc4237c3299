//! Traversal of the wide BVH: eight child boxes per SIMD test, nearest child first.

use super::Cut;
use super::lanes::Lanes;
#[cfg(target_arch = "x86_64")]
use super::simd::Avx;
use super::simd::{self, Simd, Sse};
use super::{EMPTY, NodeW, VIRTUAL, WIDTH, WideBvh};
use crate::aabb::{CULL_SLACK, ROUNDING_SLACK};
use crate::{Accelerator, Ray, TraversalStats};
use arrayvec::ArrayVec;

/// Stack entries: each level pushes at most seven siblings, and the binary tree's depth is
/// bounded (`BuildOptions::max_sah_depth` plus log2 of the primitive count), so a wide tree is
/// at most about 80 levels deep. (An `ArrayVec` is not zeroed on creation, unlike an array.)
pub(super) const STACK_SIZE: usize = 7 * 80;

/// A ray prepared for eight-box tests.
pub(crate) struct RayPre {
    origin: [f32; 3],
    /// `−1 / dir` (see [`RayPre::enter`]).
    neg_inv: [f32; 3],
    /// Per axis, the plane row ([`NodeW::planes`]) the ray meets first: the smallest corner's
    /// when the direction is positive, the largest corner's when it is negative.
    near: [usize; 3],
    /// The plane row it meets last.
    far: [usize; 3],
    /// A direction component is zero: the slab test can meet `0 · ∞ = NaN`.
    parallel: bool,
}

impl RayPre {
    pub(crate) fn new(ray: &Ray) -> Self {
        let row = |a: usize, negative: bool| if negative { 3 + a } else { a };
        let neg = [ray.dir.x < 0.0, ray.dir.y < 0.0, ray.dir.z < 0.0];
        Self {
            origin: ray.origin.to_array(),
            neg_inv: (-ray.inv_dir).to_array(),
            near: [row(0, neg[0]), row(1, neg[1]), row(2, neg[2])],
            far: [row(0, !neg[0]), row(1, !neg[1]), row(2, !neg[2])],
            parallel: ray.has_parallel_axis(),
        }
    }

    /// Which of the node's children the ray enters before `t_max` (a bit mask), and where.
    ///
    /// The near and far planes are picked by the direction's signs; an unused slot's inverted
    /// box (`lo = +∞`, `hi = −∞`) is never entered. A ray with a zero direction component takes
    /// the robust path, where `0 · ∞ = NaN` counts as no constraint (as in [`crate::Aabb::hit`]).
    #[inline(always)]
    pub(crate) fn enter<S: Simd>(&self, s: S, node: &NodeW, t_max: f32) -> (u32, S::V) {
        if self.parallel {
            let (mask, near) = self.enter_parallel(node, t_max);
            return (mask, s.load(&near));
        }
        // (plane − o) · (1/d): the form whose rounding Ize's bound covers. (The fused
        // plane · (1/d) − o · (1/d) is a little faster but cancels badly near the origin.)
        // Computed as (o − plane) · (−1/d), the same bits, so that the plane is read straight
        // into the subtraction (1–2% faster).
        let t = |row: usize, a: usize| {
            s.mul(
                s.sub(s.splat(self.origin[a]), s.load(&node.planes[row])),
                s.splat(self.neg_inv[a]),
            )
        };
        let near = s.max(
            s.max(t(self.near[0], 0), t(self.near[1], 1)),
            s.max(t(self.near[2], 2), s.splat(0.0)),
        );
        let exit = s.min(
            s.min(t(self.far[0], 0), t(self.far[1], 1)),
            t(self.far[2], 2),
        );
        let far = s.min(
            s.mul(exit, s.splat(ROUNDING_SLACK)),
            s.splat(t_max * CULL_SLACK),
        );
        (s.le(near, far), near)
    }

    /// The robust test, lane by lane (rays exactly parallel to an axis are rare).
    #[cold]
    fn enter_parallel(&self, node: &NodeW, t_max: f32) -> (u32, Lanes) {
        let (mut near, mut far) = ([0.0f32; WIDTH], [t_max * CULL_SLACK; WIDTH]);
        for a in 0..3 {
            for i in 0..WIDTH {
                let t0 = (self.origin[a] - node.planes[a].0[i]) * self.neg_inv[a];
                let t1 = (self.origin[a] - node.planes[3 + a].0[i]) * self.neg_inv[a];
                if t0.is_nan() || t1.is_nan() {
                    continue;
                }
                near[i] = near[i].max(t0.min(t1));
                far[i] = far[i].min(t0.max(t1) * ROUNDING_SLACK);
            }
        }
        let mask = (0..WIDTH)
            .filter(|&i| near[i] <= far[i])
            .fold(0, |m, i| m | 1 << i);
        (mask & node.used_mask(), Lanes(near))
    }
}

/// Marks a virtual node of a beam's cut on the any-hit stack (tree nodes number far fewer
/// than 2³¹).
const IN_CUT: u32 = 1 << 31;

/// A child reference on the traversal stack: (child, count, entry distance).
type Entry = (u32, u32, f32);

/// What a closest-hit traversal does at a leaf: test primitives (or packs) `first..first +
/// count`, lower `t_max` on a hit, and say whether there was one. A trait rather than a
/// closure, so that its `#[inline(always)]` body is compiled into the AVX2 twin of the loop.
pub(crate) trait ClosestLeaf {
    /// Leaves cheap enough to test as soon as their node is visited, in slot order (triangle
    /// packs); otherwise they are visited nearest first with the nodes (a top level's leaves
    /// are whole meshes, where the order saves far more than it costs).
    const AT_ONCE: bool = false;

    fn visit(
        &mut self,
        first: u32,
        count: u32,
        t_max: &mut f32,
        stats: &mut TraversalStats,
    ) -> bool;
}

/// What an any-hit traversal does at a leaf: return `true` to stop.
pub(crate) trait AnyLeaf {
    fn visit(&mut self, first: u32, count: u32, stats: &mut TraversalStats) -> bool;
}

/// A closure as a leaf visitor.
pub(crate) struct Visit<F>(pub F);

impl<F: FnMut(u32, u32, &mut f32, &mut TraversalStats) -> bool> ClosestLeaf for Visit<F> {
    #[inline(always)]
    fn visit(
        &mut self,
        first: u32,
        count: u32,
        t_max: &mut f32,
        stats: &mut TraversalStats,
    ) -> bool {
        (self.0)(first, count, t_max, stats)
    }
}

impl<F: FnMut(u32, u32, &mut TraversalStats) -> bool> AnyLeaf for Visit<F> {
    #[inline(always)]
    fn visit(&mut self, first: u32, count: u32, stats: &mut TraversalStats) -> bool {
        (self.0)(first, count, stats)
    }
}

impl WideBvh {
    /// Closest-hit traversal; `visit(first, count, t_max, stats)` tests a leaf's primitives,
    /// lowers `t_max` on a hit and returns whether it found one.
    ///
    /// `entry` is where the walk starts: empty for the root, or the virtual nodes of a beam's
    /// [`Cut`](super::Cut) (node 0 first), whose children are the tree's subtrees and leaves
    /// or further virtual nodes (count [`VIRTUAL`]).
    #[inline(always)]
    pub(crate) fn closest_walk<S: Simd, L: ClosestLeaf>(
        &self,
        s: S,
        ray: &Ray,
        mut t_max: f32,
        stats: &mut TraversalStats,
        leaf: &mut L,
        entry: &[NodeW],
    ) -> bool {
        if let Some((first, count)) = self.root_leaf {
            return self.bounds.hit(ray, t_max).is_some()
                && leaf.visit(first, count, &mut t_max, stats);
        }
        if self.nodes.is_empty() {
            return false;
        }
        let pre = RayPre::new(ray);
        let mut stack: ArrayVec<Entry, STACK_SIZE> = ArrayVec::new();
        let (mut child, mut count) = (0u32, if entry.is_empty() { 0 } else { VIRTUAL });
        let mut hit = false;
        let mut visited = 0u64;
        loop {
            if count != 0 && count != VIRTUAL {
                // A leaf from the stack (with `AT_ONCE`, only a beam's virtual nodes push them).
                hit |= leaf.visit(child, count, &mut t_max, stats);
                if let Some(next) = pop_nearer(&mut stack, t_max) {
                    (child, count) = next;
                    continue;
                }
                stats.nodes_visited += visited;
                return hit;
            }
            visited += 1;
            let node = if count == 0 {
                &self.nodes[child as usize]
            } else {
                &entry[child as usize]
            };
            let (mut mask, t) = pre.enter(s, node, t_max);
            // Leaves tested at once go in slot order, and the children that start beyond the
            // nearest hit are dropped after them. (Ordering them by distance tests fewer but
            // costs more than it saves; visiting them nearest first with the nodes was 3%
            // slower.) A beam's virtual nodes hold many leaves each: there nearest first tests
            // 30% fewer triangles, so they keep it.
            let leaves = if L::AT_ONCE && count == 0 {
                mask & s.positive(&node.count)
            } else {
                0
            };
            if leaves != 0 {
                let entered = s.store(t);
                let mut m = leaves;
                while m != 0 {
                    let i = m.trailing_zeros() as usize;
                    m &= m - 1;
                    if entered.0[i] <= t_max * CULL_SLACK {
                        hit |= leaf.visit(node.child[i], node.count[i], &mut t_max, stats);
                    }
                }
                mask &= !leaves & s.le(t, s.splat(t_max * CULL_SLACK));
            }
            if mask != 0 {
                let first = mask.trailing_zeros() as usize;
                let rest = mask & (mask - 1);
                if rest == 0 {
                    // One child entered: the common case, no sorting.
                    (child, count) = (node.child[first], node.count[first]);
                    continue;
                }
                let t = s.store(t);
                let second = rest.trailing_zeros() as usize;
                if rest & (rest - 1) == 0 {
                    // Two children: the nearer next, the farther on the stack.
                    let (near, far) = if t.0[second] < t.0[first] {
                        (second, first)
                    } else {
                        (first, second)
                    };
                    self.prefetch_node(node, far);
                    stack.push((node.child[far], node.count[far], t.0[far]));
                    (child, count) = (node.child[near], node.count[near]);
                    continue;
                }
                let mut hits: ArrayVec<Entry, WIDTH> = ArrayVec::new();
                hits.push((node.child[first], node.count[first], t.0[first]));
                let mut m = rest;
                while m != 0 {
                    let i = m.trailing_zeros() as usize;
                    m &= m - 1;
                    hits.push((node.child[i], node.count[i], t.0[i]));
                    self.prefetch_node(node, i);
                }
                sort_by_distance(&mut hits);
                stack.extend(hits[1..].iter().rev().copied());
                (child, count) = (hits[0].0, hits[0].1);
                continue;
            }
            match pop_nearer(&mut stack, t_max) {
                Some(next) => (child, count) = next,
                None => {
                    stats.nodes_visited += visited;
                    return hit;
                }
            }
        }
    }

    /// Any-hit traversal; `visit(first, count, stats)` returns `true` to stop.
    ///
    /// `entry` as for [`WideBvh::closest_walk`]: empty for the root, or a beam's virtual
    /// nodes. The leaves are visited in another order from a cut than from the root, but the
    /// same ones that hold a blocker (the cut is conservative).
    #[inline(always)]
    pub(crate) fn any_walk<S: Simd, L: AnyLeaf>(
        &self,
        s: S,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        leaf: &mut L,
        entry: &[NodeW],
    ) -> bool {
        if let Some((first, count)) = self.root_leaf {
            return self.bounds.hit(ray, t_max).is_some() && leaf.visit(first, count, stats);
        }
        if self.nodes.is_empty() {
            return false;
        }
        let pre = RayPre::new(ray);
        // Node indices, with IN_CUT set for a virtual node of `entry`.
        let mut stack: ArrayVec<u32, STACK_SIZE> = ArrayVec::new();
        stack.push(if entry.is_empty() { 0 } else { IN_CUT });
        let mut visited = 0u64;
        let mut blocked = false;
        'walk: while let Some(top) = stack.pop() {
            visited += 1;
            let node = if top & IN_CUT == 0 {
                &self.nodes[top as usize]
            } else {
                &entry[(top & !IN_CUT) as usize]
            };
            let (mut mask, _) = pre.enter(s, node, t_max);
            while mask != 0 {
                let i = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                match node.count[i] {
                    0 => stack.push(node.child[i]),
                    VIRTUAL => stack.push(node.child[i] | IN_CUT),
                    EMPTY => {}
                    count => {
                        if leaf.visit(node.child[i], count, stats) {
                            blocked = true;
                            break 'walk;
                        }
                    }
                }
            }
        }
        stats.nodes_visited += visited;
        blocked
    }

    #[inline(always)]
    fn closest_generic<S: Simd, F>(
        &self,
        s: S,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        mut leaf: F,
        entry: &[NodeW],
    ) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool,
    {
        let mut visit = Visit(
            |first: u32, count: u32, t_max: &mut f32, stats: &mut TraversalStats| {
                let mut hit = false;
                for &p in &self.prims[first as usize..(first + count) as usize] {
                    stats.primitives_tested += 1;
                    hit |= leaf(p, t_max);
                }
                hit
            },
        );
        self.closest_walk(s, ray, t_max, stats, &mut visit, entry)
    }

    #[inline(always)]
    fn any_generic<S: Simd, F>(
        &self,
        s: S,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        mut leaf: F,
        entry: &[NodeW],
    ) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        let mut visit = Visit(|first: u32, count: u32, stats: &mut TraversalStats| {
            self.prims[first as usize..(first + count) as usize]
                .iter()
                .any(|&p| {
                    stats.primitives_tested += 1;
                    leaf(p)
                })
        });
        self.any_walk(s, ray, t_max, stats, &mut visit, entry)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,fma")]
    fn closest_avx2<F>(
        &self,
        s: Avx,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        leaf: F,
        entry: &[NodeW],
    ) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool,
    {
        self.closest_generic(s, ray, t_max, stats, leaf, entry)
    }

    /// [`Accelerator::closest_hit`] for the rays of a beam, starting from its cut (see
    /// [`WideBvh::cut`]): the same hits, for every ray inside the beam the cut was made for.
    pub fn closest_hit_in<F>(
        &self,
        cut: &Cut,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        leaf: F,
    ) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool,
    {
        !cut.misses && self.closest_from(ray, t_max, stats, leaf, &cut.nodes)
    }

    /// The closest-hit traversal from `entry` (empty: the root), on the widest SIMD the
    /// processor has.
    #[inline]
    fn closest_from<F>(
        &self,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        leaf: F,
        entry: &[NodeW],
    ) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool,
    {
        if !ray.is_traceable() {
            return false;
        }
        #[cfg(target_arch = "x86_64")]
        if let Some(avx) = Avx::detect() {
            // SAFETY: `closest_avx2` is compiled for AVX2, which the processor has.
            #[allow(unsafe_code)]
            return unsafe { self.closest_avx2(avx, ray, t_max, stats, leaf, entry) };
        }
        self.closest_generic(Sse, ray, t_max, stats, leaf, entry)
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
        self.any_generic(s, ray, t_max, stats, leaf, entry)
    }

    /// [`Accelerator::any_hit`] for the rays of a beam, starting from its cut: the same
    /// answer, and the same primitives offered to `leaf` when it never says stop (in another
    /// order), for every ray inside the beam the cut was made for.
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
        self.any_generic(Sse, ray, t_max, stats, leaf, entry)
    }
}

impl WideBvh {
    /// Starts fetching child `i` of `node` if it is a node; it will be visited later.
    #[inline(always)]
    fn prefetch_node(&self, node: &NodeW, i: usize) {
        // A beam's virtual nodes are few and were just built: in cache already.
        if node.count[i] == 0 {
            simd::prefetch(&self.nodes[node.child[i] as usize]);
        }
    }
}

/// The next entry of the stack that may still hold a nearer hit (or a tie, see
/// [`CULL_SLACK`]): (child, count).
#[inline(always)]
fn pop_nearer(stack: &mut ArrayVec<Entry, STACK_SIZE>, t_max: f32) -> Option<(u32, u32)> {
    while let Some((c, k, t)) = stack.pop() {
        if t <= t_max * CULL_SLACK {
            return Some((c, k));
        }
    }
    None
}

/// Insertion sort of at most eight entries by entry distance.
#[inline(always)]
fn sort_by_distance(e: &mut [Entry]) {
    for i in 1..e.len() {
        let mut j = i;
        while j > 0 && e[j - 1].2 > e[j].2 {
            e.swap(j - 1, j);
            j -= 1;
        }
    }
}

impl Accelerator for WideBvh {
    fn closest_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, leaf: F) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool,
    {
        self.closest_from(ray, t_max, stats, leaf, &[])
    }

    fn any_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, leaf: F) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        self.any_from(ray, t_max, stats, leaf, &[])
    }
}
