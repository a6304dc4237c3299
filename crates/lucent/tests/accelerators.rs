//! Every accelerator finds the same surfaces as brute force, through the whole scene (two
//! levels, instances, ties), and none lets a ray slip through a closed mesh.

mod common;

use common::{any_camera, icosphere, unit_vector};
use glam::{Affine3A, Quat, Vec3};
use lucent::Rgb;
use lucent::accel::{AccelKind, Ray, TraversalStats};
use lucent::material::Material;
use lucent::sampling::{mix64, to_unit_float};
use lucent::scene::{Scene, SceneBuilder};
use lucent::shape::{Mesh, Plane, Sphere};
use proptest::prelude::*;

/// What a test scene is made of, so that it can be built once per accelerator.
#[derive(Clone, Debug)]
struct Parts {
    spheres: Vec<(Vec3, f32)>,
    meshes: Vec<Vec<[Vec3; 3]>>,
    /// (mesh, transform) placements.
    instances: Vec<(usize, Affine3A)>,
    plane: Option<(Vec3, Vec3)>,
}

fn build(parts: &Parts, kind: AccelKind) -> Scene {
    let mut b = SceneBuilder::new(any_camera());
    b.accelerator(kind);
    // One material per object, so materials tell objects apart in the comparison.
    for &(c, r) in &parts.spheres {
        let m = b.material(Material::diffuse(Rgb::gray(0.5)));
        b.sphere(
            Sphere {
                center: c,
                radius: r,
            },
            m,
        );
    }
    if let Some((p, n)) = parts.plane {
        let m = b.material(Material::diffuse(Rgb::gray(0.5)));
        b.plane(Plane::new(p, n), m);
    }
    let ids: Vec<u32> = parts
        .meshes
        .iter()
        .map(|tris| {
            let positions = tris.iter().flatten().copied().collect();
            let triangles = (0..tris.len() as u32)
                .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
                .collect();
            b.add_mesh(Mesh::new(positions, triangles))
        })
        .collect();
    for &(mesh, transform) in &parts.instances {
        let m = b.material(Material::diffuse(Rgb::gray(0.5)));
        b.instance(ids[mesh], transform, m);
    }
    b.build().unwrap()
}

fn vec3(r: f32) -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(-r..r).prop_map(Vec3::from_array)
}

fn triangle() -> impl Strategy<Value = [Vec3; 3]> {
    prop_oneof![
        4 => [vec3(5.0), vec3(5.0), vec3(5.0)],
        // Axis-aligned: all three in a plane z = const (flat boxes).
        2 => (vec3(5.0), vec3(5.0), vec3(5.0)).prop_map(|(a, b, c)| [a, Vec3::new(b.x, b.y, a.z), Vec3::new(c.x, c.y, a.z)]),
        // Degenerate: collinear, or a point.
        1 => (vec3(5.0), vec3(5.0)).prop_map(|(a, b)| [a, b, (a + b) / 2.0]),
        1 => vec3(5.0).prop_map(|a| [a, a, a]),
        // On a coarse grid: coplanar, touching, exactly shared edges.
        2 => prop::array::uniform3(prop::array::uniform3(-3i32..3)).prop_map(|t| t.map(|p| Vec3::from_array(p.map(|v| v as f32)))),
    ]
}

fn transform() -> impl Strategy<Value = Affine3A> {
    prop_oneof![
        2 => Just(Affine3A::IDENTITY),
        3 => (vec3(1.0), 0.0f32..6.3, vec3(6.0), 0.3f32..2.0, any::<bool>()).prop_map(|(axis, angle, t, s, mirror)| {
            let axis = if axis.length() > 1e-3 { axis.normalize() } else { Vec3::Y };
            let scale = Vec3::new(if mirror { -s } else { s }, s * 1.3, s * 0.8);
            Affine3A::from_scale_rotation_translation(scale, Quat::from_axis_angle(axis, angle), t)
        }),
    ]
}

fn parts() -> impl Strategy<Value = Parts> {
    (
        prop::collection::vec((vec3(6.0), 0.01f32..2.0), 0..12),
        prop::collection::vec(prop::collection::vec(triangle(), 1..25), 1..4),
        prop::collection::vec((0..3usize, transform()), 0..6),
        prop::option::of((vec3(3.0), vec3(1.0))),
    )
        .prop_map(|(spheres, meshes, placements, plane)| {
            let n = meshes.len();
            let mut instances: Vec<_> = placements.into_iter().map(|(m, t)| (m % n, t)).collect();
            // Every mesh placed at least once, and the first twice in the same place: ties.
            instances.push((0, Affine3A::IDENTITY));
            instances.push((0, Affine3A::IDENTITY));
            let plane = plane.filter(|(_, n)| n.length() > 1e-3);
            Parts {
                spheres,
                meshes,
                instances,
                plane,
            }
        })
}

fn ray() -> impl Strategy<Value = Ray> {
    let axis = (0..6usize).prop_map(|k| {
        let mut d = Vec3::ZERO;
        d[k % 3] = if k < 3 { 1.0 } else { -1.0 };
        d
    });
    let dir = prop_oneof![3 => vec3(1.0).prop_filter("non-zero", |d| d.length() > 1e-3).prop_map(|d| d.normalize()), 1 => axis];
    (vec3(12.0), dir).prop_map(|(o, d)| Ray::new(o, d))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn every_accelerator_finds_what_brute_force_finds(parts in parts(), rays in prop::collection::vec((ray(), 0.1f32..20.0), 1..30)) {
        let scenes: Vec<Scene> = AccelKind::ALL.iter().map(|&k| build(&parts, k)).collect();
        let mut stats = TraversalStats::default();
        for (ray, segment) in &rays {
            let want = scenes[0].intersect(ray, &mut stats);
            let want_occluded = scenes[0].occluded(ray, *segment, &mut stats);
            for (kind, scene) in AccelKind::ALL.iter().zip(&scenes).skip(1) {
                prop_assert_eq!(scene.intersect(ray, &mut stats), want, "{} on {:?}", kind, ray);
                prop_assert_eq!(scene.occluded(ray, *segment, &mut stats), want_occluded, "{} occlusion on {:?}", kind, ray);
            }
        }
    }
}

