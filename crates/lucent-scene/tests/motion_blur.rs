//! The shutter: a render through it equals the mean of renders at instants spread over it
//! (objects and camera), for every integrator; a scene where nothing moves renders through a
//! shutter bit for bit as without; bad shutters are refused at their place.

use lucent::render::{Hooks, RenderSettings, render};
use lucent::scene::Scene;
use lucent_scene::{LoadError, Loaded, SceneFile};
use std::path::PathBuf;

const WIDTH: usize = 64;
const HEIGHT: usize = 48;

/// A ball sliding 3 units along x and a cube turning a quarter turn over t ∈ [0, 1], a still
/// ball, on a floor under a point light; `camera` and `render` are added to the tables.
fn scene(camera: &str, render: &str, spp: u32) -> String {
    format!(
        r#"
[image]
width = {WIDTH}
height = {HEIGHT}
samples = {spp}

[camera]
eye = [0, 2, 7]
look_at = [0, 0.6, 0]
fov = 40
{camera}

[render]
{render}

[world]
background = [0.2, 0.3, 0.5]
ambient = 0.1

[[material]]
name = "floor"
kd = 0.7

[[material]]
name = "red"
kd = [0.8, 0.1, 0.05]
ks = 0.3
shininess = 40

[[light]]
type = "point"
position = [-3, 6, 4]
intensity = 30
falloff = "quadratic"

[[object]]
type = "plane"
point = [0, 0, 0]
normal = [0, 1, 0]
material = "floor"

[[object]]
type = "sphere"
center = [0, 0.6, 1]
radius = 0.6
material = "red"
motion = {{ keys = [ {{ time = 0, translate = [-1.5, 0, 0] }}, {{ time = 1, translate = [1.5, 0, 0] }} ] }}

[[object]]
type = "cube"
scale = 0.7
material = "floor"
motion = {{ keys = [ {{ time = 0, translate = [1.8, 0.7, -1.5] }}, {{ time = 1, translate = [1.8, 0.7, -1.5], rotate = [0, 90, 0] }} ] }}

[[object]]
type = "sphere"
center = [-2, 0.5, -1.5]
radius = 0.5
material = "floor"
"#
    )
}

fn load(text: &str) -> Result<Loaded, LoadError> {
    SceneFile::parse(PathBuf::from("blur.toml"), PathBuf::new(), text.to_string())?.build()
}

/// The pixels of `scene` rendered with `settings`.
fn pixels(scene: &Scene, settings: &RenderSettings) -> Vec<[f32; 3]> {
    let film = render(scene, settings, None, &Hooks::none()).unwrap().film;
    (0..film.height())
        .flat_map(|y| (0..film.width()).map(move |x| (x, y)))
        .map(|(x, y)| film.pixel(x, y).to_array())
        .collect()
}

/// The mean of renders at `n` instants evenly spread over `[0, 1]`.
fn mean_of_instants(loaded: &Loaded, n: u32) -> Vec<[f32; 3]> {
    let mut sum = vec![[0.0f32; 3]; WIDTH * HEIGHT];
    for i in 0..n {
        let instant = loaded.scene.at_time((f64::from(i) + 0.5) / f64::from(n));
        assert!(!instant.blurs());
        for (s, p) in sum.iter_mut().zip(pixels(&instant, &loaded.settings)) {
            for k in 0..3 {
                s[k] += p[k] / n as f32;
            }
        }
    }
    sum
}

/// The largest difference between the means of the 8 × 8 blocks of `a` and `b` (summed over
/// the channels), as a share of `a`'s mean brightness.
fn worst_block(a: &[[f32; 3]], b: &[[f32; 3]]) -> f32 {
    let mean = a.iter().map(|p| p.iter().sum::<f32>()).sum::<f32>() / a.len() as f32;
    let block = |p: &[[f32; 3]], bx: usize, by: usize| -> f32 {
        let mut sum = 0.0;
        for y in by..by + 8 {
            for x in bx..bx + 8 {
                sum += p[y * WIDTH + x].iter().sum::<f32>();
            }
        }
        sum / 64.0
    };
    let mut worst = 0.0f32;
    for by in (0..HEIGHT).step_by(8) {
        for bx in (0..WIDTH).step_by(8) {
            worst = worst.max((block(a, bx, by) - block(b, bx, by)).abs());
        }
    }
    worst / mean
}

