//! Where a beam's rays enter the tree: the subtrees its frustum touches, under a few virtual
//! nodes — a per-beam entry point in the spirit of Reshetov, Soupikov & Hurley 2005
//! ("Multi-level ray tracing algorithm").
//!
//! The frustum is traversed once, from the root, keeping only the children it touches and
//! opening the largest of them (by surface area) while the list stays within [`BUDGET`]
//! entries: the "deepest node every ray must enter" when one child alone is touched, a short
//! candidate list otherwise. The entries, in depth-first order (so neighbours stay together),
//! go eight to a virtual node, under a virtual root when there are more than eight. Each ray
//! of the beam then starts its ordinary traversal at the virtual root: the levels above the
//! cut are skipped, and so is every subtree outside the frustum.
//!
//! Why the hits are the same: the frustum test is conservative, so every leaf a ray of the
//! beam enters lies under an entry of the cut; the walk from the cut tests those leaves with
//! the same slab test and the same `t_max` culling, and the closest hit with its tie rule does
//! not depend on the order leaves are visited in.

use super::simd::{Simd, Sse};
use super::{EMPTY, NodeW, VIRTUAL, WIDTH, WideBvh};
use crate::{Aabb, Frustum};
use arrayvec::ArrayVec;

/// Most entries a cut holds: eight virtual nodes of eight under one virtual root.
pub const BUDGET: usize = WIDTH * WIDTH;

/// A beam's entry into one tree (see the module's docs), made by [`WideBvh::cut`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Cut {
    /// The virtual nodes, root first; empty to start at the tree's own root.
    pub(crate) nodes: Vec<NodeW>,
    /// No ray of the beam can enter the tree.
    pub(crate) misses: bool,
}

impl Cut {
    /// True when no ray of the beam can enter the tree: its queries answer "no hit" at once.
    pub fn misses(&self) -> bool {
        self.misses
    }

    /// Virtual nodes the rays start from (0: from the tree's root, or nowhere).
    pub fn virtual_nodes(&self) -> usize {
        self.nodes.len()
    }
}

/// A child slot seen from its parent: (child, count, box).
type Slot = (u32, u32, Aabb);

impl WideBvh {
    /// The entry of the rays of `frustum` into this tree.
    pub fn cut(&self, frustum: &Frustum) -> Cut {
        self.cut_within(frustum, BUDGET)
    }

    /// [`WideBvh::cut`] with at most `budget` entries (at most [`BUDGET`]): a smaller cut
    /// is quicker to make and skips fewer levels, which pays for beams of few or cheap rays.
    pub fn cut_within(&self, frustum: &Frustum, budget: usize) -> Cut {
        let budget = budget.clamp(1, BUDGET);
        if self.nodes.is_empty() {
            // One leaf, or nothing: no levels to skip.
            let misses = self.root_leaf.is_none() || !frustum.touches(&self.bounds);
            return Cut {
                nodes: vec![],
                misses,
            };
        }
        // The cut's front, in depth-first order: each touched child as (parent node, slot)
        // with the surface area that ranks it for opening (−∞ for a leaf, never opened).
        // Boxes are read from the parents only for the virtual nodes at the end; the front
        // lives on the stack (a beam's cut is made once per tile and must cost little).
        let mut front: ArrayVec<Front, { BUDGET + WIDTH }> = ArrayVec::new();
        self.push_touched(frustum, 0, &mut front);
        loop {
            // The largest openable entry (the last of equals, as `max_by` picks).
            let mut widest = None;
            let mut widest_area = f32::NEG_INFINITY;
            for (i, e) in front.iter().enumerate() {
                if e.area > f32::NEG_INFINITY && e.area >= widest_area {
                    (widest, widest_area) = (Some(i), e.area);
                }
            }
            let Some(i) = widest else { break };
            let open = front[i];
            let node = self.nodes[open.node as usize].child[open.slot as usize];
            let mut kids: ArrayVec<Front, WIDTH> = ArrayVec::new();
            self.push_touched(frustum, node, &mut kids);
            if front.len() - 1 + kids.len() > budget {
                break;
            }
            // Replace entry i by its touched children, in place.
            front.remove(i);
            for (k, kid) in kids.into_iter().enumerate() {
                front.insert(i + k, kid);
            }
        }
        if front.is_empty() {
            return Cut {
                nodes: vec![],
                misses: true,
            };
        }
        let slot = |e: &Front| -> Slot {
            let n = &self.nodes[e.node as usize];
            let k = e.slot as usize;
            (n.child[k], n.count[k], n.child_bounds(k))
        };
        let node_of = |entries: &[Front]| {
            let mut n = NodeW::empty();
            for (k, e) in entries.iter().enumerate() {
                let (child, count, b) = slot(e);
                n.set_bounds(k, b);
                n.child[k] = child;
                n.count[k] = count;
            }
            n
        };
        if front.len() <= WIDTH {
            return Cut {
                nodes: vec![node_of(&front)],
                misses: false,
            };
        }
        let mut nodes = Vec::with_capacity(1 + front.len().div_ceil(WIDTH));
        let mut root = NodeW::empty();
        for (g, c) in front.chunks(WIDTH).enumerate() {
            let b = c.iter().fold(Aabb::EMPTY, |a, e| a.union(slot(e).2));
            root.set_bounds(g, b);
            root.child[g] = 1 + g as u32;
            root.count[g] = VIRTUAL;
        }
        nodes.push(root);
        nodes.extend(front.chunks(WIDTH).map(node_of));
        Cut {
            nodes,
            misses: false,
        }
    }
}

