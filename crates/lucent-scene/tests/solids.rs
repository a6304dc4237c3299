//! The exact solids from scene files: where rays meet them, that every ray entering one leaves
//! it, and the errors for bad tables.

use glam::Vec3;
use lucent::accel::{Ray, TraversalStats};
use lucent::render::{Hooks, render};
use lucent::scene::Scene;
use lucent::spawn::spawn_ray;
use lucent_scene::SceneFile;
use std::path::PathBuf;

const HEAD: &str =
    "[camera]\neye = [0, 0, 9]\nlook_at = [0, 0, 0]\n[[material]]\nname = \"m\"\nkd = 0.5\n";

fn scene(objects: &str) -> Scene {
    let text = format!("{HEAD}{objects}");
    let file = SceneFile::parse(PathBuf::from("solids.toml"), PathBuf::new(), text).unwrap();
    file.build().unwrap().scene
}

/// Each case's objects refused with an error that starts at its place and names its cause.
fn assert_refused(cases: &[(&str, &str, &str)]) {
    for &(objects, place, cause) in cases {
        let e = error(objects);
        assert!(
            e.starts_with(place) && e.contains(cause),
            "{e}\nwanted {place} … {cause}"
        );
    }
}

fn error(objects: &str) -> String {
    let text = format!("{HEAD}{objects}");
    let file = SceneFile::parse(PathBuf::from("bad.toml"), PathBuf::new(), text).unwrap();
    file.build().map(|_| ()).expect_err("refused").to_string()
}

#[test]
fn a_cylinder_is_hit_where_its_ends_and_radius_put_it() {
    let s = scene(
        "[[object]]\ntype = \"cylinder\"\nbase = [0, 0, 0]\ncap = [0, 2, 0]\nradius = 0.5\nmaterial = \"m\"\n",
    );
    let hit = s
        .intersect(
            &Ray::new(Vec3::new(-3.0, 1.0, 0.3), Vec3::X),
            &mut TraversalStats::default(),
        )
        .unwrap();
    // x² = 0.25 − 0.09 on the side: x = −0.4.
    assert!((hit.t - 2.6).abs() < 1e-6, "{}", hit.t);
    assert!((hit.normal - Vec3::new(-0.8, 0.0, 0.6)).length() < 1e-6);
    assert!((hit.point - Vec3::new(-0.4, 1.0, 0.3)).length() < 1e-6);
    assert_eq!(s.counts().solids, 1);
}

#[test]
fn a_torus_lies_about_y_scaled_by_its_radii_and_placed() {
    let s = scene(
        "[[object]]\ntype = \"torus\"\nmajor = 2\nminor = 0.5\ntranslate = [1, 0, 0]\nmaterial = \"m\"\n",
    );
    let mut stats = TraversalStats::default();
    // Down onto the top of the tube at x = 3: its top is at y = 0.5.
    let hit = s
        .intersect(&Ray::new(Vec3::new(3.0, 5.0, 0.0), Vec3::NEG_Y), &mut stats)
        .unwrap();
    assert!((hit.t - 4.5).abs() < 1e-6 && (hit.normal - Vec3::Y).length() < 1e-6);
    // Through the hole: nothing.
    assert!(
        s.intersect(&Ray::new(Vec3::new(1.0, 5.0, 0.0), Vec3::NEG_Y), &mut stats)
            .is_none()
    );
}

