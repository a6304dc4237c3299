//! An 8-wide BVH: each node holds the boxes of up to eight children, tested against a ray at
//! once with SIMD (AVX2 where the processor has it, see [`simd`]; two SSE steps otherwise).
//!
//! Built by collapsing a binary SAH BVH, keeping its leaves, into the wide tree whose nodes
//! have the least total surface area (module `collapse`). [`WideTriangleBvh`] specialises the leaves
//! for triangles: they hold packs of eight triangles laid out for a SIMD watertight test.

mod collapse;
mod cut;
mod lanes;
mod packet;
mod simd;
mod traverse;
mod triangles;

pub use cut::{BUDGET as CUT_BUDGET, Cut};
pub use lanes::{LANES, Lanes};
pub use packet::PACKET;
pub use triangles::{PackedHit, WideTriangleBvh};

use crate::bvh::BuildOptions;
use crate::{Aabb, Bvh};

/// Children per node.
pub const WIDTH: usize = LANES;

/// `count` of an unused child slot.
pub(crate) const EMPTY: u32 = u32::MAX;

/// `count` of a child that is one of a beam's virtual nodes ([`Cut`]), not a node of the tree.
pub(crate) const VIRTUAL: u32 = u32::MAX - 1;

/// A node: eight child boxes in structure-of-arrays form, and what each child is. 256 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub struct NodeW {
    /// The children's slab planes, `planes[k][child]`: `k` = 0, 1, 2 the smallest corner's x,
    /// y, z (`+∞` for an unused slot), `k` = 3, 4, 5 the largest corner's (`−∞` when unused).
    pub planes: [Lanes; 6],
    /// Interior child: its node index. Leaf child: its first primitive slot (or pack).
    pub child: [u32; WIDTH],
    /// 0 for an interior child; the number of primitives (or packs) of a leaf child; [`EMPTY`]
    /// if unused.
    pub count: [u32; WIDTH],
}

impl NodeW {
    /// A node with every slot unused.
    pub(crate) fn empty() -> Self {
        let (lo, hi) = (Lanes::splat(f32::INFINITY), Lanes::splat(f32::NEG_INFINITY));
        Self {
            planes: [lo, lo, lo, hi, hi, hi],
            child: [0; WIDTH],
            count: [EMPTY; WIDTH],
        }
    }

    /// Child `i`'s box.
    pub fn child_bounds(&self, i: usize) -> Aabb {
        let p = |k: usize| self.planes[k].0[i];
        Aabb::new(
            glam::Vec3::new(p(0), p(1), p(2)),
            glam::Vec3::new(p(3), p(4), p(5)),
        )
    }

    pub(crate) fn set_bounds(&mut self, i: usize, b: Aabb) {
        for axis in 0..3 {
            self.planes[axis].0[i] = b.min[axis];
            self.planes[3 + axis].0[i] = b.max[axis];
        }
    }

    /// Bit `i` set for every used slot.
    #[inline]
    pub fn used_mask(&self) -> u32 {
        (0..WIDTH)
            .filter(|&i| self.count[i] != EMPTY)
            .fold(0, |m, i| m | 1 << i)
    }
}

/// An 8-wide BVH over primitive boxes; the leaf test is called per primitive.
#[derive(Clone, Debug, Default)]
pub struct WideBvh {
    pub(crate) nodes: Vec<NodeW>,
    /// Primitive indices in leaf order.
    pub(crate) prims: Vec<u32>,
    /// The root, when the whole tree is one leaf: (first slot, count) — otherwise node 0 is the root.
    pub(crate) root_leaf: Option<(u32, u32)>,
    pub(crate) bounds: Aabb,
}

/// The binary build settings for a wide tree whose leaves are tested `block` primitives at a
/// time: leaves of at most `block` primitives, costed in tests of `block`.
pub fn build_options(block: usize) -> BuildOptions {
    BuildOptions {
        max_leaf_size: block,
        block,
        ..BuildOptions::default()
    }
}

