//! What a hit carries besides its point: interpolated vertex normals, texture coordinates and
//! colours, image textures, the environment, and emission.

mod common;

use common::any_camera;
use glam::{Affine3A, Vec2, Vec3, Vec4};
use lucent::Rgb;
use lucent::accel::{AccelKind, Ray, TraversalStats};
use lucent::integrator::{Integrator, RayStats, Whitted};
use lucent::light::{Light, PointLight};
use lucent::material::{Material, Surface};
use lucent::sampling::sobol::Sampler;
use lucent::scene::{Scene, SceneBuilder};
use lucent::shape::Mesh;
use lucent::texture::{Filter, ImageMap, ImageTexture, Texture};

/// The triangle (0,0,0), (1,0,0), (0,1,0), facing +z, with per-vertex attributes.
fn triangle() -> Mesh {
    Mesh {
        positions: vec![Vec3::ZERO, Vec3::X, Vec3::Y],
        triangles: vec![[0, 1, 2]],
        normals: vec![
            Vec3::Z,
            Vec3::new(1.0, 0.0, 1.0).normalize(),
            Vec3::new(0.0, 1.0, 1.0).normalize(),
        ],
        uvs: vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
        ],
        colors: vec![
            Rgb::new(1.0, 0.0, 0.0),
            Rgb::new(0.0, 1.0, 0.0),
            Rgb::new(0.0, 0.0, 1.0),
        ],
        tangents: vec![
            Vec4::new(1.0, 0.0, 0.0, 1.0),
            Vec4::new(0.0, 1.0, 0.0, 1.0),
            Vec4::new(1.0, 0.0, 0.0, 1.0),
        ],
    }
}

fn scene_with(mesh: Mesh, material: Material, accel: AccelKind, transform: Affine3A) -> Scene {
    let mut b = SceneBuilder::new(any_camera());
    b.accelerator(accel);
    let m = b.material(material);
    let id = b.add_mesh(mesh);
    b.instance(id, transform, m);
    b.build().unwrap()
}

fn hit_at(scene: &Scene, x: f32, y: f32) -> lucent::shape::SurfaceHit {
    let ray = Ray::new(Vec3::new(x, y, 5.0), -Vec3::Z);
    scene
        .intersect(&ray, &mut TraversalStats::default())
        .unwrap()
}

#[test]
fn vertex_attributes_are_interpolated_with_the_barycentric_weights() {
    // Both the scalar leaf test (bvh) and the packed SIMD one (wide) give the same weights.
    for accel in [AccelKind::Bvh, AccelKind::Wide] {
        let scene = scene_with(
            triangle(),
            Material::diffuse(Rgb::WHITE),
            accel,
            Affine3A::IDENTITY,
        );
        // At (0.25, 0.5): weights 0.25 for A, 0.25 for B, 0.5 for C.
        let hit = hit_at(&scene, 0.25, 0.5);
        let n = triangle().normals;
        let want = (0.25 * n[0] + 0.25 * n[1] + 0.5 * n[2]).normalize();
        assert!(
            (hit.shading_normal - want).length() < 1e-5,
            "{:?}",
            hit.shading_normal
        );
        assert_eq!(hit.normal, Vec3::Z, "the geometric normal stays the face's");
        assert!((hit.uv() - Vec2::new(0.25, 0.5)).length() < 1e-6);
        let c = hit.color;
        assert!((c.r - 0.25).abs() < 1e-6 && (c.g - 0.25).abs() < 1e-6 && (c.b - 0.5).abs() < 1e-6);
    }
}

#[test]
fn shading_normals_follow_the_instance_transform() {
    let rotate = Affine3A::from_rotation_y(std::f32::consts::FRAC_PI_2);
    let scene = scene_with(
        triangle(),
        Material::diffuse(Rgb::WHITE),
        AccelKind::Wide,
        rotate,
    );
    // The triangle now lies in the plane x = 0, facing +x: local (x, y, z) is world (z, y, −x).
    // World (0, 0.1, −0.5) is local (0.5, 0.1, 0): weights 0.4, 0.5, 0.1.
    let ray = Ray::new(Vec3::new(5.0, 0.1, -0.5), -Vec3::X);
    let hit = scene
        .intersect(&ray, &mut TraversalStats::default())
        .unwrap();
    assert!((hit.normal - Vec3::X).length() < 1e-6);
    let n = triangle().normals;
    let local = (0.4 * n[0] + 0.5 * n[1] + 0.1 * n[2]).normalize();
    let want = rotate.transform_vector3(local);
    assert!(
        (hit.shading_normal - want).length() < 1e-5,
        "{:?} vs {want:?}",
        hit.shading_normal
    );
}

