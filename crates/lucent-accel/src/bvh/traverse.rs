//! Stack-based traversal: closest hit (nearer child first) and any hit.

use super::Bvh;
use crate::aabb::CULL_SLACK;
use crate::{Accelerator, Ray, TraversalStats};
use arrayvec::ArrayVec;

/// Deepest possible tree: `max_sah_depth` (48) plus log2 of 2^32 primitives, with room to
/// spare; a closest-hit traversal holds at most one entry per level. (An `ArrayVec` is not
/// zeroed on creation, unlike an array: that memset cost more than a small traversal.)
const STACK_SIZE: usize = 128;

impl Bvh {
    #[inline(always)]
    fn enter<const PARALLEL: bool>(&self, node: usize, ray: &Ray, t_max: f32) -> Option<f32> {
        let b = self.nodes[node].bounds();
        if PARALLEL {
            b.hit(ray, t_max)
        } else {
            b.hit_nonparallel(ray, t_max)
        }
    }

    fn closest<const PARALLEL: bool, F>(
        &self,
        ray: &Ray,
        mut t_max: f32,
        stats: &mut TraversalStats,
        mut leaf: F,
    ) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool,
    {
        if self.nodes.is_empty() || self.enter::<PARALLEL>(0, ray, t_max).is_none() {
            return false;
        }
        let mut stack: ArrayVec<(u32, f32), STACK_SIZE> = ArrayVec::new();
        let mut node = 0usize;
        let mut hit = false;
        loop {
            stats.nodes_visited += 1;
            let n = &self.nodes[node];
            if n.is_leaf() {
                let first = n.first as usize;
                for &p in &self.prims[first..first + n.count as usize] {
                    stats.primitives_tested += 1;
                    hit |= leaf(p, &mut t_max);
                }
            } else {
                let (a, b) = (n.first as usize, n.first as usize + 1);
                match (
                    self.enter::<PARALLEL>(a, ray, t_max),
                    self.enter::<PARALLEL>(b, ray, t_max),
                ) {
                    (Some(ta), Some(tb)) => {
                        let (near, far, t_far) = if ta <= tb { (a, b, tb) } else { (b, a, ta) };
                        stack.push((far as u32, t_far));
                        node = near;
                        continue;
                    }
                    (Some(_), None) => {
                        node = a;
                        continue;
                    }
                    (None, Some(_)) => {
                        node = b;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            // Pop the next subtree that may still hold a nearer hit.
            loop {
                let Some((next, t_entry)) = stack.pop() else {
                    return hit;
                };
                // With the box test's slack: an entry rounded up must not hide a tie.
                if t_entry <= t_max * CULL_SLACK {
                    node = next as usize;
                    break;
                }
            }
        }
    }

    fn any<const PARALLEL: bool, F>(
        &self,
        ray: &Ray,
        t_max: f32,
        stats: &mut TraversalStats,
        mut leaf: F,
    ) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        if self.nodes.is_empty() {
            return false;
        }
        // Two entries per level at most.
        let mut stack: ArrayVec<u32, { 2 * STACK_SIZE }> = ArrayVec::new();
        stack.push(0);
        while let Some(node) = stack.pop() {
            let node = node as usize;
            if self.enter::<PARALLEL>(node, ray, t_max).is_none() {
                continue;
            }
            stats.nodes_visited += 1;
            let n = &self.nodes[node];
            if n.is_leaf() {
                let first = n.first as usize;
                for &p in &self.prims[first..first + n.count as usize] {
                    stats.primitives_tested += 1;
                    if leaf(p) {
                        return true;
                    }
                }
            } else {
                stack.push(n.first + 1);
                stack.push(n.first);
            }
        }
        false
    }
}

impl Accelerator for Bvh {
    fn closest_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, leaf: F) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool,
    {
        if !ray.is_traceable() {
            return false;
        }
        if ray.has_parallel_axis() {
            self.closest::<true, F>(ray, t_max, stats, leaf)
        } else {
            self.closest::<false, F>(ray, t_max, stats, leaf)
        }
    }

    fn any_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, leaf: F) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        if !ray.is_traceable() {
            return false;
        }
        if ray.has_parallel_axis() {
            self.any::<true, F>(ray, t_max, stats, leaf)
        } else {
            self.any::<false, F>(ray, t_max, stats, leaf)
        }
    }
}