/// An entry of a cut's front while it is made: slot `slot` of node `node`, and its rank.
#[derive(Clone, Copy)]
struct Front {
    node: u32,
    slot: u8,
    /// The child's surface area if it is a tree node (it may be opened), −∞ for a leaf.
    area: f32,
}

impl WideBvh {
    /// Appends the children of node `node` that `frustum` touches to `out`, in slot order.
    #[inline]
    fn push_touched<const N: usize>(
        &self,
        frustum: &Frustum,
        node: u32,
        out: &mut ArrayVec<Front, N>,
    ) {
        let n = &self.nodes[node as usize];
        let mut mask = touched_children(frustum, n);
        while mask != 0 {
            let k = mask.trailing_zeros() as usize;
            mask &= mask - 1;
            let area = if n.count[k] == 0 {
                n.child_bounds(k).surface_area()
            } else {
                f32::NEG_INFINITY
            };
            out.push(Front {
                node,
                slot: k as u8,
                area,
            });
        }
    }
}

/// [`Frustum::touches`] for the eight children of `node` at once (bit `k` for child `k`), the
/// same planes and slack in SIMD: the cut tests some hundreds of boxes per beam, and one at
/// a time this was as slow as tracing the tile's rays. Conservative as that test is (its
/// results may differ from it in rounding, far inside the slack); an unused or empty slot is
/// never touched, and a NaN met on the way keeps the box, as there.
fn touched_children(frustum: &Frustum, node: &NodeW) -> u32 {
    let s = Sse;
    let o = frustum.origin();
    let zero = s.splat(0.0);
    let abs = |x| s.max(x, s.sub(zero, x));
    // Empty: some axis with lo > hi (unused slots hold lo = +∞, hi = −∞).
    let empty = (0..3).fold(0, |m, a| {
        m | s.lt(s.load(&node.planes[3 + a]), s.load(&node.planes[a]))
    });
    let mut outside = 0;
    for n in frustum.normals() {
        // The p-vertex: per axis the largest corner where the normal is ≥ 0, else the smallest.
        let rel = |a: usize| {
            let row = if n[a] >= 0.0 { 3 + a } else { a };
            s.sub(s.load(&node.planes[row]), s.splat(o[a]))
        };
        let (px, py, pz) = (rel(0), rel(1), rel(2));
        let dot = s.add(
            s.add(s.mul(px, s.splat(n.x)), s.mul(py, s.splat(n.y))),
            s.mul(pz, s.splat(n.z)),
        );
        let slack = s.mul(
            s.add(s.add(abs(px), abs(py)), abs(pz)),
            s.splat(-crate::frustum::ANGULAR_SLACK),
        );
        // NaN compares false: kept.
        outside |= s.lt(dot, slack);
    }
    let used = (0..WIDTH)
        .filter(|&k| node.count[k] != EMPTY)
        .fold(0u32, |m, k| m | 1 << k);
    used & !empty & !outside
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    /// A small deterministic generator (xorshift), for boxes all over and around a beam.
    fn boxes(n: usize) -> Vec<Aabb> {
        let mut x = 0x9e37_79b9_u32;
        let mut next = move || {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            (x as f32 / u32::MAX as f32) * 2.0 - 1.0
        };
        (0..n)
            .map(|_| {
                let c = Vec3::new(next() * 3.0, next() * 3.0, next() * 6.0 - 4.0);
                let h = Vec3::new(next().abs(), next().abs(), next().abs()) * 0.3;
                Aabb::new(c - h, c + h)
            })
            .collect()
    }

    #[test]
    fn eight_children_at_once_are_touched_as_one_at_a_time() {
        let c = |x: f32, y: f32| Vec3::new(x, y, -1.0);
        let f = Frustum::new(
            Vec3::new(0.1, -0.2, 0.5),
            [c(-0.2, -0.1), c(0.3, -0.1), c(0.3, 0.2), c(-0.2, 0.2)],
        )
        .unwrap();
        let mut all = boxes(800);
        // Degenerate slots: a NaN bound, an empty box (never touched), infinite bounds.
        all[3].min.x = f32::NAN;
        all[11] = Aabb::EMPTY;
        all[12].max = Vec3::INFINITY;
        all[13].min = Vec3::NEG_INFINITY;
        let (mut agree, mut touched) = (0, 0);
        for chunk in all.chunks(WIDTH) {
            let mut n = NodeW::empty();
            for (k, b) in chunk.iter().enumerate() {
                n.set_bounds(k, *b);
                n.count[k] = 1;
            }
            let mask = touched_children(&f, &n);
            for (k, b) in chunk.iter().enumerate() {
                let one = f.touches(b);
                assert!(!one || mask & 1 << k != 0, "box {b:?} lost");
                agree += usize::from(one == (mask & 1 << k != 0));
                touched += usize::from(one);
            }
            assert_eq!(mask >> chunk.len(), 0, "an unused slot");
        }
        assert_eq!(agree, all.len(), "the same answers, box for box");
        assert!(
            touched > 50 && touched < 750,
            "{touched} touched: a test of something"
        );
    }
}
