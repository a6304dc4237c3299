//! Texture filtering against aliasing: a checkered plane receding to the horizon, rendered at
//! one sample per pixel with MIP-mapped filtering over each sample's footprint (anisotropic,
//! lucent's default, and trilinear) and with plain bilinear lookups, each held to the same plane at 1024 samples per pixel without
//! prefiltering (the pixels' true averages). Far away, where a pixel covers many checks, one
//! bilinear lookup per pixel picks a check at random (the moiré that shimmers as the camera
//! moves); the filtered lookup returns their mean.
//!
//! Both the path tracer (the plane's emission texture, which camera rays see directly) and the
//! classic integrators (its diffuse texture, ray cast) filter so. Metric: the root-mean-square
//! error over the image, and the shimmer, the RMS difference between two 1-spp images from a
//! camera moved sideways by a fifth of a check (and other sample positions). The figures are in `docs/materials.md`.

use lucent::render::{Hooks, RenderSettings, render};
use lucent_scene::{LoadOptions, SceneFile, Spanned};
use std::path::Path;

/// A 256×256 checker of 16×16 squares, black and white.
fn write_checker(dir: &Path) {
    let img = image::RgbImage::from_fn(256, 256, |x, y| {
        if (x / 16 + y / 16) % 2 == 0 {
            image::Rgb([255, 255, 255])
        } else {
            image::Rgb([0, 0, 0])
        }
    });
    img.save(dir.join("checker.png")).unwrap();
}

/// The scene: a 400 × 400 plane repeating the checker 100 times each way, seen from just
/// above it from `eye_x` along x; `slot` carries the texture (`kd` ray cast, or `emission` path traced).
fn scene(integrator: &str, slot: &str, filter: &str, eye_x: f32) -> String {
    let texture = format!(
        r#"{{ image = "checker.png", encoding = "linear", filter = "{filter}", scale = [100, 100] }}"#
    );
    let material = if slot == "kd" {
        format!("type = \"whitted\"\nkd = {texture}")
    } else {
        format!("type = \"diffuse\"\nreflectance = 0\nemission = {texture}")
    };
    format!(
        r#"
[image]
width = 96
height = 64

[camera]
eye = [{eye_x}, 1, 0]
look_at = [{eye_x}, 0.75, -10]
fov = 50

[render]
integrator = "{integrator}"

[[material]]
name = "floor"
{material}

[[object]]
type = "rectangle"
scale = 200
rotate = [-90, 0, 0]
material = "floor"
"#
    )
}

/// The linear image of `text` (a scene in `dir`) at `spp` samples per pixel, seed `seed`.
fn render_scene(dir: &Path, text: &str, spp: u32, seed: u64) -> Vec<f32> {
    let path = dir.join("plane.toml");
    std::fs::write(&path, text).unwrap();
    let mut file = SceneFile::read_with(&path, &LoadOptions::default()).unwrap();
    file.desc.image.samples = Spanned::new(0..0, spp);
    let loaded = file.build().unwrap();
    let hooks = Hooks::none();
    let settings = RenderSettings {
        seed,
        ..loaded.settings
    };
    let film = render(&loaded.scene, &settings, None, &hooks).unwrap().film;
    let mut out = Vec::new();
    for y in 0..film.height() {
        for x in 0..film.width() {
            out.extend(film.pixel(x, y).to_array());
        }
    }
    out
}

fn rms(a: &[f32], b: &[f32]) -> f64 {
    let sum: f64 = a.iter().zip(b).map(|(x, y)| f64::from(x - y).powi(2)).sum();
    (sum / a.len() as f64).sqrt()
}

/// The 1-spp error and shimmer with MIP maps and without, for one integrator and slot.
fn measure(integrator: &str, slot: &str) -> [(f64, f64); 3] {
    let dir = std::env::temp_dir().join(format!(
        "lucent-filtering-{integrator}-{slot}-{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    write_checker(&dir);
    let truth = render_scene(&dir, &scene(integrator, slot, "bilinear", 0.0), 1024, 1);
    let figures = ["anisotropic", "trilinear", "bilinear"].map(|filter| {
        let a = render_scene(&dir, &scene(integrator, slot, filter, 0.0), 1, 2);
        // The camera moved sideways by a fifth of a check, and new samples.
        let b = render_scene(&dir, &scene(integrator, slot, filter, 0.05), 1, 3);
        (rms(&a, &truth), rms(&a, &b))
    });
    std::fs::remove_dir_all(&dir).unwrap();
    println!(
        "{integrator} ({slot}) at 1 spp: RMS error {:.4} anisotropic, {:.4} trilinear, {:.4} bilinear (no MIP maps); shimmer {:.4}, {:.4}, {:.4}",
        figures[0].0, figures[1].0, figures[2].0, figures[0].1, figures[1].1, figures[2].1
    );
    figures
}

#[test]
fn mip_maps_keep_a_receding_checker_from_aliasing_and_shimmering() {
    for (integrator, slot) in [("path", "emission"), ("raycast", "kd")] {
        let [anisotropic, trilinear, (plain, plain_shimmer)] = measure(integrator, slot);
        for (name, (error, shimmer)) in [("anisotropic", anisotropic), ("trilinear", trilinear)] {
            assert!(
                error < 0.6 * plain,
                "{integrator}: error {error} {name}, {plain} without MIP maps"
            );
            assert!(
                shimmer < 0.6 * plain_shimmer,
                "{integrator}: shimmer {shimmer} {name}, {plain_shimmer} without MIP maps"
            );
        }
        // Long footprints probed along their length blur less than one trilinear lookup.
        assert!(
            anisotropic.0 < trilinear.0,
            "{integrator}: {anisotropic:?} vs {trilinear:?}"
        );
    }
}