/// A flat-normal-mapped white Lambertian: a material that needs the surface's tangents.
fn normal_mapped() -> Material {
    Material {
        surface: Surface::NormalMap {
            normals: Texture::Solid(Rgb::new(0.5, 0.5, 1.0)),
            strength: 1.0,
            inner: Box::new(Surface::Diffuse {
                reflectance: Texture::Solid(Rgb::WHITE),
            }),
        },
        ..Material::diffuse(Rgb::WHITE)
    }
}

#[test]
fn mesh_tangents_are_interpolated_and_a_mirror_turns_their_handedness() {
    let scene = scene_with(
        triangle(),
        normal_mapped(),
        AccelKind::Wide,
        Affine3A::IDENTITY,
    );
    // Weights 0.25, 0.25, 0.5: 0.75 of +x, 0.25 of +y.
    let t = hit_at(&scene, 0.25, 0.5).tangent.unwrap();
    assert!((t - Vec4::new(0.75, 0.25, 0.0, 1.0)).length() < 1e-5, "{t}");
    // Mirrored in x (and seen from the same side): the tangent mirrors, the handedness turns.
    let mirror = Affine3A::from_scale(Vec3::new(-1.0, 1.0, 1.0));
    let scene = scene_with(triangle(), normal_mapped(), AccelKind::Wide, mirror);
    let t = hit_at(&scene, -0.25, 0.5).tangent.unwrap();
    assert!(
        (t - Vec4::new(-0.75, 0.25, 0.0, -1.0)).length() < 1e-5,
        "{t}"
    );
    let mut flat = triangle();
    flat.tangents.clear();
    let scene = scene_with(flat, normal_mapped(), AccelKind::Wide, Affine3A::IDENTITY);
    assert_eq!(hit_at(&scene, 0.25, 0.5).tangent, None);
    // A material whose frame does not matter (isotropic, untextured) skips the tangents.
    let scene = scene_with(
        triangle(),
        Material::diffuse(Rgb::WHITE),
        AccelKind::Wide,
        Affine3A::IDENTITY,
    );
    let hit = hit_at(&scene, 0.25, 0.5);
    assert_eq!(
        (hit.tangent, hit.dpdu, hit.dpdv),
        (None, Vec3::ZERO, Vec3::ZERO)
    );
}

#[test]
fn reversed_vertex_normals_turn_to_the_face_and_missing_ones_give_the_face() {
    let mut mesh = triangle();
    mesh.normals = vec![-Vec3::Z; 3];
    let scene = scene_with(
        mesh,
        Material::diffuse(Rgb::WHITE),
        AccelKind::Wide,
        Affine3A::IDENTITY,
    );
    assert_eq!(hit_at(&scene, 0.2, 0.2).shading_normal, Vec3::Z);
    let flat = Mesh::new(triangle().positions, triangle().triangles);
    let scene = scene_with(
        flat,
        Material::diffuse(Rgb::WHITE),
        AccelKind::Wide,
        Affine3A::IDENTITY,
    );
    let hit = hit_at(&scene, 0.2, 0.2);
    assert_eq!((hit.shading_normal, hit.color), (Vec3::Z, Rgb::WHITE));
}

