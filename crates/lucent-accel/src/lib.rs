//! Acceleration structures for ray tracing.
//!
//! This crate knows only rays, axis-aligned boxes and primitive indices. A structure is built
//! from the bounding boxes of the primitives (index `i` is the `i`-th box) and queried with a
//! ray and a *leaf test*: a closure the structure calls with the index of every primitive the
//! ray may hit. What a primitive is (a sphere, a triangle) is the caller's business.
//!
//! Conventions:
//! - a ray is `origin + t · dir` for `t` in `(0, t_max)`; `dir` need not be normalised, and `t`
//!   is measured in units of `dir`;
//! - closest hit: the leaf test intersects primitive `i` and, on a hit closer than the current
//!   `t_max`, lowers `t_max` to it and returns `true`; the structure uses the shrinking `t_max`
//!   to skip what lies beyond;
//! - any hit: the leaf test returns `true` to stop the traversal (the ray is blocked).
//!
//! [`brute_force`] is the oracle every other structure is held to. Builds run on rayon's threads
//! and give the same structure on any number of them. [`memory`] holds the one helper the
//! renderer shares for its large buffers (huge pages, so that their first touches are cheap).

pub mod aabb;
pub mod accelerator;
pub mod bounding_volumes;
pub mod brute_force;
pub mod bvh;
pub mod frustum;
mod mailbox;
pub mod memory;
pub mod octree;
pub mod ray;
pub mod triangle;
pub mod wide_bvh;

pub use aabb::Aabb;
pub use accelerator::{AccelInfo, AccelKind, Accelerator, AnyAccelerator, TraversalStats};
pub use bounding_volumes::BoundingVolumes;
pub use brute_force::BruteForce;
pub use bvh::Bvh;
pub use frustum::Frustum;
pub use octree::Octree;
pub use ray::Ray;
pub use wide_bvh::{Cut, WideBvh, WideTriangleBvh};