#[test]
fn a_cone_box_and_disc_are_hit_at_their_known_distances() {
    let s = scene(
        "[[object]]\ntype = \"cone\"\nbase = [0, 0, 0]\ncap = [0, 1, 0]\nbase_radius = 1\ncap_radius = 0\nmaterial = \"m\"\n\
         [[object]]\ntype = \"box\"\nmin = [4, 0, 0]\nmax = [5, 1, 2]\nmaterial = \"m\"\n\
         [[object]]\ntype = \"disc\"\ncenter = [-4, 0, 0]\nnormal = [0, 0, 1]\nradius = 1\nhole = 0.5\nmaterial = \"m\"\n",
    );
    let mut stats = TraversalStats::default();
    let mut t = |o: Vec3, d: Vec3| s.intersect(&Ray::new(o, d), &mut stats).map(|h| h.t);
    // The cone's radius at y = 0.5 is 0.5.
    assert!((t(Vec3::new(-3.0, 0.5, 0.0), Vec3::X).unwrap() - 2.5).abs() < 1e-6);
    assert!((t(Vec3::new(4.5, 0.5, 9.0), Vec3::NEG_Z).unwrap() - 7.0).abs() < 1e-6);
    assert!((t(Vec3::new(-4.7, 0.0, 3.0), Vec3::NEG_Z).unwrap() - 3.0).abs() < 1e-6);
    assert_eq!(
        t(Vec3::new(-4.2, 0.0, 3.0), Vec3::NEG_Z),
        None,
        "through the hole"
    );
}

#[test]
fn a_superellipsoid_of_exponents_2_is_the_octahedron_placed() {
    let s = scene(
        "[[object]]\ntype = \"superellipsoid\"\nexponents = [2, 2]\nscale = 2\ntranslate = [0, 1, 0]\nmaterial = \"m\"\n",
    );
    // |x| + |y − 1| + |z| = 2 (scaled by 2): down the y axis at x = 0.5, z = 0.5 the top face
    // is at y = 2.
    let ray = Ray::new(Vec3::new(0.5, 5.0, 0.5), Vec3::NEG_Y);
    let hit = s.intersect(&ray, &mut TraversalStats::default()).unwrap();
    assert!((hit.t - 3.0).abs() < 1e-5, "{}", hit.t);
    assert!(
        (hit.normal - Vec3::ONE.normalize()).length() < 1e-5,
        "{}",
        hit.normal
    );
}

/// Follows `ray` through the scene, crossing every surface straight on, and counts the
/// crossings until it escapes.
fn crossings(s: &Scene, mut ray: Ray) -> u32 {
    let mut stats = TraversalStats::default();
    let mut from = None;
    let mut n = 0;
    while let Some(hit) = s.intersect_from(&ray, from, &mut stats) {
        n += 1;
        assert!(n < 100, "stuck at {:?}", hit.point);
        let (next, leaving) = spawn_ray(&hit, ray.dir);
        ray = next;
        from = Some(leaving);
    }
    n
}

#[test]
fn every_ray_that_enters_a_closed_solid_leaves_it() {
    // Placed, turned and scaled unevenly; rays from all around through their middles and near
    // their edges.
    let s = scene(
        "[[object]]\ntype = \"torus\"\nmajor = 1.5\nminor = 0.4\nrotate = [30, 20, 10]\nscale = [1, 1.3, 0.8]\nmaterial = \"m\"\n\
         [[object]]\ntype = \"cylinder\"\nbase = [3, -1, 0]\ncap = [3.5, 1, 0.2]\nradius = 0.6\nmaterial = \"m\"\n\
         [[object]]\ntype = \"cone\"\nbase = [-3, -1, 0]\ncap = [-3, 1, 0.5]\nbase_radius = 0.8\ncap_radius = 0.2\nmaterial = \"m\"\n\
         [[object]]\ntype = \"box\"\nmin = [-1, 2, -1]\nmax = [1, 3, 1]\nrotate = [10, 40, 0]\nmaterial = \"m\"\n\
         [[object]]\ntype = \"superellipsoid\"\nexponents = [0.3, 1.7]\nscale = [0.8, 0.5, 0.6]\nrotate = [0, 30, 20]\ntranslate = [3, 2.5, 0]\nmaterial = \"m\"\n\
         [[object]]\ntype = \"difference\"\nmaterial = \"m\"\nrotate = [20, 0, 30]\ntranslate = [0, -1.2, 0]\nchildren = [\
           { type = \"merge\", children = [{ type = \"sphere\", center = [0, 0, 0], radius = 0.8 }, { type = \"box\", min = [0, -0.5, -0.5], max = [1.2, 0.5, 0.5] }] },\
           { type = \"cylinder\", base = [0, 0, -2], cap = [0, 0, 2], radius = 0.3 },\
           { type = \"torus\", major = 0.8, minor = 0.2, inverse = true, scale = 0.5 }]\n",
    );
    assert_eq!(s.counts().csgs, 1);
    let mut odd = 0;
    let mut hits = 0;
    let mut state = 12345u64;
    let mut rand = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 40) as f32 / (1u64 << 24) as f32
    };
    for _ in 0..20_000 {
        let dir = Vec3::new(rand() - 0.5, rand() - 0.5, rand() - 0.5).normalize_or(Vec3::X);
        let target = Vec3::new(rand() * 9.0 - 4.5, rand() * 5.0 - 1.5, rand() * 3.0 - 1.5);
        let n = crossings(&s, Ray::new(target - dir * 20.0, dir));
        hits += u32::from(n > 0);
        odd += n % 2;
    }
    assert!(
        hits > 4000,
        "{hits} rays hit: the test must reach the solids"
    );
    assert_eq!(odd, 0, "rays that entered and never left");
}

