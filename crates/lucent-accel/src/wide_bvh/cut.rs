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

use super::{EMPTY, NodeW, VIRTUAL, WIDTH, WideBvh};
use crate::{Aabb, Frustum};

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
        if self.nodes.is_empty() {
            // One leaf, or nothing: no levels to skip.
            let misses = self.root_leaf.is_none() || !frustum.touches(&self.bounds);
            return Cut {
                nodes: vec![],
                misses,
            };
        }
        let touched = |node: u32| -> Vec<Slot> {
            let n = &self.nodes[node as usize];
            (0..WIDTH)
                .filter(|&k| n.count[k] != EMPTY)
                .map(|k| (n.child[k], n.count[k], n.child_bounds(k)))
                .filter(|(_, _, b)| frustum.touches(b))
                .collect()
        };
        let mut front = touched(0);
        loop {
            let widest = (0..front.len())
                .filter(|&i| front[i].1 == 0)
                .max_by(|&a, &b| {
                    let area = |i: usize| front[i].2.surface_area();
                    area(a).total_cmp(&area(b))
                });
            let Some(i) = widest else { break };
            let kids = touched(front[i].0);
            if front.len() - 1 + kids.len() > BUDGET {
                break;
            }
            front.splice(i..=i, kids);
        }
        if front.is_empty() {
            return Cut {
                nodes: vec![],
                misses: true,
            };
        }
        let node_of = |slots: &[Slot]| {
            let mut n = NodeW::empty();
            for (k, &(child, count, b)) in slots.iter().enumerate() {
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
        let groups: Vec<Slot> = front
            .chunks(WIDTH)
            .enumerate()
            .map(|(g, c)| {
                let b = c.iter().fold(Aabb::EMPTY, |a, s| a.union(s.2));
                (1 + g as u32, VIRTUAL, b)
            })
            .collect();
        let mut nodes = vec![node_of(&groups)];
        nodes.extend(front.chunks(WIDTH).map(node_of));
        Cut {
            nodes,
            misses: false,
        }
    }
}