impl WideBvh {
    /// Builds over `boxes`: a binary SAH BVH, collapsed.
    pub fn new(boxes: &[Aabb]) -> Self {
        Self::from_binary(&Bvh::build(boxes, &build_options(4)))
    }

    /// The nodes; node 0 is the root unless the tree is a single leaf.
    pub fn nodes(&self) -> &[NodeW] {
        &self.nodes
    }

    /// Bytes held by nodes and indices.
    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * size_of::<NodeW>() + self.prims.len() * size_of::<u32>()
    }

    /// Levels of nodes on the longest root-to-leaf path (a single leaf: 1).
    pub fn depth(&self) -> usize {
        fn walk(nodes: &[NodeW], i: usize) -> usize {
            let n = &nodes[i];
            1 + (0..WIDTH)
                .filter(|&k| n.count[k] == 0)
                .map(|k| walk(nodes, n.child[k] as usize))
                .max()
                .unwrap_or(0)
        }
        if self.nodes.is_empty() {
            usize::from(self.root_leaf.is_some())
        } else {
            walk(&self.nodes, 0)
        }
    }

    /// Checks every invariant against the boxes it was built from: each primitive in exactly
    /// one leaf, each node reached once, children's boxes holding their primitives' boxes,
    /// unused slots empty and after the used ones.
    pub fn validate(&self, boxes: &[Aabb]) -> Result<(), String> {
        let mut seen = vec![false; boxes.len()];
        let check_leaf =
            |first: u32, count: u32, b: Aabb, seen: &mut Vec<bool>| -> Result<(), String> {
                let (first, count) = (first as usize, count as usize);
                let slots = self
                    .prims
                    .get(first..first + count)
                    .ok_or("a leaf runs past the primitive slots")?;
                for &p in slots {
                    let p = p as usize;
                    if p >= boxes.len() || std::mem::replace(&mut seen[p], true) {
                        return Err(format!("primitive {p} is missing or in two leaves"));
                    }
                    let inner = boxes[p];
                    let finite =
                        inner.min.is_finite() && inner.max.is_finite() && !inner.is_empty();
                    if finite && !(b.min.cmple(inner.min).all() && b.max.cmpge(inner.max).all()) {
                        return Err(format!("a leaf's box does not contain primitive {p}'s box"));
                    }
                }
                Ok(())
            };
        if let Some((first, count)) = self.root_leaf {
            check_leaf(first, count, self.bounds, &mut seen)?;
        } else if !self.nodes.is_empty() {
            let mut reached = vec![false; self.nodes.len()];
            let mut stack = vec![0usize];
            while let Some(i) = stack.pop() {
                if std::mem::replace(&mut reached[i], true) {
                    return Err(format!("node {i} is reached twice"));
                }
                let n = &self.nodes[i];
                let used = n.used_mask();
                if used & (used + 1) != 0 || used == 0 {
                    return Err(format!("node {i}'s used slots are not the first ones"));
                }
                for k in 0..WIDTH {
                    match n.count[k] {
                        EMPTY => {}
                        0 => {
                            let c = n.child[k] as usize;
                            if c <= i || c >= self.nodes.len() {
                                return Err(format!("node {i}'s child {c} is out of place"));
                            }
                            let cb = n.child_bounds(k);
                            let child = &self.nodes[c];
                            for j in 0..WIDTH {
                                if child.count[j] != EMPTY {
                                    let g = child.child_bounds(j);
                                    if !(cb.min.cmple(g.min).all() && cb.max.cmpge(g.max).all()) {
                                        return Err(format!(
                                            "node {i}'s box for child {c} does not hold its slot {j}"
                                        ));
                                    }
                                }
                            }
                            stack.push(c);
                        }
                        count => check_leaf(n.child[k], count, n.child_bounds(k), &mut seen)?,
                    }
                }
            }
            if let Some(orphan) = reached.iter().position(|r| !r) {
                return Err(format!("node {orphan} is not reachable"));
            }
        }
        match seen.iter().position(|s| !s) {
            Some(p) if !boxes[p].has_nan() => Err(format!("primitive {p} is in no leaf")),
            _ => Ok(()),
        }
    }
}
