//! The path tracer through the command line: every example renders under it, the time limit
//! stops a render with its image written, filters and lenses come from flags and files, and
//! what cannot work together is refused with one clear line.

mod common;

use common::*;

fn render_args(args: &[&str]) -> std::process::Output {
    lucent().arg("render").args(args).output().unwrap()
}

#[test]
fn the_cornell_box_and_the_examples_render_under_the_path_tracer() {
    let dir = tempfile::tempdir().unwrap();
    let root = workspace();
    for (scene, integrator) in [
        ("examples/cornell-box.xml", None),
        ("examples/materials.toml", None),
        ("examples/depth-of-field.toml", None),
        ("examples/whitted.toml", Some("path")),
        ("examples/box-room.toml", Some("path")),
    ] {
        let out = dir.path().join("out.pfm");
        let mut cmd = lucent();
        cmd.arg("render")
            .arg(root.join(scene))
            .args(["--width", "24", "--height", "16", "--spp", "8", "-o"])
            .arg(&out);
        if let Some(i) = integrator {
            cmd.args(["--integrator", i]);
        }
        let output = cmd.output().unwrap();
        assert_success(&output);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!stderr.contains("warning"), "{scene}: {stderr}");
        let image = read_pfm(&out);
        let lit = image
            .pixels
            .iter()
            .filter(|p| p.iter().sum::<f32>() > 0.0)
            .count();
        assert!(lit > image.pixels.len() / 2, "{scene}: {lit} lit pixels");
        assert!(
            image.pixels.iter().flatten().all(|c| c.is_finite()),
            "{scene}"
        );
    }
}

#[test]
fn a_time_limit_ends_the_render_with_its_image() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("box.pfm");
    let started = std::time::Instant::now();
    let output = render_to(
        &workspace().join("examples/cornell-box.xml"),
        &["--width", "32", "--height", "32", "--time-limit", "0.5"],
        &out,
    );
    assert_success(&output);
    // Without --spp the samples are unbounded: only the limit can have ended it. (A loose
    // bound: this checks that the limit stops the render, not how fast lucent is.)
    assert!(started.elapsed().as_secs_f64() < 30.0);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("spp in the time limit"), "{stdout}");
    let image = read_pfm(&out);
    assert!(image.pixels.iter().all(|p| p.iter().all(|c| c.is_finite())));
    // Every pixel got samples: the passes are even.
    let dark = image
        .pixels
        .iter()
        .filter(|p| p.iter().sum::<f32>() == 0.0)
        .count();
    assert!(dark < 8, "{dark} pixels without light");
    // No checkpoint is left: the render is finished.
    assert!(!dir.path().join("box.pfm.checkpoint").exists());

    // However short the limit, the first pass is whole: no pixel is left black.
    let output = render_to(
        &workspace().join("examples/cornell-box.xml"),
        &[
            "--width",
            "16",
            "--height",
            "16",
            "--time-limit",
            "0.000001",
        ],
        &out,
    );
    assert_success(&output);
    let image = read_pfm(&out);
    let dark = image
        .pixels
        .iter()
        .filter(|p| p.iter().sum::<f32>() == 0.0)
        .count();
    assert!(dark < 4, "{dark} black pixels after the shortest limit");

    // With --spp as well, whichever comes first ends it: here the samples.
    let output = render_to(
        &workspace().join("examples/cornell-box.xml"),
        &[
            "--width",
            "16",
            "--height",
            "16",
            "--spp",
            "2",
            "--time-limit",
            "60",
        ],
        &out,
    );
    assert_success(&output);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains(" 2 spp"), "{stdout}");
}

#[test]
fn filters_from_flags_and_files_change_the_image_not_its_mean() {
    let scene = workspace().join("examples/cornell-box.xml");
    let dir = tempfile::tempdir().unwrap();
    let mut images = Vec::new();
    for filter in ["box", "tent", "gaussian", "mitchell"] {
        let out = dir.path().join(format!("{filter}.pfm"));
        let output = lucent()
            .arg("render")
            .arg(&scene)
            .args(["--width", "32", "--height", "32", "--spp", "64"])
            .args(["--filter", filter, "-o"])
            .arg(&out)
            .output()
            .unwrap();
        assert_success(&output);
        images.push(read_pfm(&out));
    }
    let mean = |i: &Image| i.pixels.iter().flatten().sum::<f32>() / (i.pixels.len() * 3) as f32;
    for i in &images[1..] {
        assert_ne!(i.pixels, images[0].pixels);
        assert!((mean(i) - mean(&images[0])).abs() < 0.05 * mean(&images[0]));
    }
}

#[test]
fn what_cannot_work_together_is_refused() {
    let scene = workspace().join("examples/cornell-box.xml");
    let scene = scene.to_str().unwrap();
    for (args, message) in [
        (
            vec![scene, "--aa", "adaptive"],
            "need a deterministic integrator",
        ),
        (
            vec![scene, "--aa", "adaptive", "--time-limit", "2"],
            "--time-limit needs uniform sampling",
        ),
        (vec![scene, "--time-limit", "0"], "invalid value"),
        (
            vec![scene, "--shard", "0/2", "-o", "part.exr"],
            "--shard needs every sample kept in its own pixel",
        ),
    ] {
        let output = render_args(&args);
        assert!(!output.status.success(), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(
            stderr.lines().next().unwrap().contains(message),
            "{args:?}: {stderr}"
        );
    }

    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("lens.toml");
    std::fs::write(
        &path,
        "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\nfocus_distance = 3\n",
    )
    .unwrap();
    let output = render_args(&[path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("lens.toml:1:1: `focus_distance` needs an `aperture`"),
        "{stderr}"
    );
}