#[test]
fn image_textures_are_looked_up_at_the_uvs_and_tinted_by_vertex_colours() {
    // A 2×1 image: left texel red, right texel blue.
    let image =
        ImageTexture::new(2, 1, vec![Rgb::new(1.0, 0.0, 0.0), Rgb::new(0.0, 0.0, 1.0)]).unwrap();
    let mut mesh = triangle();
    mesh.colors.clear();
    let mut b = SceneBuilder::new(any_camera());
    let img = b.image(image);
    // Bilinear: the lookup at a point (the classic integrators filter over the camera's pixel
    // footprint, and these rays are not the camera's).
    let m = b.material(Material {
        kd: Texture::Image(ImageMap {
            filter: Filter::Bilinear,
            ..ImageMap::new(img)
        }),
        ..Material::default()
    });
    b.mesh(mesh, m);
    let scene = b.build().unwrap();
    let raycast = |x: f32, y: f32| {
        let ray = Ray::new(Vec3::new(x, y, 5.0), -Vec3::Z);
        Integrator::Raycast.radiance(
            &scene,
            &ray,
            &mut Sampler::new(0, 0, 0),
            &mut RayStats::default(),
        )
    };
    // u = x here: u = 0.25 is the red texel's centre, u = 0.75 the blue one's.
    assert_eq!(raycast(0.25, 0.1), Rgb::new(1.0, 0.0, 0.0));
    assert_eq!(raycast(0.75, 0.1), Rgb::new(0.0, 0.0, 1.0));
    // A material naming an image that does not exist is refused.
    let mut b = SceneBuilder::new(any_camera());
    b.material(Material {
        kd: Texture::Image(ImageMap::new(3)),
        ..Material::default()
    });
    assert!(b.build().unwrap_err().to_string().contains("image 3"));
}

#[test]
fn spheres_are_textured_at_their_lat_long_coordinates() {
    // A 2×1 image: u < 0.5 red, u ≥ 0.5 blue. Lat-long u = 0.5 + atan2(x, −z) / 2π: the
    // sphere's −x side has u = 0.25, its +x side u = 0.75 (worked out only when looked up).
    let image =
        ImageTexture::new(2, 1, vec![Rgb::new(1.0, 0.0, 0.0), Rgb::new(0.0, 0.0, 1.0)]).unwrap();
    let mut b = SceneBuilder::new(any_camera());
    let img = b.image(image);
    // Bilinear: the lookup at a point (the classic integrators filter over the camera's pixel
    // footprint, and these rays are not the camera's).
    let m = b.material(Material {
        kd: Texture::Image(ImageMap {
            filter: Filter::Bilinear,
            ..ImageMap::new(img)
        }),
        ..Material::default()
    });
    b.sphere(
        lucent::shape::Sphere {
            center: Vec3::ZERO,
            radius: 1.0,
        },
        m,
    );
    let scene = b.build().unwrap();
    let look = |from: Vec3| {
        let ray = Ray::new(from, -from.normalize());
        let hit = scene
            .intersect(&ray, &mut TraversalStats::default())
            .unwrap();
        let colour = Integrator::Raycast.radiance(
            &scene,
            &ray,
            &mut Sampler::new(0, 0, 0),
            &mut RayStats::default(),
        );
        (hit.uv(), colour)
    };
    let (uv, colour) = look(Vec3::new(-5.0, 0.0, 0.0));
    assert!((uv - Vec2::new(0.25, 0.5)).length() < 1e-6, "{uv}");
    assert_eq!(colour, Rgb::new(1.0, 0.0, 0.0));
    let (uv, colour) = look(Vec3::new(5.0, 0.0, 0.0));
    assert!((uv - Vec2::new(0.75, 0.5)).length() < 1e-6, "{uv}");
    assert_eq!(colour, Rgb::new(0.0, 0.0, 1.0));
}

#[test]
fn rays_that_miss_see_the_environment_image() {
    // Top half white, bottom half dark: a sky over a ground.
    let mut texels = vec![Rgb::WHITE; 4 * 2];
    for t in &mut texels[4..] {
        *t = Rgb::gray(0.1);
    }
    let mut b = SceneBuilder::new(any_camera());
    let sky = b.image(ImageTexture::new(4, 2, texels).unwrap());
    b.environment(Some(sky)).background(Rgb::new(1.0, 0.0, 1.0));
    let scene = b.build().unwrap();
    let whitted = Integrator::Whitted(Whitted::default());
    let look = |d: Vec3| {
        whitted.radiance(
            &scene,
            &Ray::new(Vec3::ZERO, d),
            &mut Sampler::new(0, 0, 0),
            &mut RayStats::default(),
        )
    };
    assert_eq!(look(Vec3::Y), Rgb::WHITE);
    assert_eq!(look(-Vec3::Y), Rgb::gray(0.1));
}

