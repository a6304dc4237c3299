//! Collapsing a binary BVH into an 8-wide one with the same leaves, by dynamic programming
//! over the binary tree (after Ylitie, Karras and Laine 2017, "Efficient incoherent ray
//! traversal on GPUs through compressed wide BVHs", §3.1).
//!
//! Each wide node stands for a binary interior node, and its children are binary descendants
//! whose subtrees partition that node's leaves, at most eight of them. With the leaves fixed,
//! the SAH cost of the wide tree differs between such trees only in its nodes' tests: the sum
//! of the wide nodes' surface areas. The table below finds the tree with the least. (Greedily
//! opening each node's largest child until it has eight left the bottom of the tree with nodes
//! of two or three leaves: 3,505 nodes for the bunny, against 1,886 here, and 4% more node
//! visits per incoherent ray.)

use super::{NodeW, WIDTH, WideBvh};
use crate::Bvh;
use crate::bvh::Node;

/// How binary node `n`'s subtree fills at most `s` slots of a wide node.
#[derive(Clone, Copy, Debug)]
enum Fill {
    /// As `n` alone: a leaf, or a wide node of its own.
    Whole,
    /// As it fills `s − 1` slots.
    Fewer,
    /// Split over its two children: this many slots to the first, the rest to the second.
    Split(u8),
}

/// Per binary node and slot budget `s` = 1..=8: the least area of wide nodes in its subtree
/// when it fills at most `s` slots, and the fill that reaches it.
struct Table {
    area: Vec<[f32; WIDTH]>,
    fill: Vec<[Fill; WIDTH]>,
}

impl Table {
    /// Fills the table from the leaves up (children come after their parents in `bin`).
    fn new(bin: &[Node]) -> Self {
        let mut t = Table {
            area: vec![[0.0; WIDTH]; bin.len()],
            fill: vec![[Fill::Whole; WIDTH]; bin.len()],
        };
        for i in (0..bin.len()).rev() {
            if bin[i].is_leaf() {
                continue; // a leaf costs no node, whatever its slots
            }
            let own = bin[i].bounds().surface_area();
            t.area[i][0] = own + t.split(bin, i, WIDTH).0;
            for s in 2..=WIDTH {
                let (split, share) = t.split(bin, i, s);
                let fewer = t.area[i][s - 2];
                (t.area[i][s - 1], t.fill[i][s - 1]) = if split < fewer {
                    (split, Fill::Split(share))
                } else {
                    (fewer, Fill::Fewer)
                };
            }
        }
        t
    }

    /// The least area of interior node `i`'s two children over `s` slots, and the first
    /// child's share.
    fn split(&self, bin: &[Node], i: usize, s: usize) -> (f32, u8) {
        let (l, r) = (bin[i].first as usize, bin[i].first as usize + 1);
        (1..s)
            .map(|k| (self.area[l][k - 1] + self.area[r][s - k - 1], k as u8))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .unwrap_or((f32::INFINITY, 1))
    }

    /// The binary nodes that fill `s` slots for node `i`, appended to `out`.
    fn gather(&self, bin: &[Node], i: usize, s: usize, out: &mut Vec<usize>) {
        match self.fill[i][s - 1] {
            Fill::Whole => out.push(i),
            Fill::Fewer => self.gather(bin, i, s - 1, out),
            Fill::Split(k) => {
                let first = bin[i].first as usize;
                self.gather(bin, first, k as usize, out);
                self.gather(bin, first + 1, s - k as usize, out);
            }
        }
    }

    /// The children of the wide node that stands for interior binary node `i`.
    fn children(&self, bin: &[Node], i: usize) -> Vec<usize> {
        let (_, share) = self.split(bin, i, WIDTH);
        let first = bin[i].first as usize;
        let mut out = Vec::with_capacity(WIDTH);
        self.gather(bin, first, share as usize, &mut out);
        self.gather(bin, first + 1, WIDTH - share as usize, &mut out);
        out
    }
}

impl WideBvh {
    /// The 8-wide tree with the same leaves as `bvh` whose nodes have the least total area.
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
        let table = Table::new(bin);
        let mut nodes = vec![NodeW::empty()];
        let mut work = vec![(0usize, 0usize)]; // (binary node, wide node)
        while let Some((b, w)) = work.pop() {
            for (slot, k) in table.children(bin, b).into_iter().enumerate() {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Aabb;
    use crate::bvh::BuildOptions;
    use glam::Vec3;

    /// Every way to fill at most eight slots with `i`'s subtree: lists of binary nodes.
    fn cuts(bin: &[Node], i: usize) -> Vec<Vec<usize>> {
        let mut out = vec![vec![i]];
        if !bin[i].is_leaf() {
            let first = bin[i].first as usize;
            let (left, right) = (cuts(bin, first), cuts(bin, first + 1));
            for a in &left {
                for b in &right {
                    if a.len() + b.len() <= WIDTH {
                        out.push([a.as_slice(), b.as_slice()].concat());
                    }
                }
            }
        }
        out
    }

    /// The least total node area of a wide tree for interior node `i`, by trying every way.
    fn least_area(bin: &[Node], i: usize) -> f32 {
        let first = bin[i].first as usize;
        let (left, right) = (cuts(bin, first), cuts(bin, first + 1));
        let below = |c: &usize| {
            if bin[*c].is_leaf() {
                0.0
            } else {
                least_area(bin, *c)
            }
        };
        let mut best = f32::INFINITY;
        for a in &left {
            for b in &right {
                if a.len() + b.len() <= WIDTH {
                    best = best.min(a.iter().chain(b).map(below).sum());
                }
            }
        }
        bin[i].bounds().surface_area() + best
    }

    /// The wide tree's total node area: the root's box and every interior child's box.
    fn total_area(w: &WideBvh) -> f32 {
        let children: f32 = w
            .nodes
            .iter()
            .flat_map(|n| {
                (0..WIDTH)
                    .filter(|&k| n.count[k] == 0)
                    .map(|k| n.child_bounds(k))
            })
            .map(|b| b.surface_area())
            .sum();
        w.bounds.surface_area() + children
    }

    #[test]
    fn the_collapse_has_the_least_node_area_of_all_wide_trees() {
        let mut seed = 7u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 40) as f32 / (1u64 << 24) as f32
        };
        for n in [3, 9, 14, 20] {
            let boxes: Vec<Aabb> = (0..n)
                .map(|_| {
                    let p = Vec3::new(next(), next(), next()) * 10.0;
                    Aabb::new(p, p + Vec3::new(next(), next(), next()))
                })
                .collect();
            let options = BuildOptions {
                max_leaf_size: 1,
                ..BuildOptions::default()
            };
            let bvh = Bvh::build(&boxes, &options);
            let wide = WideBvh::from_binary(&bvh);
            assert_eq!(wide.validate(&boxes), Ok(()));
            let (got, want) = (total_area(&wide), least_area(bvh.nodes(), 0));
            assert!(
                (got - want).abs() <= 1e-4 * want,
                "{n} boxes: the collapse's area {got}, the least {want}"
            );
        }
    }
}
