//! The contract every acceleration structure fulfils, and the enum that picks one at run time.

use crate::{Aabb, BoundingVolumes, BruteForce, Bvh, Octree, Ray, WideBvh};
use std::fmt;
use std::str::FromStr;

/// Work counters of one or more queries; the cost a structure saves is read off these.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraversalStats {
    /// Interior nodes or cells whose bounds were tested.
    pub nodes_visited: u64,
    /// Calls of the leaf test.
    pub primitives_tested: u64,
}

impl std::ops::AddAssign for TraversalStats {
    fn add_assign(&mut self, other: Self) {
        self.nodes_visited += other.nodes_visited;
        self.primitives_tested += other.primitives_tested;
    }
}

/// A structure over primitive bounding boxes that answers ray queries through a leaf test.
///
/// Every implementation must report the same hits as [`BruteForce`]: for closest hit, the leaf
/// test is called, with a shrinking `t_max`, on at least every primitive whose box the ray
/// enters before `t_max` (boundaries included); for any hit, on every such primitive until the
/// leaf test says stop. No primitive is offered twice in one query. A primitive whose box has
/// a NaN bound is taken to be one no ray can hit, and may never be offered.
pub trait Accelerator {
    /// Closest hit along `ray` in `(0, t_max)`.
    ///
    /// `leaf(i, &mut t_max)` intersects primitive `i`; on a hit nearer than `t_max` it sets
    /// `t_max` to the hit's distance and returns `true`. Returns whether any leaf test did.
    fn closest_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, leaf: F) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool;

    /// Any hit along `ray` in `(0, t_max)`: `leaf(i)` returns `true` to stop the traversal
    /// (primitive `i` blocks the ray). Returns whether a leaf test stopped it.
    fn any_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, leaf: F) -> bool
    where
        F: FnMut(u32) -> bool;
}

/// The structures a user can choose from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AccelKind {
    /// Every primitive tested for every ray: the lecture notes' loop, and the oracle.
    BruteForce,
    /// Every primitive's box tested first, the primitive only when its box is hit.
    BoundingVolumes,
    /// Glassner's octree: cells of eight, front to back, with mailboxes.
    Octree,
    /// A binary SAH bounding volume hierarchy.
    Bvh,
    /// An eight-wide BVH with SIMD box tests, and SIMD triangle leaves for meshes: the fastest.
    #[default]
    Wide,
}

impl AccelKind {
    /// Every kind, in the order a table lists them.
    pub const ALL: [AccelKind; 5] = [
        AccelKind::BruteForce,
        AccelKind::BoundingVolumes,
        AccelKind::Octree,
        AccelKind::Bvh,
        AccelKind::Wide,
    ];

    /// The name used on the command line and in scene files.
    pub fn name(self) -> &'static str {
        match self {
            AccelKind::BruteForce => "brute",
            AccelKind::BoundingVolumes => "bounds",
            AccelKind::Octree => "octree",
            AccelKind::Bvh => "bvh",
            AccelKind::Wide => "wide",
        }
    }

    /// Builds this structure over `boxes` (primitive `i` has box `boxes[i]`).
    pub fn build(self, boxes: &[Aabb]) -> AnyAccelerator {
        match self {
            AccelKind::BruteForce => AnyAccelerator::BruteForce(BruteForce::new(boxes)),
            AccelKind::BoundingVolumes => {
                AnyAccelerator::BoundingVolumes(BoundingVolumes::new(boxes))
            }
            AccelKind::Octree => AnyAccelerator::Octree(Octree::new(boxes)),
            AccelKind::Bvh => AnyAccelerator::Bvh(Bvh::new(boxes)),
            AccelKind::Wide => AnyAccelerator::Wide(WideBvh::new(boxes)),
        }
    }
}

impl fmt::Display for AccelKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for AccelKind {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        AccelKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| {
                let names: Vec<_> = AccelKind::ALL.iter().map(|k| k.name()).collect();
                format!(
                    "unknown accelerator `{s}` (expected one of: {})",
                    names.join(", ")
                )
            })
    }
}

/// One built structure of any kind; static dispatch through `match`.
#[derive(Clone, Debug)]
pub enum AnyAccelerator {
    /// See [`BruteForce`].
    BruteForce(BruteForce),
    /// See [`BoundingVolumes`].
    BoundingVolumes(BoundingVolumes),
    /// See [`Octree`].
    Octree(Octree),
    /// See [`Bvh`].
    Bvh(Bvh),
    /// See [`WideBvh`].
    Wide(WideBvh),
}

/// Size and shape of a built structure, for `lucent info` and benchmarks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct AccelInfo {
    /// Nodes or cells (0 for the flat structures).
    pub nodes: usize,
    /// Levels from the root to the deepest leaf (0 for the flat structures).
    pub depth: usize,
    /// Bytes of the structure itself.
    pub bytes: usize,
}

/// Calls `$body` with `$a` bound to the structure inside `$self`, whatever its kind.
macro_rules! dispatch {
    ($self:expr, $a:ident => $body:expr) => {
        match $self {
            AnyAccelerator::BruteForce($a) => $body,
            AnyAccelerator::BoundingVolumes($a) => $body,
            AnyAccelerator::Octree($a) => $body,
            AnyAccelerator::Bvh($a) => $body,
            AnyAccelerator::Wide($a) => $body,
        }
    };
}

impl AnyAccelerator {
    /// Which kind this is.
    pub fn kind(&self) -> AccelKind {
        match self {
            AnyAccelerator::BruteForce(_) => AccelKind::BruteForce,
            AnyAccelerator::BoundingVolumes(_) => AccelKind::BoundingVolumes,
            AnyAccelerator::Octree(_) => AccelKind::Octree,
            AnyAccelerator::Bvh(_) => AccelKind::Bvh,
            AnyAccelerator::Wide(_) => AccelKind::Wide,
        }
    }

    /// Node count, depth and memory.
    pub fn info(&self) -> AccelInfo {
        match self {
            AnyAccelerator::BruteForce(_) => AccelInfo::default(),
            AnyAccelerator::BoundingVolumes(a) => AccelInfo {
                bytes: a.memory_bytes(),
                ..AccelInfo::default()
            },
            AnyAccelerator::Octree(a) => AccelInfo {
                nodes: a.cell_count(),
                depth: a.depth(),
                bytes: a.memory_bytes(),
            },
            AnyAccelerator::Bvh(a) => AccelInfo {
                nodes: a.nodes().len(),
                depth: a.depth(),
                bytes: a.memory_bytes(),
            },
            AnyAccelerator::Wide(a) => AccelInfo {
                nodes: a.nodes().len(),
                depth: a.depth(),
                bytes: a.memory_bytes(),
            },
        }
    }
}

impl Accelerator for AnyAccelerator {
    #[inline]
    fn closest_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, leaf: F) -> bool
    where
        F: FnMut(u32, &mut f32) -> bool,
    {
        dispatch!(self, a => a.closest_hit(ray, t_max, stats, leaf))
    }

    #[inline]
    fn any_hit<F>(&self, ray: &Ray, t_max: f32, stats: &mut TraversalStats, leaf: F) -> bool
    where
        F: FnMut(u32) -> bool,
    {
        dispatch!(self, a => a.any_hit(ray, t_max, stats, leaf))
    }
}
