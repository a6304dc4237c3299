//! Geometry: spheres, planes, triangles and triangle meshes.
//!
//! Shapes are flat data in the scene's arrays. Ray queries go through two levels of
//! accelerators: the top level indexes *primitives* (a sphere, or an instance of a mesh), and
//! each mesh has its own accelerator over its triangles, shared by all its instances. Planes
//! are unbounded and tested apart from the accelerators.

pub mod instance;
pub mod mesh;
pub mod plane;
pub mod sphere;
pub mod triangle;

pub use instance::{Instance, Transform};
pub use mesh::Mesh;
pub use plane::Plane;
pub use sphere::{Roots, Sphere};
pub use triangle::{TriangleHit, TriangleTest};

use glam::Vec3;

/// A bounded primitive of the top-level accelerator, by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Primitive {
    /// `Scene::spheres[i]`.
    Sphere(u32),
    /// `Scene::instances[i]`: a placed mesh, with an accelerator of its own over its triangles.
    Instance(u32),
}

/// What a ray hit, and the surface there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceHit {
    /// Ray parameter of the hit.
    pub t: f32,
    /// The hit point, on the surface as closely as it can be computed.
    pub point: Vec3,
    /// Unit geometric normal as the shape defines it (outward for spheres, the plane's normal,
    /// the winding's normal for triangles), whichever side the ray came from.
    pub normal: Vec3,
    /// Coordinates for solid textures: the world position, or the plane's own 2D frame.
    pub texture_coords: Vec3,
    /// Index into the scene's materials.
    pub material: u32,
    /// Index of the scene object hit (stable across runs; for debug views and statistics).
    pub object: u32,
}
