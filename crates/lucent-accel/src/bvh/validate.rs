//! `validate()`: every structural invariant of a built BVH, checked.

use super::Bvh;
use crate::Aabb;

impl Bvh {
    /// Checks the tree against the boxes it was built from:
    /// - every primitive index appears in exactly one leaf, and every slot is used once;
    /// - every node is reached exactly once from the root (no cycles, no orphans), children
    ///   after their parent;
    /// - leaves hold at least one primitive; interior children lie inside the array;
    /// - every node's box contains its children's boxes and its primitives' boxes.
    pub fn validate(&self, boxes: &[Aabb]) -> Result<(), String> {
        if boxes.is_empty() {
            return if self.nodes.is_empty() && self.prims.is_empty() {
                Ok(())
            } else {
                Err("an empty build must hold nothing".into())
            };
        }
        if self.prims.len() != boxes.len() {
            return Err(format!(
                "{} primitive slots for {} primitives",
                self.prims.len(),
                boxes.len()
            ));
        }
        let mut seen_prim = vec![false; boxes.len()];
        let mut seen_node = vec![false; self.nodes.len()];
        let mut slots_used = 0usize;
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            if std::mem::replace(&mut seen_node[i], true) {
                return Err(format!("node {i} is reached twice"));
            }
            let n = &self.nodes[i];
            let b = n.bounds();
            if n.is_leaf() {
                let (first, count) = (n.first as usize, n.count as usize);
                if first + count > self.prims.len() {
                    return Err(format!("leaf {i} runs past the primitive slots"));
                }
                slots_used += count;
                for &p in &self.prims[first..first + count] {
                    let p = p as usize;
                    if p >= boxes.len() {
                        return Err(format!(
                            "leaf {i} names primitive {p}, which does not exist"
                        ));
                    }
                    if std::mem::replace(&mut seen_prim[p], true) {
                        return Err(format!("primitive {p} is in two leaves"));
                    }
                    if !contains(b, boxes[p]) {
                        return Err(format!(
                            "leaf {i}'s box does not contain primitive {p}'s box"
                        ));
                    }
                }
            } else {
                let c = n.first as usize;
                if c <= i || c + 1 >= self.nodes.len() {
                    return Err(format!(
                        "node {i}'s children {c}, {} are out of place",
                        c + 1
                    ));
                }
                for child in [c, c + 1] {
                    if !contains(b, self.nodes[child].bounds()) {
                        return Err(format!(
                            "node {i}'s box does not contain child {child}'s box"
                        ));
                    }
                    stack.push(child);
                }
            }
        }
        if let Some(orphan) = seen_node.iter().position(|s| !s) {
            return Err(format!("node {orphan} is not reachable from the root"));
        }
        if slots_used != self.prims.len() {
            return Err(format!(
                "leaves use {slots_used} of {} primitive slots",
                self.prims.len()
            ));
        }
        Ok(())
    }
}

/// `outer ⊇ inner`, where an empty or non-finite inner box (a degenerate primitive) is
/// contained in anything.
fn contains(outer: Aabb, inner: Aabb) -> bool {
    if inner.is_empty() || !(inner.min.is_finite() && inner.max.is_finite()) {
        return true;
    }
    outer.min.cmple(inner.min).all() && outer.max.cmpge(inner.max).all()
}