#[test]
fn a_bored_box_is_hit_on_its_faces_and_walls_in_their_materials() {
    let s = scene(
        "[[material]]\nname = \"wall\"\nkd = 0.2\n\
         [[object]]\ntype = \"difference\"\nmaterial = \"m\"\ntranslate = [0, 1, 0]\nchildren = [\
           { type = \"box\", min = [-1, -1, -1], max = [1, 1, 1] },\
           { type = \"cylinder\", base = [0, 0, -2], cap = [0, 0, 2], radius = 0.5, material = \"wall\" }]\n",
    );
    let mut stats = TraversalStats::default();
    let mut hit = |o: Vec3, d: Vec3| s.intersect(&Ray::new(o, d), &mut stats);
    assert!(
        hit(Vec3::new(0.1, 1.0, 5.0), Vec3::NEG_Z).is_none(),
        "down the bore"
    );
    let face = hit(Vec3::new(0.7, 1.0, 5.0), Vec3::NEG_Z).unwrap();
    assert!((face.t - 4.0).abs() < 1e-6 && (face.normal - Vec3::Z).length() < 1e-6);
    assert_eq!(face.material, 0);
    // From inside the bore, across it: the wall at x = 0.5, facing into the bore.
    let wall = hit(Vec3::new(0.0, 1.0, 0.0), Vec3::X).unwrap();
    assert!((wall.t - 0.5).abs() < 1e-6 && (wall.normal + Vec3::X).length() < 1e-6);
    assert_eq!(wall.material, 1, "the cylinder's own material");
}

