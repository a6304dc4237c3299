//! Lights from images: a projector throws its slide the right way round and as bright as its
//! texels say, a goniometric light's map turns with its `up`, a textured spot is its image under
//! its edge; the path tracer and the photon mapper agree on what they light (the photons carry
//! the flux the light sends); bad tables are refused at their place.

use glam::Vec3;
use lucent::Rgb;
use lucent::light::Light;
use lucent::render::{Hooks, render};
use lucent_scene::{LoadError, Loaded, SceneFile};
use std::path::PathBuf;

/// A scratch folder of this test process.
fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("lucent-image-lights-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes a linear float image (EXR) of `w × h` texels.
fn write_exr(path: &std::path::Path, w: u32, h: u32, texels: &[[f32; 3]]) {
    let raw: Vec<f32> = texels.iter().flatten().copied().collect();
    image::Rgb32FImage::from_raw(w, h, raw)
        .unwrap()
        .save(path)
        .unwrap();
}

/// A 2 × 2 slide: red top left, green top right, blue bottom left, white bottom right.
const SLIDE: [[f32; 3]; 4] = [
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 1.0, 1.0],
];

/// `text` (a scene file) loaded in folder `dir`.
fn load_in(dir: &std::path::Path, text: &str) -> Result<Loaded, LoadError> {
    SceneFile::parse(dir.join("scene.toml"), dir.to_path_buf(), text.to_string())?.build()
}

/// The one light of a scene with `light` (the table's keys) beside image `slide.exr`.
fn light_of(name: &str, texels: (u32, u32, &[[f32; 3]]), light: &str) -> Light {
    let dir = scratch(name);
    write_exr(&dir.join("slide.exr"), texels.0, texels.1, texels.2);
    let text = format!("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[[light]]\n{light}\n");
    let loaded = load_in(&dir, &text).unwrap_or_else(|e| panic!("{e}"));
    loaded.scene.lights[0].clone()
}

/// The intensity `light` sends towards `p` (its quadratic falloff undone).
fn intensity_towards(light: &Light, p: Vec3) -> Rgb {
    let from = light.position().unwrap();
    light
        .illuminate(p)
        .map_or(Rgb::BLACK, |s| s.intensity * (p - from).length_squared())
}

fn close(a: Rgb, b: Rgb) -> bool {
    (a.r - b.r).abs() < 1e-3 && (a.g - b.g).abs() < 1e-3 && (a.b - b.b).abs() < 1e-3
}

#[test]
fn a_projector_throws_its_slide_the_right_way_round() {
    let light = light_of(
        "projector",
        (2, 2, &SLIDE),
        "type = \"projection\"\nfile = \"slide.exr\"\nposition = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 40\nintensity = 2",
    );
    // The texels' centres, on a wall 5 away: a quarter of the frustum's width off the axis.
    let t = 20f32.to_radians().tan() * 0.5 * 5.0;
    let at = |x: f32, y: f32| intensity_towards(&light, Vec3::new(x * t, y * t, -5.0));
    assert!(
        close(at(-1.0, 1.0), Rgb::new(2.0, 0.0, 0.0)),
        "{:?}",
        at(-1.0, 1.0)
    );
    assert!(close(at(1.0, 1.0), Rgb::new(0.0, 2.0, 0.0)));
    assert!(close(at(-1.0, -1.0), Rgb::new(0.0, 0.0, 2.0)));
    assert!(close(at(1.0, -1.0), Rgb::new(2.0, 2.0, 2.0)));
    // Beyond the frustum's edge and behind the projector: nothing.
    assert_eq!(at(2.2, 0.0), Rgb::BLACK);
    assert_eq!(
        intensity_towards(&light, Vec3::new(0.0, 0.0, 5.0)),
        Rgb::BLACK
    );
}

