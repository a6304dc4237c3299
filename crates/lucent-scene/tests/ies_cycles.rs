//! A photometric light against Blender's Cycles on the same IES file: a lamp above a floor and
//! before a wall, its asymmetric profile (`data/ies-asymmetric.ies`) throwing a lobe onto the
//! wall, rendered by Cycles (`bench/peers/cycles_ies.py`, 4096 spp, stored as
//! `data/cycles-ies.exr`) and by lucent's path tracer. The pattern — where the lobe lands, its
//! shape, the falloff and the light the surfaces pass on — must agree; the absolute scale is
//! normalised out (Cycles' IES node and its lamp's watts do not state candela).
//!
//! Cycles measures the horizontal angle `C` clockwise seen from above, from the lamp's `−y`;
//! LM-63 and lucent counter-clockwise from `+x` (see docs/lights.md). The profile is symmetric
//! about its 90°–270° plane, so the two readings differ by a turn only, which lucent's `front`
//! gives: Cycles' lobe at `C = 90°` goes to `−x`, and so does lucent's with `front = [0, 0, −1]`.

use lucent::render::{Hooks, render};
use lucent_scene::SceneFile;
use std::path::{Path, PathBuf};

const WIDTH: usize = 96;
const HEIGHT: usize = 64;

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data")
}

/// The comparison scene, in lucent's y-up frame (Cycles' is z-up: its `(x, y, z)` is lucent's
/// `(x, z, −y)`).
fn scene(front: &str) -> String {
    format!(
        r#"
[image]
width = {WIDTH}
height = {HEIGHT}
samples = 256

[camera]
eye = [0, 4, 7]
look_at = [0, 1, -1]
fov = 50

[render]
integrator = "path"
max_depth = 9

[world]
background = 0

[[material]]
name = "grey"
type = "diffuse"
reflectance = 0.5

[[object]]
type = "rectangle"
scale = 10
rotate = [-90, 0, 0]
material = "grey"

[[object]]
type = "rectangle"
scale = 10
translate = [0, 0, -3]
material = "grey"

[[light]]
type = "photometric"
file = "ies-asymmetric.ies"
position = [0, 3, 0]
front = {front}
"#
    )
}

/// lucent's image of the scene, each channel's value per pixel (rows from the top).
fn lucent_image(front: &str) -> Vec<f32> {
    let loaded = SceneFile::parse(data().join("ies-cycles.toml"), data(), scene(front))
        .and_then(|f| f.build())
        .unwrap_or_else(|e| panic!("{e}"));
    let film = render(&loaded.scene, &loaded.settings, None, &Hooks::none())
        .unwrap()
        .film;
    let mut out = Vec::with_capacity(WIDTH * HEIGHT * 3);
    for y in 0..film.height() {
        for x in 0..film.width() {
            out.extend(film.pixel(x, y).to_array());
        }
    }
    out
}

/// Cycles' image (rows from the top, RGB).
fn cycles_image() -> Vec<f32> {
    let img = image::open(data().join("cycles-ies.exr"))
        .expect("the Cycles reference reads")
        .into_rgb32f();
    assert_eq!(
        (img.width() as usize, img.height() as usize),
        (WIDTH, HEIGHT)
    );
    img.into_raw()
}

/// `v` divided by its mean.
fn normalised(v: &[f32]) -> Vec<f32> {
    let mean = v.iter().sum::<f32>() / v.len() as f32;
    v.iter().map(|x| x / mean).collect()
}

/// The largest difference of the 8 × 8 blocks' means (channels summed) between `a` and `b`,
/// both normalised to a mean of 1.
fn worst_block(a: &[f32], b: &[f32]) -> f32 {
    let block = |v: &[f32], bx: usize, by: usize| -> f32 {
        let mut sum = 0.0;
        for y in by..by + 8 {
            for x in bx..bx + 8 {
                sum += v[(y * WIDTH + x) * 3..][..3].iter().sum::<f32>();
            }
        }
        sum / (64.0 * 3.0)
    };
    let mut worst = 0.0f32;
    for by in (0..HEIGHT).step_by(8) {
        for bx in (0..WIDTH).step_by(8) {
            worst = worst.max((block(a, bx, by) - block(b, bx, by)).abs());
        }
    }
    worst
}

#[test]
fn the_lamps_pattern_agrees_with_cycles() {
    let cycles = normalised(&cycles_image());
    let lucent = normalised(&lucent_image("[0, 0, -1]"));
    let off = worst_block(&cycles, &lucent);
    // The same file read with lucent's default orientation (C = 0° along +x): the lobe lands
    // elsewhere, which the metric must see.
    let turned = worst_block(&cycles, &normalised(&lucent_image("[1, 0, 0]")));
    println!("worst 8×8 block, normalised: {off:.4} (turned a quarter: {turned:.4})");
    assert!(off < 0.05, "lucent is {off} off Cycles");
    assert!(turned > 10.0 * 0.05, "a turned lamp is only {turned} off");
}
