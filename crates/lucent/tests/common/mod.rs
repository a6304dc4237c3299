//! Shared helpers of the renderer's integration tests.
#![allow(dead_code)] // each test file uses a different subset

use glam::Vec3;
use lucent::Rgb;
use lucent::camera::Camera;
use lucent::material::Material;
use lucent::render::{Hooks, RenderSettings, Rendered, render};
use lucent::scene::{Scene, SceneBuilder};
use lucent::shape::{Mesh, Sphere};
use std::sync::atomic::AtomicBool;

/// A camera that no test looks through.
pub fn any_camera() -> Camera {
    Camera::new(Vec3::new(0.0, 0.0, 10.0), Vec3::ZERO, Vec3::Y, 45.0, 4, 4).unwrap()
}

/// An icosphere of radius 1 about the origin, `subdivisions` times refined, outward winding.
pub fn icosphere(subdivisions: u32) -> Mesh {
    let t = (1.0 + 5f32.sqrt()) / 2.0;
    let mut positions: Vec<Vec3> = [
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ]
    .iter()
    .map(|&p| Vec3::from_array(p).normalize())
    .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdivisions {
        let mut midpoints = std::collections::HashMap::new();
        let mut mid = |a: u32, b: u32, positions: &mut Vec<Vec3>| -> u32 {
            *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                positions.push((positions[a as usize] + positions[b as usize]).normalize());
                positions.len() as u32 - 1
            })
        };
        let mut next = Vec::with_capacity(triangles.len() * 4);
        for [a, b, c] in triangles {
            let (ab, bc, ca) = (
                mid(a, b, &mut positions),
                mid(b, c, &mut positions),
                mid(c, a, &mut positions),
            );
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        triangles = next;
    }
    Mesh::new(positions, triangles)
}

/// `mesh` scaled by `scale` and moved by `offset`.
pub fn placed(mut mesh: Mesh, scale: f32, offset: Vec3) -> Mesh {
    mesh.positions
        .iter_mut()
        .for_each(|p| *p = *p * scale + offset);
    mesh
}

/// A scene holding only `mesh`.
pub fn mesh_scene(mesh: Mesh) -> Scene {
    let mut b = SceneBuilder::new(any_camera());
    let m = b.material(Material::diffuse(Rgb::gray(0.5)));
    b.mesh(mesh, m);
    b.build().unwrap()
}

/// A scene holding only `sphere`.
pub fn sphere_scene(sphere: Sphere) -> Scene {
    let mut b = SceneBuilder::new(any_camera());
    let m = b.material(Material::diffuse(Rgb::gray(0.5)));
    b.sphere(sphere, m);
    b.build().unwrap()
}

/// A unit vector from two numbers in [0, 1).
pub fn unit_vector(u: f32, v: f32) -> Vec3 {
    let z = 1.0 - 2.0 * u;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = std::f32::consts::TAU * v;
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// Renders `scene` with `settings` to the end: no cancellation, progress or checkpoints.
pub fn render_all(scene: &Scene, settings: &RenderSettings) -> Rendered {
    let cancel = AtomicBool::new(false);
    let hooks = Hooks {
        cancel: &cancel,
        progress: &|_, _| {},
        checkpoint: None,
    };
    render(scene, settings, None, &hooks).unwrap()
}
