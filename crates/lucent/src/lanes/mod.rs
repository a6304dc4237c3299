//! Code written once for one path and for eight paths in lanes (the SIMD-lanes design; see
//! `docs/path.md`, "Paths in lanes").
//!
//! Shading code that both the scalar path tracer and the lane path tracer run is generic over
//! a [`Real`]: `f32`, or [`wide::f32x8`] with a lane mask for every branch. Every operation is
//! the same IEEE operation in every lane, so lane `i` of the wide code computes exactly the
//! bits the scalar code computes for path `i`: the scalar path tracer stays the reference, and
//! the lanes are tested against it bit for bit.

mod real;
mod trig;
mod vec3;

pub use real::{Mask, Real};
pub use trig::{sin_cos_quarter, sin_cos_turn};
pub use vec3::V3;

/// Paths per lane group.
pub const LANES: usize = 8;
