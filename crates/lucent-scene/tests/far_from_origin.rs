//! The same scene moved far from the origin, or scaled down or up, renders as it does at the
//! origin (issue 26, class 6): a unit sphere on a floor under a point light, by the Whitted
//! integrator, whose hard shadow shows any secondary ray that starts in the wrong place.
//!
//! Before ray origins were offset in proportion to the hit's own error bound (`spawn.rs`), the
//! floor's shadow vanished at an offset of 1e5 (190 of 4,096 pixels more than 10% off: shadow
//! rays started 2 units up, over the sphere) and a scene scaled to 1e-6 had 145 such pixels (a
//! fixed offset near the origin larger than the scene); the path tracer's worst 8 × 8 block at
//! 1e5 was 73% off (a halo of leaked light), 2.8% then. A unit sphere at 1e7 is two ulps of
//! a single-precision coordinate wide: since scenes are built relative to a point near their
//! camera (`scene_origin`), from positions read in double precision, every offset renders as
//! the origin does (at 1e5, 41 pixels were off before that, none now; path 0.02%).

use lucent::render::{Hooks, render};
use lucent_scene::SceneFile;
use std::path::PathBuf;

/// The scene moved by `offset` on every axis and scaled by `scale` about the origin (the
/// camera, the light's position and, under quadratic falloff, its intensity with it), rendered
/// by `integrator` with `samples` per pixel.
fn scene(offset: f64, scale: f64, integrator: &str, samples: u32) -> String {
    let v = |x: f64, y: f64, z: f64| {
        format!(
            "[{}, {}, {}]",
            x * scale + offset,
            y * scale + offset,
            z * scale + offset
        )
    };
    format!(
        "[image]\nwidth = 64\nheight = 64\nsamples = {samples}\n\
         [render]\nintegrator = \"{integrator}\"\n\
         [camera]\neye = {}\nlook_at = {}\n\
         [[material]]\nname = \"m\"\ntype = \"diffuse\"\nreflectance = 0.7\n\
         [[object]]\ntype = \"sphere\"\ncenter = {}\nradius = {}\nmaterial = \"m\"\n\
         [[object]]\ntype = \"rectangle\"\nscale = {}\nrotate = [-90, 0, 0]\ntranslate = {}\nmaterial = \"m\"\n\
         [[light]]\ntype = \"point\"\nposition = {}\nintensity = {}\nfalloff = \"quadratic\"\n",
        v(0.0, 1.0, 5.0),
        v(0.0, 0.5, 0.0),
        v(0.0, 1.0, 0.0),
        scale,
        10.0 * scale,
        v(0.0, 0.0, 0.0),
        v(2.0, 5.0, 3.0),
        30.0 * scale * scale,
    )
}

/// The rendered pixels of the scene (Whitted, one sample).
fn pixels(offset: f64, scale: f64) -> Vec<[f32; 3]> {
    rendered(scene(offset, scale, "whitted", 1))
}

/// The pixels of the scene file `text`.
fn rendered(text: String) -> Vec<[f32; 3]> {
    let loaded = SceneFile::parse(PathBuf::from("far.toml"), PathBuf::new(), text)
        .and_then(|f| f.build())
        .unwrap_or_else(|e| panic!("{e}"));
    let film = render(&loaded.scene, &loaded.settings, None, &Hooks::none())
        .unwrap()
        .film;
    (0..film.height())
        .flat_map(|y| (0..film.width()).map(move |x| (x, y)))
        .map(|(x, y)| film.pixel(x, y).to_array())
        .collect()
}

/// How many pixels of `b` differ from `a` by more than a tenth (of the brighter channel, or of
/// 1e-3 for black ones).
fn pixels_off(a: &[[f32; 3]], b: &[[f32; 3]]) -> usize {
    a.iter()
        .zip(b)
        .filter(|(p, q)| {
            let scale = p.iter().copied().fold(1e-3, f32::max);
            (0..3).any(|k| (p[k] - q[k]).abs() > 0.1 * scale)
        })
        .count()
}

#[test]
fn offsets_and_scales_keep_the_shadow_and_shading() {
    let at_origin = pixels(0.0, 1.0);
    // The shadow is there to lose: a good share of the floor is dark.
    let dark = at_origin.iter().filter(|p| p[0] == 0.0).count();
    assert!(dark > 200, "{dark} dark pixels");
    // (offset, scale, most pixels off): at 1e5 a coordinate's ulp is 0.008, and the sphere's
    // silhouette and the shadow's edge move by it.
    for (offset, scale, most) in [
        (1e3, 1.0, 0),
        (1e5, 1.0, 0),
        (1e7, 1.0, 0),
        (0.0, 1e-6, 0),
        (0.0, 1e-3, 0),
        (0.0, 1e3, 0),
        (0.0, 1e6, 0),
    ] {
        let off = pixels_off(&at_origin, &pixels(offset, scale));
        println!("offset {offset:e}, scale {scale:e}: {off} of 4096 pixels more than 10% off");
        assert!(
            off <= most,
            "offset {offset}, scale {scale}: {off} pixels off"
        );
    }
}