#[test]
fn a_wide_slide_widens_the_frustum_by_its_aspect() {
    let wide: Vec<[f32; 3]> = (0..8).map(|i| [i as f32, 1.0, 0.0]).collect();
    let light = light_of(
        "wide",
        (4, 2, &wide),
        "type = \"projection\"\nfile = \"slide.exr\"\nposition = [0, 0, 0]\ndirection = [0, 0, -1]\nfov = 40",
    );
    let half_width = 20f32.to_radians().tan() * 2.0;
    let inside = intensity_towards(&light, Vec3::new(0.95 * half_width, 0.0, -1.0));
    let outside = intensity_towards(&light, Vec3::new(1.05 * half_width, 0.0, -1.0));
    assert!(
        inside.g > 0.9 && outside == Rgb::BLACK,
        "{inside:?} {outside:?}"
    );
}

#[test]
fn a_goniometric_map_turns_with_its_up() {
    // A lat-long map lit only in its top rows (towards the pole), and an equal-area one lit
    // only at its centre (the pole too).
    let mut latlong = vec![[0.0f32; 3]; 8 * 4];
    for t in latlong.iter_mut().take(8) {
        *t = [1.0; 3];
    }
    let mut equal_area = vec![[0.0f32; 3]; 8 * 8];
    for (x, y) in [(3, 3), (4, 3), (3, 4), (4, 4)] {
        equal_area[y * 8 + x] = [1.0; 3];
    }
    for (name, (w, h, texels), mapping) in [
        ("latlong", (8, 4, &latlong), "latlong"),
        ("equal-area", (8, 8, &equal_area), "equal-area"),
    ] {
        for (up, towards, away) in [
            ("[0, 1, 0]", Vec3::Y, -Vec3::Y),
            ("[1, 0, 0]", Vec3::X, -Vec3::X),
            ("[0, 0, -1]", -Vec3::Z, Vec3::Y),
        ] {
            let light = light_of(
                &format!("{name}-{}", towards.x + 2.0 * towards.y),
                (w, h, texels),
                &format!(
                    "type = \"goniometric\"\nfile = \"slide.exr\"\nmapping = \"{mapping}\"\nposition = [1, 2, 3]\nup = {up}"
                ),
            );
            let p = Vec3::new(1.0, 2.0, 3.0);
            let lit = intensity_towards(&light, p + towards * 4.0);
            let dark = intensity_towards(&light, p + away * 4.0);
            assert!(
                lit.g > 0.99 && dark == Rgb::BLACK,
                "{name} up {up}: {lit:?} {dark:?}"
            );
        }
    }
}

#[test]
fn a_textured_spot_is_its_image_under_its_edge() {
    let white = [[1.0f32; 3]; 4];
    let spot = |file: &str| {
        format!(
            "type = \"spot\"\n{file}position = [0, 0, 0]\ndirection = [0, -1, 0]\ncutoff = 30\ncutoff_start = 20\nintensity = 3"
        )
    };
    let plain = light_of("spot-plain", (2, 2, &white), &spot(""));
    let textured = light_of(
        "spot-white",
        (2, 2, &white),
        &spot("file = \"slide.exr\"\n"),
    );
    for deg in [0.0f32, 10.0, 19.0, 22.0, 25.0, 29.0, 31.0, 60.0] {
        let d = Vec3::new(deg.to_radians().sin(), -deg.to_radians().cos(), 0.0);
        let (a, b) = (plain.illuminate(d * 2.0), textured.illuminate(d * 2.0));
        let (a, b) = (
            a.map_or(0.0, |s| s.intensity.g),
            b.map_or(0.0, |s| s.intensity.g),
        );
        assert!((a - b).abs() < 1e-5, "{deg}°: plain {a}, textured {b}");
    }
    // The slide across the cone (past its texels' centres, where no two mix): the four
    // quadrants are the slide's four colours.
    let coloured = light_of(
        "spot-slide",
        (2, 2, &SLIDE),
        &spot("file = \"slide.exr\"\n"),
    );
    let mut seen = Vec::new();
    for (x, z) in [(-0.3, -0.3), (0.3, -0.3), (-0.3, 0.3), (0.3, 0.3)] {
        let s = coloured
            .illuminate(Vec3::new(x, -1.0, z))
            .unwrap()
            .intensity;
        seen.push([s.r > 0.0, s.g > 0.0, s.b > 0.0]);
    }
    seen.sort();
    let mut want = vec![
        [true, false, false],
        [false, true, false],
        [false, false, true],
        [true, true, true],
    ];
    want.sort();
    assert_eq!(seen, want);
}

