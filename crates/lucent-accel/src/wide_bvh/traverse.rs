//! Traversal of the 4-wide BVH: four child boxes per SIMD test, nearest child first.

use super::{EMPTY, Node4, WIDTH, WideBvh};
use crate::aabb::{CULL_SLACK, ROUNDING_SLACK};
use crate::{Accelerator, Ray, TraversalStats};
use arrayvec::ArrayVec;
use wide::f32x4;

/// Stack entries: each level pushes at most three siblings; the depth is bounded by the binary
/// tree's (see `BuildOptions::max_sah_depth`).
const STACK_SIZE: usize = 256;

/// A ray prepared for four-box tests.
pub(crate) struct RayPre {
    origin: [f32x4; 3],
    inv_dir: [f32x4; 3],
    /// Per axis: the direction is negative, so the near plane is the box's `hi`.
    negative: [bool; 3],
}

impl RayPre {
    pub(crate) fn new(ray: &Ray) -> Self {
        let o = ray.origin;
        let i = ray.inv_dir;
        Self {
            origin: [f32x4::splat(o.x), f32x4::splat(o.y), f32x4::splat(o.z)],
            inv_dir: [f32x4::splat(i.x), f32x4::splat(i.y), f32x4::splat(i.z)],
            negative: [ray.dir.x < 0.0, ray.dir.y < 0.0, ray.dir.z < 0.0],
        }
    }

    /// Which of the node's children the ray enters before `t_max` (a bit mask), and where.
    ///
    /// `PARALLEL` is the robust variant for rays with a zero direction component, where the
    /// slab test can meet `0 · ∞ = NaN` (treated as no constraint, as in [`crate::Aabb::hit`]).
    /// Otherwise the near and far planes are picked by the direction's signs, and an unused
    /// slot's inverted box (`lo = +∞`, `hi = −∞`) is never entered.
    #[inline(always)]
    pub(crate) fn enter<const PARALLEL: bool>(
        &self,
        node: &Node4,
        t_max: f32,
    ) -> (u32, [f32; WIDTH]) {
        let zero = f32x4::splat(0.0);
        let (mut near, mut far) = (zero, f32x4::splat(t_max * CULL_SLACK));
        if PARALLEL {
            for a in 0..3 {
                let t0 = (f32x4::from(node.lo[a]) - self.origin[a]) * self.inv_dir[a];
                let t1 = (f32x4::from(node.hi[a]) - self.origin[a]) * self.inv_dir[a];
                let nan = t0.is_nan() | t1.is_nan();
                near = near.max(nan.bitselect(f32x4::splat(f32::NEG_INFINITY), t0.min(t1)));
                far = far.min(nan.bitselect(
                    f32x4::splat(f32::INFINITY),
                    t0.max(t1) * f32x4::splat(ROUNDING_SLACK),
                ));
            }
            let mask = near.simd_le(far).to_bitmask() & node.used_mask();
            return (mask, near.to_array());
        }
        let mut exit = f32x4::splat(f32::INFINITY);
        for a in 0..3 {
            let (n, f) = if self.negative[a] {
                (node.hi[a], node.lo[a])
            } else {
                (node.lo[a], node.hi[a])
            };
            near = near.fast_max((f32x4::from(n) - self.origin[a]) * self.inv_dir[a]);
            exit = exit.fast_min((f32x4::from(f) - self.origin[a]) * self.inv_dir[a]);
        }
        far = far.fast_min(exit * f32x4::splat(ROUNDING_SLACK));
        (near.simd_le(far).to_bitmask(), near.to_array())
    }
}

/// A child reference on the traversal stack: (child, count, entry distance).
type Entry = (u32, u32, f32);

