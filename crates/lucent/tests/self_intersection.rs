//! The self-intersection policy: secondary rays never hit the surface they leave, on spheres,
//! meshes and planes, small and large, near and far from the origin.

mod common;

use common::{any_camera, icosphere, mesh_scene, placed, sphere_scene, unit_vector};
use glam::{Affine3A, Vec3};
use lucent::Rgb;
use lucent::accel::{Ray, TraversalStats};
use lucent::material::Material;
use lucent::sampling::{mix64, to_unit_float};
use lucent::scene::{Scene, SceneBuilder};
use lucent::shape::{Mesh, Plane, Sphere};
use lucent::spawn::spawn_ray;

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f32 {
        self.0 = mix64(self.0);
        to_unit_float(self.0)
    }

    fn unit(&mut self) -> Vec3 {
        let (u, v) = (self.next(), self.next());
        unit_vector(u, v)
    }
}

/// For many rays aimed at the (convex) object: rays leaving the hit point outwards hit nothing,
/// shadow rays outwards are never blocked, and rays leaving it inwards reach the far side.
fn check_convex(scene: &Scene, center: Vec3, radius: f32, rays: usize) {
    let mut stats = TraversalStats::default();
    let mut rng = Rng(99);
    for _ in 0..rays {
        let dir = rng.unit();
        let aim = center + 0.9 * radius * rng.unit();
        let ray = Ray::new(aim - 4.0 * radius * dir, dir);
        let Some(hit) = scene.intersect(&ray, &mut stats) else {
            continue;
        };
        let n = hit.normal;
        // Not grazing: at least 17° off the tangent plane, so that on a faceted mesh the inward
        // ray cannot legitimately meet a neighbouring facet right away.
        let out = rng.unit();
        let out = if out.dot(n) < 0.0 { -out } else { out };
        let out = if out.dot(n) < 0.3 {
            (out + n).normalize()
        } else {
            out
        };
        let (leaving, from) = spawn_ray(&hit, out);
        let again = scene.intersect_from(&leaving, Some(from), &mut stats);
        assert_eq!(again, None, "outgoing ray re-hit at {}", hit.point);
        let blocked = scene.occlusion(&leaving, 10.0 * radius, Some(from), &mut stats, |_, _| true);
        assert!(!blocked, "shadow acne at {}", hit.point);
        let (inward, from) = spawn_ray(&hit, -out);
        let far = scene
            .intersect_from(&inward, Some(from), &mut stats)
            .expect("the inward ray hits the far side");
        assert!(
            far.t > 0.2 * radius,
            "inward ray re-hit its own point (t = {})",
            far.t
        );
    }
}

#[test]
fn spheres_small_and_large_near_and_far_from_the_origin() {
    for (center, radius) in [
        (Vec3::ZERO, 1.0),
        (Vec3::new(0.3, -0.2, 0.1), 0.01),
        (Vec3::new(1e4, 2e3, -5e3), 50.0),
        (Vec3::new(-300.0, 0.0, 100.0), 1.0),
        // Large spheres whose surface passes near the origin: a ground sphere.
        (Vec3::new(0.0, -1000.0, 0.0), 1000.0),
        (Vec3::new(0.0, -1e5, 0.0), 1e5),
        // Issue 26's offsets and scales: a unit sphere 1e5 out, and one scaled by 1e-6 and 1e6.
        (Vec3::splat(1e5), 1.0),
        (Vec3::new(1e5, -1e5, 3e4), 2.0),
        (Vec3::splat(1e-6), 1e-6),
        (Vec3::splat(1e6), 1e6),
        // 1e7 out, where f32 coordinates are whole units apart: spheres tens to millions of
        // units across (a unit sphere there is two ulps wide, out of reach of f32 world space).
        (Vec3::splat(1e7), 100.0),
        (Vec3::new(1e7, -1e7, 3e6), 20.0),
        (Vec3::new(0.0, -1e7, 0.0), 1e7),
    ] {
        check_convex(
            &sphere_scene(Sphere { center, radius }),
            center,
            radius,
            rays(20_000),
        );
    }
}