/// The means of the 8 × 8 blocks of a 64 × 64 image, summed over the channels.
fn block_means(p: &[[f32; 3]]) -> Vec<f32> {
    (0..64)
        .map(|b| {
            let (bx, by) = (b % 8 * 8, b / 8 * 8);
            let mut sum = 0.0;
            for y in by..by + 8 {
                for x in bx..bx + 8 {
                    sum += p[y * 64 + x].iter().sum::<f32>();
                }
            }
            sum / 64.0
        })
        .collect()
}

/// The path tracer (interreflection, the light found by both techniques) agrees within noise:
/// every 8 × 8 block's mean within 5% of the image's mean brightness of the one at the origin.
#[test]
fn the_path_tracer_agrees_within_noise_far_out_and_scaled() {
    let at_origin = block_means(&rendered(scene(0.0, 1.0, "path", 16)));
    let mean = at_origin.iter().sum::<f32>() / 64.0;
    for (offset, scale) in [(1e3, 1.0), (1e5, 1.0), (1e7, 1.0), (0.0, 1e-6), (0.0, 1e6)] {
        let there = block_means(&rendered(scene(offset, scale, "path", 16)));
        let worst = at_origin
            .iter()
            .zip(&there)
            .map(|(a, b)| (a - b).abs() / mean)
            .fold(0.0, f32::max);
        println!(
            "path, offset {offset:e}, scale {scale:e}: worst block off by {:.2}% of the mean",
            100.0 * worst
        );
        assert!(worst < 0.05, "offset {offset}, scale {scale}: {worst}");
    }
}

/// A scene given as `body` (objects and lights) seen by a camera at `eye` looking at
/// `look_at` with field of view `fov`, Whitted, 64 × 64.
fn framed(eye: [f64; 3], look_at: [f64; 3], fov: f64, body: &str) -> String {
    format!(
        "[image]\nwidth = 64\nheight = 64\nsamples = 1\n[render]\nintegrator = \"whitted\"\n\
         [camera]\neye = {eye:?}\nlook_at = {look_at:?}\nfov = {fov}\n{body}"
    )
}

/// Solid textures are defined in the world, not in the rebased scene: a checkerboard of cubes
/// of side 0.3 on a sphere and a rectangle looks the same after a move by 6e4 (a whole number
/// of its periods, 0.6), though the scene is then built about another origin (60416, not one).
#[test]
fn solid_textures_stay_in_the_world() {
    let at = |o: f64| {
        let p = |x: f64, y: f64, z: f64| format!("[{}, {}, {}]", x + o, y + o, z + o);
        let body = format!(
            "[[material]]\nname = \"m\"\ntype = \"whitted\"\nkd = {{ checker = {{ even = 0.9, odd = 0.1, size = 0.3 }} }}\n\
             [[object]]\ntype = \"sphere\"\ncenter = {}\nradius = 1\nmaterial = \"m\"\n\
             [[object]]\ntype = \"rectangle\"\nscale = 4\nrotate = [-90, 0, 0]\ntranslate = {}\nmaterial = \"m\"\n\
             [[light]]\ntype = \"point\"\nposition = {}\n",
            p(0.0, 1.15, 0.0),
            // Mid-cell: a floor on a cell boundary flickers between cells on rounding.
            p(0.0, 0.15, 0.0),
            p(2.0, 5.0, 3.0),
        );
        let eye = [o, 2.0 + o, 6.0 + o];
        rendered(framed(eye, [o, 0.5 + o, o], 45.0, &body))
    };
    let (here, there) = (at(0.0), at(6e4));
    let off = pixels_off(&here, &there);
    println!("checker at 6e4: {off} of 4096 pixels more than 10% off");
    // The texture's cells alternate across the whole view: a shift shows everywhere (1,403
    // pixels when the origin was not added back); its edges move by a world coordinate's step
    // at 6e4, 0.004 (10 pixels).
    assert!(off <= 40, "{off} pixels off");
}

/// A motion's keys turn about the world's origin, wherever the scene is built from: a sphere
/// at x = 2 turned a quarter about y by its only key is where a sphere placed at z = −2 is,
/// seen from 2,000 units away (so the scene is rebased, to z = 2048).
#[test]
fn motion_keys_turn_about_the_worlds_origin_in_a_rebased_scene() {
    let body = |sphere: &str| {
        format!(
            "[[material]]\nname = \"m\"\ntype = \"diffuse\"\nreflectance = 0.7\n\
             [[object]]\ntype = \"sphere\"\nradius = 0.5\nmaterial = \"m\"\n{sphere}\n\
             [[light]]\ntype = \"directional\"\ndirection = [-1, -1, -1]\n"
        )
    };
    let eye = [0.0, 0.0, 2000.0];
    let view = |b: &str| rendered(framed(eye, [0.0, 0.0, -2.0], 0.06, &body(b)));
    let turned =
        view("center = [2, 0, 0]\nmotion = { keys = [{ time = 0, rotate = [0, 90, 0] }] }");
    let placed = view("center = [0, 0, -2]");
    let lit = placed.iter().filter(|p| p[0] > 0.0).count();
    assert!(lit > 200, "the sphere fills {lit} pixels");
    let off = pixels_off(&placed, &turned);
    println!("turned by its key in a rebased scene: {off} of 4096 pixels off");
    assert!(off <= 8, "{off} pixels off");
}
