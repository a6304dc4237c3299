//! lucent: a ray tracer for learning, teaching and using ray tracing.
//!
//! This crate is the renderer. It reads no files: a scene arrives as values, built with a
//! [`scene::SceneBuilder`] (the `lucent-scene` crate turns scene files into one), and leaves as
//! a [`film::Film`] of linear radiance.
//!
//! # Conventions
//! - Right-handed coordinates, y up; angles in radians in code (degrees only in files).
//! - Colours are linear RGB ([`Rgb`]); no gamma inside the renderer.
//! - A ray is `origin + t·dir`, `t > 0`; camera and secondary rays have unit `dir`.
//! - Normals are unit length. A hit's normal is the shape's own geometric normal (outward for
//!   spheres), whichever side the ray came from; shading turns it to face the ray.
//! - Image rows run from the top (row 0) down.
//! - Every random number is a pure function of (seed, pixel, sample, dimension): see
//!   [`sampling`].

pub mod bsdf;
pub mod camera;
pub mod color;
pub mod film;
mod first_hits;
pub mod integrator;
pub mod lanes;
pub mod light;
pub mod material;
pub mod medium;
pub mod motion;
pub mod optics;
pub mod render;
pub mod sampling;
pub mod scene;
pub mod schedule;
pub mod shape;
pub mod spawn;
pub mod special;
pub mod study;
pub mod texture;

pub use color::Rgb;
pub use lucent_accel as accel;
