//! The lecture notes' loop: every object tested against every ray.
//!
//! ```text
//! For each object in the scene
//!     If the ray intersects the object, and is closest yet
//!         Record intersection and object
//! ```
//! Cost grows with objects × rays; it is the reference the other structures are held to.

use crate::{Aabb, Accelerator, Ray, TraversalStats};

/// Tests every primitive, in index order, for every ray.
#[derive(Clone, Debug)]
pub struct BruteForce {
    count: u32,
}

impl BruteForce {
    /// Built over `boxes`; only their number matters here.
    pub fn new(boxes: &[Aabb]) -> Self {
        let count = u32::try_from(boxes.len()).expect("more than 2^32 primitives");
        Self { count }
    }

    /// How many primitives it holds.
    pub fn len(&self) -> usize {
        self.count as usize
    }

    /// True when it holds none.
    pub fn is_empty(&self) -> bool {
        self.count == 0
    }
}

impl Accelerator for BruteForce {
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
        for i in 0..self.count {
            stats.primitives_tested += 1;
            hit |= leaf(i, &mut t_max);
        }
        hit
    }

    fn any_hit<F>(&self, ray: &Ray, _t_max: f32, stats: &mut TraversalStats, mut leaf: F) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        if !ray.is_traceable() {
            return false;
        }
        for i in 0..self.count {
            stats.primitives_tested += 1;
            if leaf(i) {
                return true;
            }
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec3;

    fn three_boxes() -> Vec<Aabb> {
        vec![Aabb::new(Vec3::ZERO, Vec3::ONE); 3]
    }

    #[test]
    fn closest_hit_visits_every_primitive_with_a_shrinking_t_max() {
        let bf = BruteForce::new(&three_boxes());
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        let hits_at = [5.0, 2.0, 3.0];
        let mut seen_t_max = vec![];
        let mut stats = TraversalStats::default();
        let hit = bf.closest_hit(&ray, 10.0, &mut stats, |i, t_max| {
            seen_t_max.push(*t_max);
            let t = hits_at[i as usize];
            let closer = t < *t_max;
            if closer {
                *t_max = t;
            }
            closer
        });
        assert!(hit);
        assert_eq!(seen_t_max, [10.0, 5.0, 2.0]);
        assert_eq!(stats.primitives_tested, 3);
    }

    #[test]
    fn any_hit_stops_at_the_first_blocker() {
        let bf = BruteForce::new(&three_boxes());
        let ray = Ray::new(Vec3::ZERO, Vec3::X);
        let mut stats = TraversalStats::default();
        assert!(bf.any_hit(&ray, 1.0, &mut stats, |i| i == 1));
        assert_eq!(stats.primitives_tested, 2);
        assert!(!bf.any_hit(&ray, 1.0, &mut stats, |_| false));
    }
}
