//! `lucent explain`: the ray tree of a pixel, its contributions adding up to the pixel.

mod common;

use common::{assert_success, lucent, read_pfm};

/// The three numbers after `label` in `text`.
fn triple(text: &str, label: &str) -> [f32; 3] {
    let line = text.lines().find(|l| l.starts_with(label)).unwrap();
    let v: Vec<f32> = line[label.len()..]
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    [v[0], v[1], v[2]]
}

fn explain(dir: &std::path::Path, args: &[&str]) -> String {
    let output = lucent()
        .current_dir(dir)
        .arg("explain")
        .args(args)
        .output()
        .unwrap();
    assert_success(&output);
    String::from_utf8(output.stdout).unwrap()
}

#[test]
fn the_glass_sphere_shows_a_refracted_chain_that_adds_up_to_the_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let size = ["--width", "80", "--height", "60"];
    // Pixel (19, 31) of the default scene at 80×60 sees the glass sphere.
    let mut args = vec!["--pixel", "19,31", "--svg", "tree.svg"];
    args.extend(size);
    let text = explain(dir.path(), &args);
    // Into the glass, through it and out: refracted rays entering and leaving object #2.
    assert!(text.contains("camera ray"), "{text}");
    let entering = text.find("hits object #2 (material #2) at t").unwrap();
    assert!(text[entering..].contains("entering"));
    let refracted = text.find("refracted ray").unwrap();
    assert!(text[refracted..].contains("leaving its surface"), "{text}");
    let sum = triple(&text, "sum of contributions:");
    let value = triple(&text, "pixel value:");
    for c in 0..3 {
        assert!((sum[c] - value[c]).abs() <= 1e-5, "{sum:?} {value:?}");
    }
    // The same value as the render's pixel.
    let mut render = vec!["render", "-o", "image.pfm"];
    render.extend(size);
    assert_success(
        &lucent()
            .current_dir(dir.path())
            .args(&render)
            .output()
            .unwrap(),
    );
    let rendered = read_pfm(&dir.path().join("image.pfm")).at(19, 31);
    for c in 0..3 {
        assert!(
            (rendered[c] - value[c]).abs() <= 1e-6,
            "{rendered:?} {value:?}"
        );
    }
    let svg = std::fs::read_to_string(dir.path().join("tree.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.matches("refracted ray").count() >= 2);
}

#[test]
fn total_internal_reflection_is_marked() {
    // Under a glass surface, looking up at a grazing angle: past the critical angle (41.8°
    // for glass to air) the ray cannot leave, and its transmitted share is reflected.
    let scene = r#"
        [image]
        width = 9
        height = 9
        [camera]
        eye = [0, -1, 5]
        look_at = [0, -0.8, 0]
        fov = 10
        [world]
        background = [0.2, 0.4, 0.8]
        [[material]]
        name = "glass"
        kt = 0.9
        kr = 0.05
        ior = 1.5
        [[material]]
        name = "floor"
        kd = 0.5
        [[object]]
        type = "plane"
        point = [0, 0, 0]
        normal = [0, 1, 0]
        material = "glass"
        [[object]]
        type = "plane"
        point = [0, -3, 0]
        normal = [0, 1, 0]
        material = "floor"
        [[light]]
        type = "directional"
        direction = [0, -1, 0]
    "#;
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tir.toml"), scene).unwrap();
    let text = explain(dir.path(), &["tir.toml", "--pixel", "4,4"]);
    assert!(text.contains("leaving its surface"), "{text}");
    assert!(text.contains("total internal reflection"), "{text}");
    let (sum, value) = (
        triple(&text, "sum of contributions:"),
        triple(&text, "pixel value:"),
    );
    for c in 0..3 {
        assert!((sum[c] - value[c]).abs() <= 1e-5, "{sum:?} {value:?}");
    }
}

#[test]
fn bad_requests_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    for args in [
        &["explain", "--pixel", "800,10"][..],
        &["explain", "--pixel", "3"],
        &["explain", "--pixel", "1,1", "--integrator", "raycast"],
        &["explain", "--pixel", "1,1", "--aa", "adaptive"],
    ] {
        let output = lucent()
            .current_dir(dir.path())
            .args(args)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success(), "{args:?}");
        assert!(stderr.contains("error"), "{stderr}");
        assert!(!stderr.contains("panicked"), "{stderr}");
    }
}

#[test]
fn one_sample_of_many_is_explained_on_request() {
    let dir = tempfile::tempdir().unwrap();
    let output = lucent()
        .current_dir(dir.path())
        .args(["explain", "--pixel", "10,10", "--spp", "100"])
        .output()
        .unwrap();
    assert!(!output.status.success());
    assert!(String::from_utf8_lossy(&output.stderr).contains("--sample K"));
    let text = explain(
        dir.path(),
        &["--pixel", "10,10", "--spp", "100", "--sample", "99"],
    );
    assert!(text.contains("sample 99, through"), "{text}");
    assert_eq!(text.matches("camera ray").count(), 1);
    let value = triple(&text, "sample value:");
    // Pixel (10, 10) sees the sky: the background.
    assert!((value[2] - 0.85).abs() < 1e-6, "{value:?}");
}
