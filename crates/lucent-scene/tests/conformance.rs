//! The material conformance suite: every BSDF and texture kind lucent reads from Mitsuba XML,
//! rendered from the same file as Mitsuba 3 renders it.
//!
//! `tests/conformance/scenes/*.xml` are small Mitsuba scenes (a ball on a checkered floor, or
//! a textured plane, under a sky and a sun, 64 × 64, box filter) and
//! `tests/conformance/references/*.exr` Mitsuba 3.9.1's images of them (`llvm_ad_rgb`, 16,384
//! samples per pixel), both made by `bench/peers/run.sh conformance write` and `… refs`
//! (`references.json` records how each was made).
//!
//! Metric: per channel, the mean of every 8 × 8 block and of the whole image, lucent's against
//! Mitsuba's, relative to Mitsuba's — a block darker than a tenth of the image's mean counts
//! against that tenth, so that near-black blocks do not divide by noise. Tolerance: 2% for
//! every block and for the whole image (the issue's figure); at 256 samples per pixel (1024 for
//! rough glass) lucent's noise makes up under half of it, and the figures of every case
//! are in `docs/materials.md`. A mismatched distribution (GGX for Beckmann) fails
//! it, as a test shows.
//!
//! The participating media (`medium-*`, rendered by Mitsuba's `volpath`; `medium-smoke` a
//! heterogeneous grid) are noisier: at 512 samples lucent's blocks spread by up to ~8% (the
//! fog) while its whole image is within a few tenths of a percent; they are held to 10% per
//! block and 1% for the whole image at 512 samples; at high sample counts every case came
//! within 2% per block (`docs/media.md`). A medium with the wrong albedo, and a grid in the
//! wrong place, fail that, as two tests show.

use lucent::render::{Hooks, RenderSettings, render};
use lucent_scene::{LoadOptions, SceneFile, Spanned};
use std::path::{Path, PathBuf};

/// Samples per pixel lucent renders each case with: 256, and 1024 for rough glass and the
/// transmissive principled cases, whose light refracted from the small sun is the noisiest to
/// find, and for the Cornell box, lit only by its small ceiling light.
fn spp(name: &str) -> u32 {
    if is_medium(name) {
        512
    } else if name.starts_with("roughdielectric")
        || name == "principled-transmissive"
        || name == "principledthin"
        || name == "cbox-spectral"
    {
        1024
    } else {
        256
    }
}
/// The tolerance on every block and on the whole image.
const TOLERANCE: f64 = 0.02;
/// The media cases' tolerances: every block, the whole image.
const MEDIA_TOLERANCE: (f64, f64) = (0.10, 0.01);

fn is_medium(name: &str) -> bool {
    name.starts_with("medium-")
}
const BLOCK: usize = 8;

fn suite() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/conformance")
}

/// The cases: the scene files' names, sorted.
fn cases() -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(suite().join("scenes"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter_map(|f| f.strip_suffix(".xml").map(str::to_string))
        .collect();
    names.sort();
    names
}

/// Mitsuba's image of a case, as rows of RGB from the top.
fn reference(name: &str) -> (usize, usize, Vec<[f32; 3]>) {
    let path = suite().join("references").join(format!("{name}.exr"));
    let img = image::open(&path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .into_rgb32f();
    let (w, h) = (img.width() as usize, img.height() as usize);
    (w, h, img.pixels().map(|p| p.0).collect())
}

/// lucent's image of the scene in `text`, a case's XML (its textures named relative to the
/// suite's `scenes` folder).
fn render_text(name: &str, text: &str) -> (usize, usize, Vec<[f32; 3]>) {
    let textures = suite().join("textures");
    let text = text.replace("../textures/", &format!("{}/", textures.display()));
    // Tests run in parallel, and two may render the same case: a file of each render's own.
    static RENDERS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = RENDERS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let path = std::env::temp_dir().join(format!(
        "lucent-conformance-{name}-{}-{n}.xml",
        std::process::id()
    ));
    std::fs::write(&path, text).unwrap();
    let file = SceneFile::read_with(&path, &LoadOptions::default());
    std::fs::remove_file(&path).unwrap();
    let mut file = file.unwrap();
    file.desc.image.samples = Spanned::new(0..0, spp(name));
    let loaded = file.build().unwrap();
    assert!(loaded.warnings.is_empty(), "{name}: {:#?}", loaded.warnings);
    let hooks = Hooks::none();
    let settings = RenderSettings {
        seed: 17,
        ..loaded.settings
    };
    let film = render(&loaded.scene, &settings, None, &hooks).unwrap().film;
    let (w, h) = (film.width() as usize, film.height() as usize);
    let mut pixels = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            pixels.push(film.pixel(x as u32, y as u32).to_array());
        }
    }
    (w, h, pixels)
}

fn render_case(name: &str) -> (usize, usize, Vec<[f32; 3]>) {
    let text = std::fs::read_to_string(suite().join("scenes").join(format!("{name}.xml"))).unwrap();
    render_text(name, &text)
}

