//! The `[camera]` table.

use super::{Finite, Vector};
use serde::{Deserialize, Serialize};

/// `[camera]`: a pinhole camera.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    /// Where the eye is.
    pub eye: Vector,
    /// The point seen at the image's centre.
    pub look_at: Vector,
    /// Which way is up in the image (default `[0, 1, 0]`).
    #[serde(default = "default_up")]
    pub up: Vector,
    /// Vertical field of view in degrees (default 45).
    #[serde(default = "default_fov")]
    pub fov: Finite,
}

fn default_up() -> Vector {
    Vector(glam::Vec3::Y)
}

fn default_fov() -> Finite {
    Finite(45.0)
}
