//! Why a scene cannot be built.

use super::MediaError;
use thiserror::Error;

/// Why a scene cannot be built.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SceneError {
    /// A shape names a material that does not exist.
    #[error("object {object} uses material {material}, but the scene has {count} materials")]
    NoSuchMaterial {
        /// The object's id.
        object: u32,
        /// The material index it gave.
        material: u32,
        /// How many materials exist.
        count: usize,
    },
    /// An instance names a mesh that does not exist.
    #[error("object {object} places mesh {mesh}, but the scene has {count} meshes")]
    NoSuchMesh {
        /// The object's id.
        object: u32,
        /// The mesh index it gave.
        mesh: u32,
        /// How many meshes exist.
        count: usize,
    },
    /// An instance's transform cannot be inverted.
    #[error("object {0}'s transform is singular (it flattens the mesh) or not finite")]
    SingularTransform(u32),
    /// More primitives than indices can address.
    #[error("the scene has {0} primitives; at most {max} are supported", max = u32::MAX)]
    TooManyPrimitives(usize),
    /// A mesh index points past its vertex array.
    #[error("mesh {mesh}: triangle {triangle} uses vertex {vertex}, but it has {count}")]
    VertexOutOfRange {
        /// The mesh's index.
        mesh: u32,
        /// The triangle's index.
        triangle: usize,
        /// The bad vertex index.
        vertex: u32,
        /// How many vertices exist.
        count: usize,
    },
    /// A mesh's normals, texture coordinates or colours do not match its vertices.
    #[error("mesh {mesh}: {why}")]
    BadVertexData {
        /// The mesh's index.
        mesh: u32,
        /// What is wrong.
        why: String,
    },
    /// A motion is given for an object that does not exist.
    #[error("a motion is given for object {object}, but the scene has {count} objects")]
    NoSuchObject {
        /// The object id given.
        object: u32,
        /// How many objects exist.
        count: u32,
    },
    /// A motion is given for an infinite plane.
    #[error("object {0} is an infinite plane, which cannot move")]
    PlaneCannotMove(u32),
    /// A motion is given for an object that emits light.
    #[error(
        "object {0} emits light and cannot move: the light tables of the path tracer are built once for every instant"
    )]
    EmitterCannotMove(u32),
    /// A solid's material is an area light.
    #[error(
        "object {0} is a {1} and emits light: only spheres and meshes can be area lights (an emission texture glows without lighting)"
    )]
    SolidCannotEmit(u32, &'static str),
    /// A motion is given for a solid.
    #[error("object {0} is a {1}, which cannot move (only spheres and meshes can)")]
    SolidCannotMove(u32, &'static str),
    /// A solid alone has no bounds.
    #[error(
        "object {0} is an unbounded {1}: give it bounds, or cut it with an intersection or a difference"
    )]
    SolidUnbounded(u32, &'static str),
    /// A sphere's motion scales unevenly.
    #[error("object {0} is a sphere: its motion must scale alike on every axis")]
    SphereScaleNotUniform(u32),
    /// The media are wrong.
    #[error(transparent)]
    Media(#[from] MediaError),
    /// A texture or the environment names an image that does not exist.
    #[error("image {image} is used, but the scene has {count} images")]
    NoSuchImage {
        /// The image index given.
        image: u32,
        /// How many images exist.
        count: usize,
    },
}