#[test]
fn emission_is_seen_from_the_front_only() {
    let glow = Material {
        ke: Rgb::new(2.0, 1.0, 0.5),
        ..Material::default()
    };
    let mut b = SceneBuilder::new(any_camera());
    let m = b.material(glow);
    b.mesh(Mesh::new(triangle().positions, triangle().triangles), m);
    b.light(Light::Point(PointLight {
        position: Vec3::new(0.2, 0.2, 3.0),
        intensity: Rgb::WHITE,
        falloff: Default::default(),
    }));
    let scene = b.build().unwrap();
    let whitted = Integrator::Whitted(Whitted::default());
    let front = Ray::new(Vec3::new(0.2, 0.2, 5.0), -Vec3::Z);
    let back = Ray::new(Vec3::new(0.2, 0.2, -5.0), Vec3::Z);
    assert_eq!(
        whitted.radiance(
            &scene,
            &front,
            &mut Sampler::new(0, 0, 0),
            &mut RayStats::default()
        ),
        Rgb::new(2.0, 1.0, 0.5)
    );
    assert_eq!(
        whitted.radiance(
            &scene,
            &back,
            &mut Sampler::new(0, 0, 0),
            &mut RayStats::default()
        ),
        Rgb::BLACK
    );
}

#[test]
fn a_merged_placement_has_the_normals_of_a_placement_kept_apart() {
    // A 10×10 grid of 200 slightly bent triangles, without vertex normals: placed once it is
    // merged into world space (its normals computed at build), placed twice it is not (its
    // normals computed at each hit). Rotated, scaled and mirrored, the normals agree bit for
    // bit (the points differ by rounding: one is found in world space, the other in the
    // object's).
    let n = 10;
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f32 / n as f32, j as f32 / n as f32);
            positions.push(Vec3::new(x, y, 0.05 * (7.0 * x).sin() * (5.0 * y).cos()));
        }
    }
    let mut triangles = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let k = (j * (n + 1) + i) as u32;
            let row = n as u32 + 1;
            triangles.push([k, k + 1, k + row + 1]);
            triangles.push([k, k + row + 1, k + row]);
        }
    }
    let grid = Mesh::new(positions, triangles);
    let place = Affine3A::from_scale_rotation_translation(
        Vec3::new(-2.0, 1.5, 1.0),
        glam::Quat::from_axis_angle(Vec3::new(0.3, 0.2, 1.0).normalize(), 0.7),
        Vec3::new(0.2, -0.4, 0.0),
    );
    let far = Affine3A::from_translation(Vec3::new(50.0, 0.0, 0.0));
    let build = |twice: bool| {
        let mut b = SceneBuilder::new(any_camera());
        let m = b.material(Material::lambertian(Rgb::gray(0.5)));
        let id = b.add_mesh(grid.clone());
        b.instance(id, place, m);
        if twice {
            b.instance(id, far, m);
        }
        b.build().unwrap()
    };
    let (merged, apart) = (build(false), build(true));
    let mut hits = 0;
    for i in 0..40 {
        for j in 0..40 {
            let (x, y) = (-2.5 + i as f32 * 0.1, -1.0 + j as f32 * 0.1);
            let ray = Ray::new(
                Vec3::new(x, y, 5.0),
                Vec3::new(0.05, 0.02, -1.0).normalize(),
            );
            let mut stats = TraversalStats::default();
            let (a, b) = (
                merged.intersect(&ray, &mut stats),
                apart.intersect(&ray, &mut stats),
            );
            assert_eq!(
                a.map(|h| (h.normal, h.shading_normal)),
                b.map(|h| (h.normal, h.shading_normal))
            );
            hits += usize::from(a.is_some());
        }
    }
    assert!(hits > 200, "{hits} hits");
}