impl WideBvh {
    /// Closest-hit traversal; `visit(first, count, t_max, stats)` tests a leaf's primitives,
    /// lowers `t_max` on a hit and returns whether it found one.
    #[inline(always)]
    pub(crate) fn closest_walk<const PARALLEL: bool, F>(
        &self,
        ray: &Ray,
        mut t_max: f32,
        stats: &mut TraversalStats,
        mut visit: F,
    ) -> bool
    where
        F: FnMut(u32, u32, &mut f32, &mut TraversalStats) -> bool,
    {
        if let Some((first, count)) = self.root_leaf {
            return self.bounds.hit(ray, t_max).is_some() && visit(first, count, &mut t_max, stats);
        }
        if self.nodes.is_empty() {
            return false;
        }
        let pre = RayPre::new(ray);
        let mut stack: ArrayVec<Entry, STACK_SIZE> = ArrayVec::new();
        let (mut child, mut count) = (0u32, 0u32);
        let mut hit = false;
        loop {
            if count == 0 {
                stats.nodes_visited += 1;
                let node = &self.nodes[child as usize];
                let (mut mask, t) = pre.enter::<PARALLEL>(node, t_max);
                if mask != 0 {
                    let mut hits: [Entry; WIDTH] = [(0, 0, 0.0); WIDTH];
                    let mut n = 0;
                    while mask != 0 {
                        let i = mask.trailing_zeros() as usize;
                        mask &= mask - 1;
                        hits[n] = (node.child[i], node.count[i], t[i]);
                        n += 1;
                    }
                    sort_by_distance(&mut hits[..n]);
                    stack.extend(hits[1..n].iter().rev().copied());
                    (child, count) = (hits[0].0, hits[0].1);
                    continue;
                }
            } else {
                hit |= visit(child, count, &mut t_max, stats);
            }
            // The next subtree that may still hold a nearer hit (or a tie, see CULL_SLACK).
            loop {
                let Some((c, k, t)) = stack.pop() else {
                    return hit;
                };
                if t <= t_max * CULL_SLACK {
                    (child, count) = (c, k);
                    break;
                }
            }
        }
    }

    /// Any-hit traversal; `visit(first, count, stats)` returns `true` to stop.
    #[inline(always)]
    pub(crate) fn any_walk<const PARALLEL: bool, F>(
        &self,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        mut visit: F,
    ) -> bool
    where
        F: FnMut(u32, u32, &mut TraversalStats) -> bool,
    {
        if let Some((first, count)) = self.root_leaf {
            return self.bounds.hit(ray, t_max).is_some() && visit(first, count, stats);
        }
        if self.nodes.is_empty() {
            return false;
        }
        let pre = RayPre::new(ray);
        let mut stack: ArrayVec<u32, STACK_SIZE> = ArrayVec::new();
        stack.push(0);
        while let Some(top) = stack.pop() {
            stats.nodes_visited += 1;
            let node = &self.nodes[top as usize];
            let (mut mask, _) = pre.enter::<PARALLEL>(node, t_max);
            while mask != 0 {
                let i = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                match node.count[i] {
                    0 => {
                        stack.push(node.child[i]);
                    }
                    EMPTY => {}
                    count => {
                        if visit(node.child[i], count, stats) {
                            return true;
                        }
                    }
                }
            }
        }
        false
    }
}

/// Insertion sort of at most four entries by entry distance.
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
    fn closest_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, mut leaf: F) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool,
    {
        let visit = |first: u32, count: u32, t_max: &mut f32, stats: &mut TraversalStats| {
            let mut hit = false;
            for &p in &self.prims[first as usize..(first + count) as usize] {
                stats.primitives_tested += 1;
                hit |= leaf(p, t_max);
            }
            hit
        };
        if ray.has_parallel_axis() {
            self.closest_walk::<true, _>(ray, t_max, stats, visit)
        } else {
            self.closest_walk::<false, _>(ray, t_max, stats, visit)
        }
    }

    fn any_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, mut leaf: F) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        let visit = |first: u32, count: u32, stats: &mut TraversalStats| {
            self.prims[first as usize..(first + count) as usize]
                .iter()
                .any(|&p| {
                    stats.primitives_tested += 1;
                    leaf(p)
                })
        };
        if ray.has_parallel_axis() {
            self.any_walk::<true, _>(ray, t_max, stats, visit)
        } else {
            self.any_walk::<false, _>(ray, t_max, stats, visit)
        }
    }
}