/// `n` rays per case, or `SELF_INTERSECTION_RAYS` of them (10⁶ for the measure).
fn rays(n: usize) -> usize {
    std::env::var("SELF_INTERSECTION_RAYS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(n)
}

#[test]
fn meshes_small_and_large_near_and_far_from_the_origin() {
    for (center, radius) in [
        (Vec3::ZERO, 1.0),
        (Vec3::new(1e4, 2e3, -5e3), 50.0),
        (Vec3::new(0.5, 0.5, 0.5), 0.02),
        (Vec3::new(0.0, -1000.0, 0.0), 1000.0),
        (Vec3::splat(1e5), 1.0),
        (Vec3::splat(1e-6), 1e-6),
        (Vec3::splat(1e6), 1e6),
        (Vec3::splat(1e7), 100.0),
        (Vec3::new(-1e7, 1e7, 2e6), 1e3),
    ] {
        check_convex(
            &mesh_scene(placed(icosphere(3), radius, center)),
            center,
            radius,
            rays(4_000),
        );
    }
}

/// Adds a ground of material `m` to a scene.
type AddGround = Box<dyn Fn(&mut SceneBuilder, u32)>;

/// Shadow rays from a large, finely tessellated ground (coplanar neighbours at ±1000) and from
/// an infinite plane and a large ground sphere, towards a light above: none is blocked, since
/// nothing lies between the ground and the light.
#[test]
fn no_shadow_acne_on_large_grounds() {
    let grid = |n: u32, half: f32, tilt: f32| {
        let mut positions = vec![];
        for j in 0..=n {
            for i in 0..=n {
                let (x, z) = (
                    -half + 2.0 * half * i as f32 / n as f32,
                    -half + 2.0 * half * j as f32 / n as f32,
                );
                positions.push(Vec3::new(x, tilt * x, z));
            }
        }
        let mut triangles = vec![];
        for j in 0..n {
            for i in 0..n {
                let k = j * (n + 1) + i;
                triangles.push([k, k + n + 1, k + 1]);
                triangles.push([k + 1, k + n + 1, k + n + 2]);
            }
        }
        Mesh::new(positions, triangles)
    };
    let grounds: Vec<(&str, AddGround)> = vec![
        (
            "flat grid",
            Box::new(move |b: &mut SceneBuilder, m| {
                b.mesh(grid(64, 1000.0, 0.0), m);
            }),
        ),
        (
            "tilted grid",
            Box::new(move |b: &mut SceneBuilder, m| {
                b.mesh(grid(64, 1000.0, 0.37), m);
            }),
        ),
        (
            "two huge tilted triangles",
            Box::new(move |b: &mut SceneBuilder, m| {
                b.mesh(grid(1, 1000.0, 0.37), m);
            }),
        ),
        (
            "instanced grid",
            Box::new(move |b: &mut SceneBuilder, m| {
                let id = b.add_mesh(grid(16, 1.0, 0.0));
                b.instance(id, Affine3A::from_scale(Vec3::new(1000.0, 1.0, 1000.0)), m);
            }),
        ),
        (
            "plane",
            Box::new(|b: &mut SceneBuilder, m| {
                b.plane(Plane::new(Vec3::ZERO, Vec3::Y), m);
            }),
        ),
        (
            "ground sphere",
            Box::new(|b: &mut SceneBuilder, m| {
                b.sphere(
                    Sphere {
                        center: Vec3::new(0.0, -1000.0, 0.0),
                        radius: 1000.0,
                    },
                    m,
                );
            }),
        ),
    ];
    for (name, add) in grounds {
        let mut b = SceneBuilder::new(any_camera());
        let m = b.material(Material::diffuse(Rgb::gray(0.5)));
        add(&mut b, m);
        let scene = b.build().unwrap();
        let mut stats = TraversalStats::default();
        let mut rng = Rng(5);
        let light = Vec3::new(3.0, 50.0, -2.0);
        let mut acne = 0;
        for _ in 0..20_000 {
            // Camera rays from above hitting the ground near the origin.
            let eye = Vec3::new(0.0, 5.0, 8.0);
            let target = Vec3::new(10.0 * (rng.next() - 0.5), 0.0, 10.0 * (rng.next() - 0.5));
            let ray = Ray::new(eye, (target - eye).normalize());
            let Some(hit) = scene.intersect(&ray, &mut stats) else {
                continue;
            };
            let to_light = light - hit.point;
            let (shadow, from) = spawn_ray(&hit, to_light.normalize());
            if scene.occlusion(
                &shadow,
                to_light.length(),
                Some(from),
                &mut stats,
                |_, _| true,
            ) {
                acne += 1;
            }
        }
        assert_eq!(
            acne, 0,
            "{name}: {acne} shadow rays blocked by the ground itself"
        );
    }
}