/// The worst block's and the whole image's relative error (see the module docs).
fn errors(img: &[[f32; 3]], reference: &[[f32; 3]], w: usize, h: usize) -> (f64, f64) {
    let mean = |px: &[[f32; 3]], c: usize| {
        px.iter().map(|p| f64::from(p[c])).sum::<f64>() / px.len() as f64
    };
    let mut worst = 0.0f64;
    let mut whole = 0.0f64;
    for c in 0..3 {
        let floor = 0.1 * mean(reference, c);
        let (a, b) = (mean(img, c), mean(reference, c));
        whole = whole.max((a - b).abs() / b);
        for by in 0..h / BLOCK {
            for bx in 0..w / BLOCK {
                let block = |px: &[[f32; 3]]| {
                    let mut sum = 0.0f64;
                    for y in by * BLOCK..(by + 1) * BLOCK {
                        for x in bx * BLOCK..(bx + 1) * BLOCK {
                            sum += f64::from(px[y * w + x][c]);
                        }
                    }
                    sum / (BLOCK * BLOCK) as f64
                };
                let (a, b) = (block(img), block(reference));
                worst = worst.max((a - b).abs() / b.max(floor));
            }
        }
    }
    (worst, whole)
}

/// Renders every case of `names`, and the failures against `(block, whole)` tolerances.
fn failures(names: &[String], (block, whole_image): (f64, f64)) -> Vec<String> {
    let mut failures = Vec::new();
    println!("{:40} {:>10} {:>10}", "case", "worst 8x8", "whole");
    for name in names {
        let (w, h, reference) = reference(name);
        let (iw, ih, img) = render_case(name);
        assert_eq!((iw, ih), (w, h), "{name}");
        let (worst, whole) = errors(&img, &reference, w, h);
        println!("{name:40} {:9.2}% {:9.2}%", 100.0 * worst, 100.0 * whole);
        if worst > block || whole > whole_image {
            failures.push(format!(
                "{name}: worst block {:.2}%, whole image {:.2}%",
                100.0 * worst,
                100.0 * whole
            ));
        }
    }
    failures
}

#[test]
fn every_case_agrees_with_mitsuba_within_two_percent() {
    let names: Vec<_> = cases().into_iter().filter(|n| !is_medium(n)).collect();
    assert!(names.len() >= 30, "only {} cases", names.len());
    let failures = failures(&names, (TOLERANCE, TOLERANCE));
    assert!(failures.is_empty(), "over 2%:\n{}", failures.join("\n"));
}

#[test]
fn media_agree_with_mitsubas_volpath() {
    let names: Vec<_> = cases().into_iter().filter(|n| is_medium(n)).collect();
    assert!(names.len() >= 3, "only {} media cases", names.len());
    let failures = failures(&names, MEDIA_TOLERANCE);
    assert!(
        failures.is_empty(),
        "over the tolerance:\n{}",
        failures.join("\n")
    );
}

/// The media cases can fail: the fog with a tenth more albedo (0.935, 0.88, 0.77 for 0.85,
/// 0.8, 0.7) is outside their tolerance.
#[test]
fn a_wrong_albedo_fails_the_media_metric() {
    let name = "medium-cbox-fog";
    let text = std::fs::read_to_string(suite().join("scenes").join(format!("{name}.xml"))).unwrap();
    let right = r#"<rgb name="albedo" value="0.85, 0.8, 0.7"/>"#;
    assert!(text.contains(right));
    let wrong = r#"<rgb name="albedo" value="0.935, 0.88, 0.77"/>"#;
    let (w, h, reference) = reference(name);
    let (_, _, img) = render_text(name, &text.replace(right, wrong));
    let (worst, whole) = errors(&img, &reference, w, h);
    println!("wrong albedo: worst block {worst}, whole image {whole}");
    assert!(
        worst > MEDIA_TOLERANCE.0 || whole > 3.0 * MEDIA_TOLERANCE.1,
        "a wrong albedo passed: worst block {worst}, whole image {whole}"
    );
}

/// A grid in the wrong place fails too: the smoke's density moved 0.1 (an eighth of its box's
/// width) to the right inside its box.
#[test]
fn a_misplaced_grid_fails_the_media_metric() {
    let name = "medium-smoke";
    let text = std::fs::read_to_string(suite().join("scenes").join(format!("{name}.xml"))).unwrap();
    let right = r#"<translate x="-0.86" y="-0.99" z="-0.6"/>"#;
    assert!(text.contains(right));
    let wrong = r#"<translate x="-0.76" y="-0.99" z="-0.6"/>"#;
    let (w, h, reference) = reference(name);
    let (_, _, img) = render_text(name, &text.replace(right, wrong));
    let (worst, whole) = errors(&img, &reference, w, h);
    println!("misplaced grid: worst block {worst}, whole image {whole}");
    assert!(
        worst > MEDIA_TOLERANCE.0 || whole > 3.0 * MEDIA_TOLERANCE.1,
        "a misplaced grid passed: worst block {worst}, whole image {whole}"
    );
}

/// The suite can fail: Mitsuba's Beckmann ball rendered with GGX facets of the same roughness
/// (what lucent did before it read Beckmann) is far outside the tolerance.
#[test]
fn a_wrong_distribution_fails_the_metric() {
    let name = "roughconductor-beckmann-0.4";
    let text = std::fs::read_to_string(suite().join("scenes").join(format!("{name}.xml"))).unwrap();
    assert!(text.contains("beckmann"));
    let (w, h, reference) = reference(name);
    let (_, _, img) = render_text(name, &text.replace("beckmann", "ggx"));
    let (worst, _) = errors(&img, &reference, w, h);
    assert!(
        worst > 3.0 * TOLERANCE,
        "GGX passed for Beckmann: worst block {worst}"
    );
}