/// Renders `text` through its shutter and as the mean of 32 instants, and checks that they
/// agree within `tolerance` (worst block) while one instant alone does not.
fn blur_is_the_mean_of_instants(text: &str, tolerance: f32) {
    let loaded = load(text).unwrap_or_else(|e| panic!("{e}"));
    assert!(loaded.scene.blurs());
    let blurred = pixels(&loaded.scene, &loaded.settings);
    let mean = mean_of_instants(&loaded, 32);
    let off = worst_block(&mean, &blurred);
    let instant = pixels(&loaded.scene.at_time(0.5), &loaded.settings);
    let still_off = worst_block(&mean, &instant);
    println!("worst block: blurred {off:.4}, one instant {still_off:.4} (tolerance {tolerance})");
    assert!(
        off <= tolerance,
        "blurred is {off} off the mean of instants"
    );
    assert!(
        still_off > 4.0 * tolerance,
        "one instant is only {still_off} off: the test cannot tell blur from none"
    );
}

const SHUTTER: &str = "shutter = [0, 1]";

#[test]
fn whitted_blur_is_the_mean_of_instants() {
    blur_is_the_mean_of_instants(&scene(SHUTTER, "integrator = \"whitted\"", 64), 0.01);
}

#[test]
fn path_traced_blur_is_the_mean_of_instants() {
    blur_is_the_mean_of_instants(&scene(SHUTTER, "integrator = \"path\"", 64), 0.02);
}

#[test]
fn adaptive_blur_is_the_mean_of_instants() {
    let render = "integrator = \"whitted\"\naa = \"adaptive\"\naa_depth = 4";
    blur_is_the_mean_of_instants(&scene(SHUTTER, render, 1), 0.02);
}

#[test]
fn photon_mapped_blur_is_the_mean_of_instants() {
    // Under a black sky: the sky's photons are the noise of a render this short.
    let text = scene(SHUTTER, "integrator = \"sppm\"\nphotons = 100000", 32)
        .replace("background = [0.2, 0.3, 0.5]", "background = 0");
    blur_is_the_mean_of_instants(&text, 0.05);
}

#[test]
fn a_moving_camera_blurs_the_still_scene() {
    let camera = format!(
        "{SHUTTER}\nmotion = {{ keys = [ {{ time = 0, translate = [-1, 0, 0] }}, {{ time = 1, translate = [1, 0, 0] }} ] }}"
    );
    let text = still(&scene(&camera, "integrator = \"whitted\"", 64));
    let loaded = load(&text).unwrap();
    assert!(loaded.scene.camera_moves() && loaded.scene.moving_objects() == 0);
    blur_is_the_mean_of_instants(&text, 0.01);
}

/// `text` with its objects' motions taken away (the camera's, on one line, stays).
fn still(text: &str) -> String {
    text.lines()
        .filter(|l| !l.starts_with("motion = { keys = [ { time = 0, translate = [-1.5"))
        .filter(|l| !l.starts_with("motion = { keys = [ { time = 0, translate = [1.8"))
        .map(|l| format!("{l}\n"))
        .collect()
}

#[test]
fn a_still_scene_renders_bit_for_bit_as_without_a_shutter() {
    for render in [
        "integrator = \"whitted\"",
        "integrator = \"path\"",
        "integrator = \"sppm\"",
        "integrator = \"whitted\"\naa = \"adaptive\"",
    ] {
        let still = still(&scene("", render, 4));
        let without = load(&still).unwrap();
        let with = load(&still.replace("fov = 40", &format!("fov = 40\n{SHUTTER}"))).unwrap();
        assert!(with.scene.shutter().is_some() && !with.scene.blurs());
        let (a, b) = (
            pixels(&without.scene, &without.settings),
            pixels(&with.scene, &with.settings),
        );
        assert!(a == b, "{render}: a shutter changed a still scene");
    }
}

#[test]
fn an_instant_of_a_scene_with_a_shutter_is_that_instant() {
    let loaded = load(&scene(SHUTTER, "integrator = \"whitted\"", 4)).unwrap();
    let plain = load(&scene("", "integrator = \"whitted\"", 4)).unwrap();
    let at = loaded.scene.at_time(0.25);
    assert!(at.shutter().is_none() && !at.blurs());
    assert!(pixels(&at, &loaded.settings) == pixels(&plain.scene.at_time(0.25), &plain.settings));
}

#[test]
fn bad_shutters_are_refused_at_their_place() {
    let e = load(&scene("shutter = [1, 0.5]", "", 1))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("blur.toml:11:11: "), "{e}");
    assert!(e.contains("closes (0.5) before it opens (1)"), "{e}");
    let e = load(&scene("shutter = [1]", "", 1))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("blur.toml:11:11: "), "{e}");
}
