//! The rays a benchmark traces: camera rays, incoherent rays and occlusion segments, all
//! fixed by a seed.

use glam::Vec3;
use lucent::accel::{Aabb, Ray};
use lucent::sampling::{hash, to_unit_float};
use lucent::scene::Scene;

/// A set of rays with the segment length each is traced over.
pub struct RaySet {
    /// The rays.
    pub rays: Vec<Ray>,
    /// `t_max` of each ray (infinite for closest-hit sets).
    pub t_max: Vec<f32>,
}

/// One ray per pixel centre of the scene's camera.
pub fn camera_rays(scene: &Scene) -> RaySet {
    let (w, h) = (scene.camera.width(), scene.camera.height());
    let rays: Vec<Ray> = (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| scene.camera.ray(x as f32 + 0.5, y as f32 + 0.5))
        .collect();
    let t_max = vec![f32::INFINITY; rays.len()];
    RaySet { rays, t_max }
}

fn uniform_point(b: Aabb, seed: u64, i: u64, dim: u32) -> Vec3 {
    let u = |k: u32| to_unit_float(hash(seed, i, 0, dim + k));
    b.min + b.extent() * Vec3::new(u(0), u(1), u(2))
}

fn uniform_direction(seed: u64, i: u64) -> Vec3 {
    let z = 1.0 - 2.0 * to_unit_float(hash(seed, i, 1, 0));
    let phi = std::f32::consts::TAU * to_unit_float(hash(seed, i, 1, 1));
    let r = (1.0 - z * z).max(0.0).sqrt();
    Vec3::new(r * phi.cos(), r * phi.sin(), z)
}

/// `n` rays from uniform points in the scene's bounds in uniform directions.
pub fn incoherent_rays(scene: &Scene, n: usize, seed: u64) -> RaySet {
    let b = scene.bounds();
    let rays = (0..n as u64)
        .map(|i| Ray::new(uniform_point(b, seed, i, 0), uniform_direction(seed, i)))
        .collect();
    RaySet {
        rays,
        t_max: vec![f32::INFINITY; n],
    }
}

/// `n` segments between pairs of uniform points in the scene's bounds (any-hit queries).
pub fn occlusion_rays(scene: &Scene, n: usize, seed: u64) -> RaySet {
    let b = scene.bounds();
    let (mut rays, mut t_max) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for i in 0..n as u64 {
        let (p, q) = (
            uniform_point(b, seed ^ 0x5eed, i, 0),
            uniform_point(b, seed ^ 0x5eed, i, 3),
        );
        let d = q - p;
        let len = d.length().max(f32::MIN_POSITIVE);
        rays.push(Ray::new(p, d / len));
        t_max.push(len);
    }
    RaySet { rays, t_max }
}