/// A closed icosphere with every vertex moved along its normal by up to ±2% of the radius.
fn bumped_icosphere(subdivisions: u32, seed: u64) -> Mesh {
    let mut mesh = icosphere(subdivisions);
    for (i, p) in mesh.positions.iter_mut().enumerate() {
        *p *= 1.0 + 0.04 * (to_unit_float(mix64(seed ^ i as u64)) - 0.5);
    }
    mesh
}

/// Rays aimed exactly at the mesh's vertices and at points of its edges, from outside and from
/// inside: every one hits. Outside origins lie within 30° of the target's radial direction, so
/// that no ray merely grazes the silhouette (where a miss by rounding is legitimate).
fn count_misses(scene: &Scene, mesh: &Mesh, to_world: Affine3A, rays: usize) -> usize {
    let mut stats = TraversalStats::default();
    let mut state = 7u64;
    let mut next = || {
        state = mix64(state);
        to_unit_float(state)
    };
    let center = to_world.transform_point3(Vec3::ZERO);
    let mut misses = 0;
    for i in 0..rays {
        let [a, b, c] = mesh.vertices((i % mesh.triangles.len()) as u32);
        let local = match i % 3 {
            0 => a,                 // a vertex
            1 => a.lerp(b, next()), // a point of an edge
            _ => b.lerp(c, next()),
        };
        let target = to_world.transform_point3(local);
        let origin = if i % 2 == 0 {
            let radial = (local.normalize() + 0.5 * unit_vector(next(), next())).normalize();
            center + 5.0 * to_world.transform_vector3(radial) // outside
        } else {
            center + 0.3 * unit_vector(next(), next()) // inside
        };
        let ray = Ray::new(origin, (target - origin).normalize());
        if scene.intersect(&ray, &mut stats).is_none() {
            misses += 1;
        }
    }
    misses
}

#[test]
fn no_ray_slips_through_a_closed_mesh() {
    let mesh = bumped_icosphere(3, 42);
    let far = Vec3::new(1.0e4, -2.0e3, 5.0e3);
    for kind in AccelKind::ALL {
        // The hierarchies take a million rays; the flat structures test every triangle per
        // ray, so they take fewer.
        let rays = if matches!(kind, AccelKind::BruteForce | AccelKind::BoundingVolumes) {
            30_000
        } else {
            1_000_000
        };
        for to_world in [Affine3A::IDENTITY, Affine3A::from_translation(far)] {
            // Placed far by an instance transform, and also with the far positions stored.
            let mut b = SceneBuilder::new(any_camera());
            b.accelerator(kind);
            let m = b.material(Material::default());
            let id = b.add_mesh(mesh.clone());
            b.instance(id, to_world, m);
            let scene = b.build().unwrap();
            assert_eq!(
                count_misses(&scene, &mesh, to_world, rays / 2),
                0,
                "{kind}, instanced at {}",
                to_world.translation
            );

            let mut baked = mesh.clone();
            baked
                .positions
                .iter_mut()
                .for_each(|p| *p = to_world.transform_point3(*p));
            let mut b = SceneBuilder::new(any_camera());
            b.accelerator(kind);
            let m = b.material(Material::default());
            b.mesh(baked, m);
            let scene = b.build().unwrap();
            assert_eq!(
                count_misses(&scene, &mesh, to_world, rays / 2),
                0,
                "{kind}, stored at {}",
                to_world.translation
            );
        }
    }
}

/// A mesh placed a thousand times is stored once: memory grows with the placements, not with
/// the triangles they show, and every placement is hit where its transform puts it.
#[test]
fn a_thousand_instances_are_stored_once() {
    let mesh = icosphere(5); // 20,480 triangles
    let per_mesh = mesh.triangles.len();
    let mut b = SceneBuilder::new(any_camera());
    let m = b.material(Material::default());
    let id = b.add_mesh(mesh);
    let mut centers = vec![];
    for k in 0..1000 {
        let c = Vec3::new(
            (k % 10) as f32 * 3.0,
            ((k / 10) % 10) as f32 * 3.0,
            (k / 100) as f32 * 3.0,
        );
        centers.push(c);
        b.instance(
            id,
            Affine3A::from_scale_rotation_translation(
                Vec3::splat(0.5 + (k % 3) as f32 * 0.25),
                Quat::from_rotation_y(k as f32),
                c,
            ),
            m,
        );
    }
    let scene = b.build().unwrap();
    assert_eq!(scene.counts().triangles, 1000 * per_mesh);
    let report = scene.accel_report();
    // 20 million triangles shown; the structures hold one mesh's worth and a thousand boxes.
    assert!(report.bytes < 8_000_000, "{} bytes", report.bytes);
    let mut stats = TraversalStats::default();
    for (k, c) in centers.iter().enumerate() {
        let radius = 0.5 + (k % 3) as f32 * 0.25;
        let ray = Ray::new(*c + Vec3::new(0.0, 0.0, 1.4), -Vec3::Z);
        let hit = scene
            .intersect(&ray, &mut stats)
            .expect("every placement is there");
        assert!(
            (hit.t - (1.4 - radius)).abs() < 0.02 * radius,
            "placement {k}: t = {}",
            hit.t
        );
    }
}