#[test]
fn bad_combinations_are_refused_at_their_keys() {
    let cases = [
        (
            "[[object]]\ntype = \"union\"\nmaterial = \"m\"\nchildren = [{ type = \"box\", min = [0, 0, 0], max = [1, 1, 1] }]\n",
            "bad.toml:10:12:",
            "a union needs at least two `children`, got 1",
        ),
        (
            "[[object]]\ntype = \"merge\"\nmaterial = \"m\"\n",
            "bad.toml:7:1:",
            "a merge needs `children`",
        ),
        (
            "[[object]]\ntype = \"union\"\nmaterial = \"m\"\nchildren = [{ type = \"mesh\", file = \"a.obj\" }, { type = \"sphere\", center = [0, 0, 0], radius = 1 }]\n",
            "bad.toml:10:13:",
            "a mesh cannot be part of a combination",
        ),
        (
            "[[object]]\ntype = \"union\"\nmaterial = \"m\"\nchildren = [{ type = \"disc\", center = [0, 0, 0], normal = [0, 1, 0], radius = 1 }, { type = \"sphere\", center = [0, 0, 0], radius = 1 }]\n",
            "bad.toml:10:13:",
            "a disc bounds no volume",
        ),
        (
            "[[object]]\ntype = \"union\"\nmaterial = \"m\"\nchildren = [{ type = \"sphere\", center = [0, 0, 0], radius = 1, material = \"nope\" }, { type = \"sphere\", center = [1, 0, 0], radius = 1 }]\n",
            "bad.toml:10:75:",
            "unknown material `nope`",
        ),
        (
            "[[object]]\ntype = \"union\"\nmaterial = \"m\"\nchildren = [{ type = \"sphere\", center = [0, 0, 0], radius = 1, uv_axes = [[1, 0, 0], [0, 1, 0], [0, 0, 1]] }, { type = \"sphere\", center = [1, 0, 0], radius = 1, scale = 2 }]\n",
            "bad.toml:10:",
            "does not apply to a sphere",
        ),
        (
            "[[object]]\ntype = \"intersection\"\nmaterial = \"m\"\ninverse = true\nchildren = [{ type = \"sphere\", center = [0, 0, 0], radius = 1 }, { type = \"sphere\", center = [1, 0, 0], radius = 1 }]\n",
            "bad.toml:7:1:",
            "`inverse` does not apply to an intersection",
        ),
        (
            "[[object]]\ntype = \"union\"\nmaterial = \"m\"\nchildren = [{ type = \"sphere\", center = [0, 0, 0], radius = 1, inverse = true }, { type = \"sphere\", center = [1, 0, 0], radius = 1 }]\n",
            "bad.toml:7:1:",
            "unbounded",
        ),
        (
            "[[object]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\n",
            "bad.toml:7:1:",
            "a box needs `material`",
        ),
    ];
    assert_refused(&cases);
}

#[test]
fn bad_solids_are_refused_at_their_keys() {
    let cases = [
        (
            "[[object]]\ntype = \"cylinder\"\nbase = [0, 0, 0]\ncap = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n",
            "bad.toml:10:7:",
            "`cap` must differ from its `base`",
        ),
        (
            "[[object]]\ntype = \"cone\"\nbase = [0, 0, 0]\ncap = [0, 1, 0]\nbase_radius = 0\ncap_radius = 0\nmaterial = \"m\"\n",
            "bad.toml:12:14:",
            "radii cannot both be 0",
        ),
        (
            "[[object]]\ntype = \"disc\"\ncenter = [0, 0, 0]\nnormal = [0, 1, 0]\nradius = 1\nhole = 1\nmaterial = \"m\"\n",
            "bad.toml:12:8:",
            "`hole` must be at least 0 and below its radius",
        ),
        (
            "[[object]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [1, 0, 1]\nmaterial = \"m\"\n",
            "bad.toml:10:7:",
            "`max` must be above its `min` on every axis",
        ),
        (
            "[[object]]\ntype = \"torus\"\nmajor = 1\nmaterial = \"m\"\n",
            "bad.toml:7:1:",
            "a torus needs `minor`",
        ),
        (
            "[[object]]\ntype = \"torus\"\nmajor = 1\nminor = -0.5\nmaterial = \"m\"\n",
            "bad.toml:10:9:",
            "`minor` must be between",
        ),
        (
            "[[object]]\ntype = \"superellipsoid\"\nexponents = [0, 1]\nmaterial = \"m\"\n",
            "bad.toml:9:13:",
            "`exponents` must each be from 0.01 to 10",
        ),
        (
            "[[object]]\ntype = \"torus\"\nmajor = 1\nminor = 0.5\nradius = 2\nmaterial = \"m\"\n",
            "bad.toml:11:10:",
            "`radius` does not apply to a torus",
        ),
        (
            "[[object]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\nmaterial = \"m\"\nmotion = { oscillate = { offset = [0, 0.5, 0], period = 2 } }\n",
            "bad.toml:12:10:",
            "a box cannot move yet",
        ),
        (
            "[[material]]\nname = \"lamp\"\ntype = \"diffuse\"\nemission = 5\n[[object]]\ntype = \"cylinder\"\nbase = [0, 0, 0]\ncap = [0, 1, 0]\nradius = 1\nmaterial = \"lamp\"\n",
            "bad.toml:16:12:",
            "a cylinder cannot be an area light yet",
        ),
    ];
    assert_refused(&cases);
}

