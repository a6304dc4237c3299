//! Bounding volumes, the notes' first speedup: "intersect with a box, if hit the box,
//! intersect with the object".
//!
//! Every primitive is still visited for every ray, but only a cheap ray–box test is paid for
//! those the ray misses; the primitive's own test runs only when its box is hit.

use crate::{Aabb, Accelerator, Ray, TraversalStats};

/// Each primitive's box, tested before the primitive.
#[derive(Clone, Debug)]
pub struct BoundingVolumes {
    boxes: Vec<Aabb>,
}

impl BoundingVolumes {
    /// Keeps a copy of `boxes`.
    pub fn new(boxes: &[Aabb]) -> Self {
        Self {
            boxes: boxes.to_vec(),
        }
    }

    /// Bytes held.
    pub fn memory_bytes(&self) -> usize {
        self.boxes.len() * size_of::<Aabb>()
    }
}

impl Accelerator for BoundingVolumes {
    fn closest_hit<F>(
        &self,
        ray: &Ray,
        mut t_max: f32,
        stats: &mut TraversalStats,
        mut leaf: F,
    ) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool,
    {
        if !ray.is_traceable() {
            return false;
        }
        let mut hit = false;
        for (i, b) in self.boxes.iter().enumerate() {
            stats.nodes_visited += 1;
            if b.hit(ray, t_max).is_some() {
                stats.primitives_tested += 1;
                hit |= leaf(i as u32, &mut t_max);
            }
        }
        hit
    }

    fn any_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, mut leaf: F) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        if !ray.is_traceable() {
            return false;
        }
        for (i, b) in self.boxes.iter().enumerate() {
            stats.nodes_visited += 1;
            if b.hit(ray, t_max).is_some() {
                stats.primitives_tested += 1;
                if leaf(i as u32) {
                    return true;
                }
            }
        }
        false
    }
}
