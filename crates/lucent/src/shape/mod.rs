//! Geometry: spheres, planes, triangles and triangle meshes, and the mathematical solids
//! ([`solid`]).
//!
//! Shapes are flat data in the scene's arrays. Ray queries go through two levels of
//! accelerators: the top level indexes *primitives* (a sphere, or an instance of a mesh), and
//! each mesh has its own accelerator over its triangles, shared by all its instances. Planes
//! are unbounded and tested apart from the accelerators.

pub mod instance;
pub mod mesh;
pub mod plane;
pub mod solid;
pub mod sphere;
pub mod triangle;

pub use instance::{Instance, Transform};
pub use mesh::Mesh;
pub use plane::Plane;
pub use solid::csg::{Csg, CsgError, CsgHit, CsgOp, CsgTree};
pub use solid::{Solid, SolidPoint, SolidShape};
pub use sphere::{Roots, Sphere, SphereMap};
pub use triangle::{TriangleHit, TriangleTest};

use glam::Vec3;

/// A bounded primitive of the top-level accelerator, by index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Primitive {
    /// `Scene::spheres[i]`.
    Sphere(u32),
    /// `Scene::instances[i]`: a placed mesh, with an accelerator of its own over its triangles.
    Instance(u32),
    /// `Scene::solids[i]`: a box, cylinder, cone, disc, ellipsoid or torus.
    Solid(u32),
    /// `Scene::csgs[i]`: solids combined.
    Csg(u32),
    /// The instances stored together in world space (see the scene's module docs).
    Merged,
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
    /// Unit shading normal: the mesh's interpolated vertex normal where it has them (turned to
    /// the geometric normal's side), else the geometric normal.
    pub shading_normal: Vec3,
    /// Texture coordinates for image textures: a mesh's interpolated UVs, a sphere's lat-long
    /// coordinates, a plane's own 2D frame; see [`SurfaceHit::uv`].
    pub uv: Uv,
    /// The mesh's interpolated vertex colour, white elsewhere; multiplies the diffuse colour.
    pub color: crate::Rgb,
    /// Index into the scene's materials.
    pub material: u32,
    /// Index of the scene object hit (stable across runs; for debug views and statistics).
    pub object: u32,
    /// Which surface was hit: a ray leaving it is not tested against it again (see
    /// [`crate::spawn`]).
    pub surface: SurfaceId,
    /// A triangle's barycentric weights of its corners A, B, C at the hit; zero for other
    /// shapes.
    pub bary: [f32; 3],
    /// A bound on the absolute rounding error of `point`, per axis.
    pub error: Vec3,
    /// `∂p/∂u`, the change of the point with the first texture coordinate (world space; the
    /// shading frame's tangent; see [`SurfaceHit::dpdv`]).
    pub dpdu: Vec3,
    /// `∂p/∂v`. Both come from the shape's parametrisation: a mesh's UVs (its barycentric
    /// coordinates without them), a sphere's latitude and longitude, a plane's own frame.
    /// [`crate::scene::Scene`]'s queries leave both (and `tangent`) zero on meshes and spheres
    /// whose material does not need them ([`crate::material::Material::needs_tangents`]).
    pub dpdv: Vec3,
    /// A mesh's own tangent frame where it has one (glTF's `TANGENT`, or MikkTSpace's): the
    /// interpolated tangent (world space, not unit) the shading frame follows instead of
    /// `dpdu`, and in `w` the bitangent's handedness, `±1` (the bitangent is `w·(n × t)`).
    pub tangent: Option<glam::Vec4>,
}

/// A hit's texture coordinates, or how to find them when a texture asks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Uv {
    /// These coordinates.
    At(glam::Vec2),
    /// A sphere's longitude and latitude of the hit's normal in its [`SphereMap`]: worked out
    /// only when a texture needs them (an `atan2` and an `acos` were a seventh of a camera
    /// ray's whole query on the default scene, for nothing when the sphere has no image).
    Sphere(SphereMap),
}

impl SurfaceHit {
    /// The texture coordinates of the hit (see [`SurfaceHit::uv`]'s field).
    #[inline]
    pub fn uv(&self) -> glam::Vec2 {
        match self.uv {
            Uv::At(uv) => uv,
            Uv::Sphere(map) => map.uv(self.normal),
        }
    }
}

/// One surface of the scene, as a ray leaving it must know it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SurfaceId {
    /// An infinite plane.
    Plane(u32),
    /// A sphere.
    Sphere(u32),
    /// A solid (see [`Solid`]).
    Solid(u32),
    /// A combination of solids (see [`Csg`]).
    Csg(u32),
    /// Triangle `index` of instance `instance`.
    Triangle {
        /// The instance.
        instance: u32,
        /// The triangle within its mesh.
        index: u32,
    },
}

/// `γ(n) = n·ε / (1 − n·ε)` with `ε = 2⁻²⁴`: the relative error bound of `n` chained roundings
/// (Higham; as pbrt uses it for hit-point error bounds).
pub const fn gamma(n: u32) -> f32 {
    let e = n as f32 * f32::EPSILON * 0.5;
    e / (1.0 - e)
}