/// The scene's image, as linear pixels.
fn image(text: &str) -> Vec<[f32; 3]> {
    let file = SceneFile::parse(PathBuf::from("box.toml"), PathBuf::new(), text.to_string());
    let loaded = file.unwrap().build().unwrap();
    let film = render(&loaded.scene, &loaded.settings, None, &Hooks::none())
        .unwrap()
        .film;
    let (w, h) = (film.width(), film.height());
    (0..h)
        .flat_map(|y| (0..w).map(move |x| (x, y)))
        .map(|(x, y)| film.pixel(x, y).to_array())
        .collect()
}

#[test]
fn the_exact_box_renders_as_the_triangle_cube_does() {
    // The same box, turned and scaled, once as the triangles of `cube` and once as the exact
    // solid, under a point light and an area light, by Whitted and by the path tracer: the
    // same surface, so the same image but for rounding at its edges.
    for integrator in ["whitted", "path"] {
        let scene = |object: &str| {
            format!(
                "[image]\nwidth = 48\nheight = 36\nsamples = 16\n\
                 [render]\nintegrator = \"{integrator}\"\n\
                 [camera]\neye = [3, 4, 6]\nlook_at = [0, 0.5, 0]\nfov = 40\n\
                 [world]\nbackground = 0.2\nambient = 0.1\n\
                 [[material]]\nname = \"m\"\ntype = \"diffuse\"\nreflectance = [0.7, 0.5, 0.3]\n\
                 [[material]]\nname = \"lamp\"\ntype = \"diffuse\"\nreflectance = 0\nemission = 4\n\
                 [[light]]\ntype = \"point\"\nposition = [-3, 5, 2]\nintensity = 20\n\
                 [[object]]\ntype = \"sphere\"\ncenter = [2, 4, -2]\nradius = 0.5\nmaterial = \"lamp\"\n\
                 [[object]]\ntype = \"plane\"\npoint = [0, -1, 0]\nnormal = [0, 1, 0]\nmaterial = \"m\"\n\
                 [[object]]\n{object}\nscale = [1.2, 0.8, 0.6]\nrotate = [0, 30, 10]\nmaterial = \"m\"\n"
            )
        };
        let cube = image(&scene("type = \"cube\""));
        let exact = image(&scene(
            "type = \"box\"\nmin = [-1, -1, -1]\nmax = [1, 1, 1]",
        ));
        if integrator == "whitted" {
            // Pixels along the silhouette may take a sample differently; nothing else may.
            let differ = cube
                .iter()
                .zip(&exact)
                .filter(|(a, b)| (0..3).any(|c| (a[c] - b[c]).abs() > 1e-3 * (1.0 + a[c])))
                .count();
            assert!(differ <= 12, "{differ} of {} pixels differ", cube.len());
        } else {
            // The faces' tangents differ (the mesh's from its uvs, the box's from its own
            // frame), so the same random numbers sample other directions: the same image in
            // expectation, compared per 8×8 block.
            let worst = worst_block(&cube, &exact, 48);
            assert!(worst < 0.03, "the worst 8×8 block differs by {worst}");
        }
        let box_pixels = cube.iter().filter(|p| p[0] > 0.0 && p[0] != p[2]).count();
        assert!(box_pixels > 200, "the box must fill part of the image");
    }
}

/// The largest relative difference of two images' 8×8 block means (width `w`), per channel.
fn worst_block(a: &[[f32; 3]], b: &[[f32; 3]], w: usize) -> f32 {
    let h = a.len() / w;
    let mut worst = 0.0f32;
    for by in 0..h / 8 {
        for bx in 0..w / 8 {
            for c in 0..3 {
                let sum = |img: &[[f32; 3]]| {
                    (0..64)
                        .map(|i| img[(by * 8 + i / 8) * w + bx * 8 + i % 8][c])
                        .sum::<f32>()
                };
                let (x, y) = (sum(a), sum(b));
                worst = worst.max((x - y).abs() / x.abs().max(y.abs()).max(1e-3));
            }
        }
    }
    worst
}

