//! The `[camera]` table.

use super::{Finite, MotionDesc, Point, Vector};
use serde::{Deserialize, Serialize};
use toml::Spanned;

/// `[camera]`: a pinhole camera, a thin lens when `aperture` is given, or an orthographic
/// projection when `orthographic` is.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CameraDesc {
    /// Where the eye is.
    pub eye: Point,
    /// The point seen at the image's centre.
    pub look_at: Point,
    /// Which way is up in the image (default `[0, 1, 0]`).
    #[serde(default = "default_up")]
    pub up: Vector,
    /// Vertical field of view in degrees (default 45).
    #[serde(default = "default_fov")]
    pub fov: Finite,
    /// Radius of the lens's aperture, in scene units (default 0: a pinhole, all in focus).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aperture: Option<Finite>,
    /// Distance from the eye, along the view direction, of the plane in focus (default: the
    /// distance to `look_at`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub focus_distance: Option<Finite>,
    /// An orthographic projection instead of a perspective one: the height of the view, in
    /// scene units (its width follows the image's aspect). Parallel rays along the view
    /// direction start on the plane through `eye`; `fov` is not used.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orthographic: Option<Finite>,
    /// How the camera moves (see [`MotionDesc`]): the eye as a point, the view with it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub motion: Option<Spanned<MotionDesc>>,
    /// `[open, close]` in seconds: the render sees the scene over this interval (motion
    /// blur); without it, at time 0 (or `--time`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shutter: Option<Spanned<[Finite; 2]>>,
    /// The `[[medium]]` the camera sits in (fog); default none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub medium: Option<Spanned<String>>,
}

fn default_up() -> Vector {
    Vector(glam::Vec3::Y)
}

fn default_fov() -> Finite {
    Finite(45.0)
}
