//! What an importer (OBJ, PLY, glTF, Mitsuba XML) gives: a scene description like the TOML
//! reader's, whose relative file names start from the imported file's folder.

use crate::desc::SceneDesc;

/// A scene read from a foreign format.
#[derive(Clone, Debug)]
pub struct Imported {
    /// The scene. When `camera_given` is false its camera is a placeholder, replaced by one
    /// framing the scene's bounds.
    pub desc: SceneDesc,
    /// Whether the file had a camera.
    pub camera_given: bool,
    /// What was read but cannot be rendered as written (one line each, naming the file).
    pub warnings: Vec<String>,
}

/// A placeholder camera, for files without one.
pub fn placeholder_camera() -> toml::Spanned<crate::desc::CameraDesc> {
    use crate::desc::{CameraDesc, Finite, Vector};
    toml::Spanned::new(
        0..0,
        CameraDesc {
            eye: Vector(glam::Vec3::Z),
            look_at: Vector(glam::Vec3::ZERO),
            up: Vector(glam::Vec3::Y),
            fov: Finite(45.0),
        },
    )
}