/// A grey box, open towards the camera, lit by a projector at its front.
fn lit_box(integrator: &str, spp: u32) -> String {
    let photons = if integrator == "sppm" {
        "photons = 200000"
    } else {
        ""
    };
    format!(
        r#"
[image]
width = 32
height = 32
samples = {spp}
[camera]
eye = [0, 0, 4]
look_at = [0, 0, 0]
fov = 50
[render]
integrator = "{integrator}"
max_depth = 6
{photons}
[world]
background = 0
[[material]]
name = "grey"
type = "diffuse"
reflectance = 0.6
[[light]]
type = "projection"
file = "slide.exr"
position = [0, 0, 2]
direction = [0, -0.2, -1]
fov = 50
intensity = 10
[[object]]
type = "rectangle"
translate = [0, 0, -1]
material = "grey"
[[object]]
type = "rectangle"
rotate = [-90, 0, 0]
translate = [0, -1, 0]
material = "grey"
[[object]]
type = "rectangle"
rotate = [0, 90, 0]
translate = [-1, 0, 0]
material = "grey"
"#
    )
}

/// The mean of every pixel's channels.
fn mean(loaded: &Loaded) -> f32 {
    let film = render(&loaded.scene, &loaded.settings, None, &Hooks::none())
        .unwrap()
        .film;
    let mut sum = 0.0;
    for y in 0..film.height() {
        for x in 0..film.width() {
            let p = film.pixel(x, y);
            sum += p.r + p.g + p.b;
        }
    }
    sum / (3 * film.width() * film.height()) as f32
}

#[test]
fn the_path_tracer_and_the_photon_mapper_agree_on_a_projectors_light() {
    let dir = scratch("box");
    write_exr(&dir.join("slide.exr"), 2, 2, &SLIDE);
    let path = mean(&load_in(&dir, &lit_box("path", 256)).unwrap());
    let sppm = mean(&load_in(&dir, &lit_box("sppm", 64)).unwrap());
    println!("mean radiance: path {path:.5}, sppm {sppm:.5}");
    assert!(path > 0.01, "{path}");
    assert!(
        (path - sppm).abs() < 0.05 * path,
        "path {path}, sppm {sppm}"
    );
}

#[test]
fn bad_tables_are_refused_at_their_place() {
    let dir = scratch("errors");
    write_exr(&dir.join("slide.exr"), 2, 2, &SLIDE);
    let scene = |light: &str| {
        format!("[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n[[light]]\n{light}\n")
    };
    let error = |light: &str| load_in(&dir, &scene(light)).unwrap_err().to_string();
    let base = "type = \"projection\"\nfile = \"slide.exr\"\nposition = [0, 0, 0]";
    let e = error(&format!("{base}\nmapping = \"latlong\""));
    assert!(e.contains(":8:") && e.contains("mapping"), "{e}");
    let e = error(&format!("{base}\ndirection = [0, 1, 0]\nup = [0, 2, 0]"));
    assert!(e.contains(":9:") && e.contains("`up`"), "{e}");
    let e = error(&format!("{base}\nfov = 180"));
    assert!(e.contains(":8:") && e.contains("fov"), "{e}");
    let e = error("type = \"goniometric\"\nfile = \"nowhere.exr\"\nposition = [0, 0, 0]");
    assert!(e.contains("nowhere.exr"), "{e}");
    let e = error("type = \"goniometric\"\nposition = [0, 0, 0]");
    assert!(e.contains("file"), "{e}");
}
