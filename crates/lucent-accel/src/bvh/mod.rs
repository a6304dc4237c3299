//! A binary bounding volume hierarchy built with the surface area heuristic.
//!
//! Nodes are 32 bytes: a box and two integers. An interior node's two children are adjacent
//! in the node array (`first`, `first + 1`); a leaf lists `count` primitives starting at
//! `first` in the primitive-index array. Closest-hit traversal visits the nearer child first
//! and skips subtrees that start beyond the nearest hit so far; any-hit traversal stops at the
//! first blocker.

mod build;
mod traverse;
mod validate;

pub use build::BuildOptions;

use crate::Aabb;
use glam::Vec3;

/// One node: 32 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub struct Node {
    /// The box's smallest corner.
    pub min: [f32; 3],
    /// Interior: index of the first child (the second follows it). Leaf: first primitive slot.
    pub first: u32,
    /// The box's largest corner.
    pub max: [f32; 3],
    /// Number of primitives of a leaf; 0 for an interior node.
    pub count: u32,
}

impl Node {
    /// The node's box.
    #[inline]
    pub fn bounds(&self) -> Aabb {
        Aabb::new(Vec3::from_array(self.min), Vec3::from_array(self.max))
    }

    /// True for a leaf.
    #[inline]
    pub fn is_leaf(&self) -> bool {
        self.count > 0
    }
}

/// A binary BVH over primitive boxes.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    /// Primitive indices in leaf order.
    prims: Vec<u32>,
}

impl Bvh {
    /// Builds over `boxes` with the default options.
    pub fn new(boxes: &[Aabb]) -> Self {
        Self::build(boxes, &BuildOptions::default())
    }

    /// The nodes; node 0 is the root (none when there are no primitives).
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// Primitive indices in the order the leaves refer to them.
    pub fn prim_indices(&self) -> &[u32] {
        &self.prims
    }

    /// Bytes held by nodes and indices.
    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * size_of::<Node>() + self.prims.len() * size_of::<u32>()
    }

    /// The number of nodes on the longest root-to-leaf path (0 when empty).
    pub fn depth(&self) -> usize {
        fn walk(nodes: &[Node], i: usize) -> usize {
            let n = &nodes[i];
            if n.is_leaf() {
                1
            } else {
                1 + walk(nodes, n.first as usize).max(walk(nodes, n.first as usize + 1))
            }
        }
        if self.nodes.is_empty() {
            0
        } else {
            walk(&self.nodes, 0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nodes_are_32_bytes() {
        assert_eq!(size_of::<Node>(), 32);
    }
}