#[test]
fn an_algebraic_paraboloid_cut_to_a_box_is_hit_where_its_equation_says() {
    // y = x² + z² (x² + z² − y = 0), cut to y ≤ 4, moved up by 1.
    let s = scene(
        "[[object]]\ntype = \"algebraic\"\nterms = [[1, 2, 0, 0], [1, 0, 0, 2], [-1, 0, 1, 0]]\nbounds = [[-2, 0, -2], [2, 4, 2]]\ntranslate = [0, 1, 0]\nmaterial = \"m\"\n",
    );
    // Down at x = 1: the bowl at y = 1 + 1 = 2, its normal (−2x, 1, −2z) normalised, up and
    // out.
    let ray = Ray::new(Vec3::new(1.0, 8.0, 0.0), Vec3::NEG_Y);
    let hit = s.intersect(&ray, &mut TraversalStats::default()).unwrap();
    assert!((hit.t - 6.0).abs() < 1e-5, "{}", hit.t);
    let n = Vec3::new(2.0, -1.0, 0.0).normalize();
    assert!((hit.normal - n).length() < 1e-5, "{}", hit.normal);
    // Beyond the box (x = 2.5) nothing, though the surface goes on.
    let beside = Ray::new(Vec3::new(2.5, 20.0, 0.0), Vec3::NEG_Y);
    assert!(
        s.intersect(&beside, &mut TraversalStats::default())
            .is_none()
    );
}

#[test]
fn a_plane_cuts_a_ball_in_a_combination() {
    let s = scene(
        "[[object]]\ntype = \"intersection\"\nmaterial = \"m\"\nchildren = [\n  { type = \"sphere\", center = [0, 0, 0], radius = 1 },\n  { type = \"plane\", point = [0, 0.5, 0], normal = [0, 1, 0] },\n]\n",
    );
    // From above: the flat cut at y = 0.5; from the side at y = 0.75, nothing.
    let down = Ray::new(Vec3::new(0.2, 5.0, 0.0), Vec3::NEG_Y);
    let hit = s.intersect(&down, &mut TraversalStats::default()).unwrap();
    assert!((hit.t - 4.5).abs() < 1e-5 && (hit.normal - Vec3::Y).length() < 1e-5);
    let side = Ray::new(Vec3::new(-5.0, 0.75, 0.0), Vec3::X);
    assert!(s.intersect(&side, &mut TraversalStats::default()).is_none());
}

#[test]
fn bad_algebraic_surfaces_are_refused_at_their_keys() {
    let head = "[[object]]\ntype = \"algebraic\"\nmaterial = \"m\"\n";
    let cases = [
        (
            format!("{head}terms = [[1, 2, 0, 0], [1, 0, 2, 0]]\n"),
            "bad.toml:7:1",
            "needs `bounds`",
        ),
        (
            format!("{head}terms = [[1, 5, 0, 0]]\nbounds = [[-1, -1, -1], [1, 1, 1]]\n"),
            "bad.toml:10:9",
            "whole powers from 0 to 4",
        ),
        (
            format!("{head}terms = [[1, 2, 2, 1]]\nbounds = [[-1, -1, -1], [1, 1, 1]]\n"),
            "bad.toml:10:9",
            "adding up to at most 4",
        ),
        (
            format!("{head}terms = [[3, 0, 0, 0]]\nbounds = [[-1, -1, -1], [1, 1, 1]]\n"),
            "bad.toml:10:9",
            "degree 1 or more",
        ),
        (
            format!("{head}terms = [[1, 1, 0, 0]]\nbounds = [[1, -1, -1], [1, 1, 1]]\n"),
            "bad.toml:11:10",
            "max above min",
        ),
    ];
    for (objects, place, cause) in &cases {
        let e = error(objects);
        assert!(
            e.starts_with(place) && e.contains(cause),
            "{e}\nwanted {place} … {cause}"
        );
    }
}
