//! The path tracer against Mitsuba 3 on the Cornell box: the scene file lucent ships
//! (`examples/cornell-box.xml`, Mitsuba's own `cbox`) rendered at 64 × 64 converges to
//! Mitsuba 3.9.1's image of it (`llvm_ad_rgb`, 65,536 samples per pixel, made by
//! `bench/peers/run.sh refs`; its own noise against a second seed is a relative MSE of
//! about 1e-5).
//!
//! Metric: relative MSE over every pixel and channel, `mean((a − b)² / (b² + 0.01))`, the one
//! `bench/peers/mitsuba.py` reports. Tolerance: below 1e-3 (the acceptance figure); at 1024
//! samples per pixel lucent's own noise is about a fifth of that.

use lucent::render::{Hooks, RenderSettings, render};
use lucent_scene::{LoadOptions, SceneFile, Spanned};
use std::path::{Path, PathBuf};

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A little-endian RGB Portable Float Map, rows from the top.
fn read_pfm(path: &Path) -> (u32, u32, Vec<[f32; 3]>) {
    let bytes = std::fs::read(path).unwrap();
    let mut fields = Vec::new();
    let mut start = 0;
    while fields.len() < 4 {
        let end = start
            + bytes[start..]
                .iter()
                .position(|b| b.is_ascii_whitespace())
                .unwrap();
        if end > start {
            fields.push(String::from_utf8(bytes[start..end].to_vec()).unwrap());
        }
        start = end + 1;
    }
    assert_eq!(fields[0], "PF");
    let (w, h): (u32, u32) = (fields[1].parse().unwrap(), fields[2].parse().unwrap());
    assert!(fields[3].parse::<f32>().unwrap() < 0.0, "little-endian");
    let data = &bytes[start..];
    let mut rows = vec![[0.0f32; 3]; (w * h) as usize];
    for y in 0..h as usize {
        for x in 0..w as usize {
            let i = ((y * w as usize) + x) * 12;
            let c =
                |k: usize| f32::from_le_bytes(data[i + 4 * k..i + 4 * k + 4].try_into().unwrap());
            // PFM rows run from the bottom.
            rows[(h as usize - 1 - y) * w as usize + x] = [c(0), c(1), c(2)];
        }
    }
    (w, h, rows)
}

#[test]
fn the_cornell_box_converges_to_mitsubas_image() {
    let root = workspace();
    let (w, h, reference) =
        read_pfm(&root.join("crates/lucent-scene/tests/data/cbox-64-mitsuba.pfm"));
    let mut file = SceneFile::read_with(
        &root.join("examples/cornell-box.xml"),
        &LoadOptions::default(),
    )
    .unwrap();
    file.desc.image.width = Spanned::new(0..0, w);
    file.desc.image.height = Spanned::new(0..0, h);
    file.desc.image.samples = Spanned::new(0..0, 1024);
    let loaded = file.build().unwrap();
    assert!(loaded.warnings.is_empty(), "{:#?}", loaded.warnings);
    let hooks = Hooks::none();
    let settings = RenderSettings {
        seed: 11,
        ..loaded.settings
    };
    let film = render(&loaded.scene, &settings, None, &hooks).unwrap().film;
    let mut rel = 0.0f64;
    let mut light = 0.0f32;
    for y in 0..h {
        for x in 0..w {
            let a = film.pixel(x, y).to_array();
            let b = reference[(y * w + x) as usize];
            light = light.max(b[0]);
            for c in 0..3 {
                let d = f64::from(a[c] - b[c]);
                rel += d * d / (f64::from(b[c]) * f64::from(b[c]) + 0.01);
            }
        }
    }
    rel /= f64::from(w * h * 3);
    assert!(light > 10.0, "the reference shows the light: {light}");
    assert!(rel < 1e-3, "relative MSE {rel:.3e} against Mitsuba 3");
    println!("relative MSE against Mitsuba 3 at 1024 spp: {rel:.3e}");
}
