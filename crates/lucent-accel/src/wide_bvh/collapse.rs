//! Collapsing a binary BVH into an 8-wide one.

use super::{NodeW, WIDTH, WideBvh};
use crate::Bvh;

impl WideBvh {
    /// The 8-wide tree with the same leaves as `bvh`.
    pub fn from_binary(bvh: &Bvh) -> Self {
        let bin = bvh.nodes();
        let prims = bvh.prim_indices().to_vec();
        let Some(root) = bin.first() else {
            return Self::default();
        };
        let bounds = root.bounds();
        if root.is_leaf() {
            return Self {
                nodes: vec![],
                prims,
                root_leaf: Some((root.first, root.count)),
                bounds,
            };
        }
        let mut nodes = vec![NodeW::empty()];
        let mut work = vec![(0usize, 0usize)]; // (binary node, wide node)
        while let Some((b, w)) = work.pop() {
            // Gather up to four children, opening the largest interior one each time (up to eight).
            let first = bin[b].first as usize;
            let mut kids = vec![first, first + 1];
            while kids.len() < WIDTH {
                let area = |k: usize| bin[k].bounds().surface_area();
                let widest = (0..kids.len())
                    .filter(|&s| !bin[kids[s]].is_leaf())
                    .max_by(|&x, &y| area(kids[x]).total_cmp(&area(kids[y])));
                let Some(slot) = widest else { break };
                let k = kids[slot];
                let c = bin[k].first as usize;
                kids[slot] = c;
                kids.push(c + 1);
            }
            for (slot, &k) in kids.iter().enumerate() {
                let n = &bin[k];
                nodes[w].set_bounds(slot, n.bounds());
                if n.is_leaf() {
                    nodes[w].child[slot] = n.first;
                    nodes[w].count[slot] = n.count;
                } else {
                    let child = nodes.len();
                    nodes.push(NodeW::empty());
                    nodes[w].child[slot] = child as u32;
                    nodes[w].count[slot] = 0;
                    work.push((k, child));
                }
            }
        }
        Self {
            nodes,
            prims,
            root_leaf: None,
            bounds,
        }
    }
}
