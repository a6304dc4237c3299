//! What an importer (OBJ, PLY, glTF, Mitsuba XML) gives: a scene description like the TOML
//! reader's, whose relative file names start from the imported file's folder — and the pieces
//! a scene without a camera or lights gets.

use crate::desc::{
    CameraDesc, Color, Finite, LightDesc, LightKind, MaterialDesc, Point, SceneDesc, Vector,
};
use crate::framing::Framing;
use glam::Vec3;
use lucent::Rgb;
use toml::Spanned;

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
    /// The file's lights are all it has, none meaning darkness (POV-Ray's ambient-only
    /// scenes): no default light is added.
    pub lit_as_given: bool,
}

/// A placeholder camera, for files without one.
pub fn placeholder_camera() -> Spanned<CameraDesc> {
    Spanned::new(
        0..0,
        CameraDesc {
            eye: Point(glam::DVec3::Z),
            look_at: Point(glam::DVec3::ZERO),
            up: Vector(Vec3::Y),
            fov: Finite(45.0),
            aperture: None,
            focus_distance: None,
            orthographic: None,
            motion: None,
            shutter: None,
            medium: None,
        },
    )
}

/// The light a scene without any gets: white, travelling away from the upper left behind a
/// framing camera (of the default [`Framing`]: [`crate::SceneFile::set_framing`] turns it with
/// the camera), with a little ambient light.
pub fn add_default_light(desc: &mut SceneDesc) {
    let mut light = LightDesc::new(LightKind::Directional);
    let direction = Framing::default().light_direction();
    light.direction = Some(Spanned::new(0..0, Vector(direction)));
    desc.lights.push(Spanned::new(0..0, light));
    desc.world.ambient = Color(Rgb::gray(0.1));
    desc.world.background = Color(Rgb::gray(0.05));
}

/// The material of mesh files without their own: a light grey with a soft highlight.
pub fn default_material(name: &str) -> MaterialDesc {
    let mut m = MaterialDesc::named(name);
    m.ka = Some(Color(Rgb::gray(0.8)));
    m.kd = Some(crate::desc::TextureDesc::gray(0.8));
    m.ks = Some(Color(Rgb::gray(0.2)));
    m.shininess = Some(Spanned::new(0..0, Finite(30.0)));
    m
}
