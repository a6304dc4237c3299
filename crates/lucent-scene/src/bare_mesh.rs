//! A mesh file on its own, made into a scene: a grey material, a camera framing its bounds
//! from the front (+z, looking down −z), a light at the camera, a dark grey background.

use crate::build::Loaded;
use crate::error::LoadError;
use crate::hash::Fingerprint;
use crate::mesh_file::read_mesh_fingerprinted;
use glam::Vec3;
use lucent::Rgb;
use lucent::accel::AccelKind;
use lucent::camera::Camera;
use lucent::light::{Falloff, Light, PointLight};
use lucent::material::Material;
use lucent::render::RenderSettings;
use lucent::scene::SceneBuilder;
use std::path::Path;

/// Vertical field of view of the framing camera, in degrees.
const FOV: f32 = 40.0;

/// The scene of the mesh file (OBJ or PLY) at `path`, rendered at `width × height` with `accel`.
pub fn bare_mesh_scene(
    path: &Path,
    width: u32,
    height: u32,
    accel: AccelKind,
) -> Result<Loaded, LoadError> {
    let mut inputs = Fingerprint::default();
    let mesh = read_mesh_fingerprinted(path, &mut inputs)?;
    let bounds = mesh.bounds();
    if bounds.is_empty() {
        return Err(LoadError::file(path, "the mesh has no vertices"));
    }
    // Far enough back that the bounding sphere fits the narrower field of view.
    let radius = (0.5 * bounds.extent().length()).max(1e-6);
    let aspect = width as f32 / height as f32;
    let half_fov = (0.5 * FOV)
        .to_radians()
        .tan()
        .min(aspect * (0.5 * FOV).to_radians().tan());
    let distance = radius / half_fov.atan().sin();
    let target = bounds.center();
    let eye = target + Vec3::new(0.0, 0.25 * radius, distance);
    let camera = Camera::new(eye, target, Vec3::Y, FOV, width, height)
        .map_err(|e| LoadError::file(path, e.to_string()))?;

    let mut b = SceneBuilder::new(camera);
    b.background(Rgb::gray(0.05))
        .ambient(Rgb::gray(0.1))
        .accelerator(accel);
    let grey = b.material(Material {
        ka: Rgb::gray(0.8),
        ks: Rgb::gray(0.2),
        shininess: 30.0,
        ..Material::diffuse(Rgb::gray(0.8))
    });
    b.mesh(mesh, grey);
    b.light(Light::Point(PointLight {
        position: eye + Vec3::new(radius, radius, 0.0),
        intensity: Rgb::WHITE,
        falloff: Falloff::None,
    }));
    let scene = b
        .build()
        .map_err(|e| LoadError::file(path, e.to_string()))?;
    Ok(Loaded {
        scene,
        settings: RenderSettings::default(),
        inputs: inputs.value(),
    })
}
