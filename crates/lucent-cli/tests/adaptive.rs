//! `--aa adaptive` through the command line: the density map, the flags' checks, and shards
//! that merge into the very image of a whole render.

mod common;

use common::{assert_success, lucent, read_pfm};
use std::path::Path;

fn run(dir: &Path, args: &[&str]) -> std::process::Output {
    lucent().current_dir(dir).args(args).output().unwrap()
}

const SMALL: [&str; 4] = ["--width", "40", "--height", "30"];

#[test]
fn the_density_map_shows_where_the_corners_went() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let grey = |threshold: &str| {
        let mut args = vec!["render", "-o", "a.pfm", "--aa", "adaptive"];
        args.extend(SMALL);
        args.extend(["--aa-threshold", threshold, "--density-map", "map.png"]);
        let output = run(d, &args);
        assert_success(&output);
        let stdout = String::from_utf8_lossy(&output.stdout).to_string();
        assert!(stdout.contains("corner rays per pixel"), "{stdout}");
        let map = image::open(d.join("map.png")).unwrap().to_luma8();
        assert_eq!(map.dimensions(), (40, 30));
        map.into_raw()
    };
    // Threshold 0 splits every pixel to the depth limit: all white; infinity none: all black.
    assert!(grey("0").iter().all(|&v| v == 255));
    assert!(grey("inf").iter().all(|&v| v == 0));
    // In between, the edges of the default scene's spheres and checks are split, not the sky.
    let map = grey("0.1");
    let split = map.iter().filter(|&&v| v > 0).count();
    assert!(split > 40 && split < map.len() * 3 / 4, "{split}");
    assert_eq!(map[0], 0, "the sky's corner is not split");
}

#[test]
fn adaptive_settings_need_adaptive_sampling() {
    let dir = tempfile::tempdir().unwrap();
    for args in [
        &["render", "--aa-threshold", "0.1"][..],
        &["render", "--aa-depth", "2"],
        &["render", "--density-map", "m.png"],
        &["render", "--aa", "adaptive", "--density-map", "m.exr"],
        &["render", "--aa", "adaptive", "--aa-depth", "9"],
        &["render", "--aa", "adaptive", "--aa-threshold", "-1"],
        &["render", "--aa-block", "2"],
        &["render", "--aa", "adaptive", "--aa-block", "2"],
        &["render", "--aa", "quadtree", "--aa-block", "5"],
        &["render", "--aa", "adaptive", "--spp", "4"],
        &["render", "--no-shadows", "--integrator", "raycast"],
    ] {
        let output = run(dir.path(), args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{args:?}");
        assert!(stderr.starts_with("error"), "{args:?}: {stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(!dir.path().join("render.png").exists());
    }
}

#[test]
fn a_quadtree_render_takes_fewer_rays_than_adaptive() {
    let dir = tempfile::tempdir().unwrap();
    let rays = |aa: &str| {
        let mut args = vec![
            "render",
            "-o",
            "q.pfm",
            "--aa",
            aa,
            "--density-map",
            "q.png",
        ];
        args.extend(SMALL);
        let output = run(dir.path(), &args);
        assert_success(&output);
        let stdout = String::from_utf8_lossy(&output.stdout).to_string();
        let camera = stdout.split("(camera ").nth(1).unwrap();
        camera.split(',').next().unwrap().parse::<u64>().unwrap()
    };
    let (quadtree, adaptive) = (rays("quadtree"), rays("adaptive"));
    assert!(quadtree < adaptive, "{quadtree} {adaptive}");
}

#[test]
fn adaptive_shards_merge_into_the_whole_image() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let with = |extra: &[&str]| {
        let mut args = vec!["render", "--aa", "adaptive", "--aa-depth", "2"];
        args.extend(SMALL);
        args.extend(extra);
        assert_success(&run(d, &args));
    };
    with(&["-o", "whole.pfm"]);
    with(&["--shard", "0/2", "-o", "p0.exr", "--threads", "1"]);
    with(&["--shard", "1/2", "-o", "p1.exr"]);
    assert_success(&run(d, &["merge", "p0.exr", "p1.exr", "-o", "merged.pfm"]));
    assert_eq!(
        read_pfm(&d.join("merged.pfm")),
        read_pfm(&d.join("whole.pfm"))
    );
    // The sampling is part of what a shard must share with the others.
    let mut uniform = vec!["render", "--shard", "1/2", "-o", "uniform.exr"];
    uniform.extend(SMALL);
    assert_success(&run(d, &uniform));
    let output = run(d, &["merge", "p0.exr", "uniform.exr", "-o", "x.pfm"]);
    assert!(!output.status.success());
}

/// Root-mean-square difference over every channel of two images.
fn rmse(a: &common::Image, b: &common::Image) -> f64 {
    let sum: f64 = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .flat_map(|(p, q)| (0..3).map(move |c| f64::from(p[c] - q[c]).powi(2)))
        .sum();
    (sum / (3 * a.pixels.len()) as f64).sqrt()
}

#[test]
fn adaptive_matches_sixteen_samples_with_fewer_rays() {
    // The default scene at 200×150 against a 256-spp reference: adaptive sampling at its
    // defaults is as close as 16 uniform samples per pixel, with fewer than half the camera
    // rays (at 800×600, where edges are sparser, a quarter: see docs/performance.md).
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let render = |extra: &[&str], out: &str| -> (common::Image, f64) {
        let mut args = vec!["render", "--width", "200", "--height", "150", "-o", out];
        args.extend(extra);
        let output = run(d, &args);
        assert_success(&output);
        let stdout = String::from_utf8_lossy(&output.stdout).to_string();
        let camera = stdout.split("(camera ").nth(1).unwrap();
        let camera: f64 = camera.split(',').next().unwrap().parse().unwrap();
        (read_pfm(&d.join(out)), camera / (200.0 * 150.0))
    };
    let (reference, _) = render(&["--spp", "256", "--seed", "7"], "ref.pfm");
    let (uniform, per_pixel) = render(&["--spp", "16"], "u16.pfm");
    assert_eq!(per_pixel, 16.0);
    let (adaptive, rays) = render(&["--aa", "adaptive"], "a.pfm");
    let (e_uniform, e_adaptive) = (rmse(&uniform, &reference), rmse(&adaptive, &reference));
    assert!(
        e_adaptive <= 1.05 * e_uniform,
        "{e_adaptive} vs {e_uniform}"
    );
    assert!(rays < 8.0, "{rays} camera rays per pixel");
    // Four uniform samples per pixel, about as many camera rays, are far worse.
    let (plain, _) = render(&["--spp", "4", "--seed", "9"], "u4.pfm");
    assert!(rmse(&plain, &reference) > 2.0 * e_adaptive);
}

#[test]
fn the_aa_flag_overrides_a_scene_files_sampling() {
    let dir = tempfile::tempdir().unwrap();
    let scene = "[image]\nwidth = 16\nheight = 12\n[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n\
                 [render]\naa = \"quadtree\"\naa_block = 2\naa_threshold = 0.05\n";
    std::fs::write(dir.path().join("s.toml"), scene).unwrap();
    for aa in ["uniform", "adaptive", "quadtree"] {
        let output = run(dir.path(), &["render", "s.toml", "--aa", aa, "-o", "x.png"]);
        assert_success(&output);
    }
    let output = run(
        dir.path(),
        &["explain", "s.toml", "--pixel", "1,1", "--aa", "uniform"],
    );
    assert_success(&output);
}
