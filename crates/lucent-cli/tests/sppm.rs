//! The photon mapper through the command line: the caustic examples render, classic lights are
//! made physical with a warning, what it cannot do is refused, and a stopped render keeps its
//! image.

mod common;

use common::*;
use std::time::Duration;

#[test]
fn the_caustic_examples_render_with_their_caustic() {
    let dir = tempfile::tempdir().unwrap();
    for scene in ["examples/caustic.toml", "examples/cornell-glass.toml"] {
        let out = dir.path().join("out.pfm");
        let output = render_to(
            &workspace().join(scene),
            &["--width", "32", "--height", "24", "--spp", "4"],
            &out,
        );
        assert_success(&output);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!stderr.contains("warning"), "{scene}: {stderr}");
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(stdout.contains("photon "), "{scene}: {stdout}");
        let image = read_pfm(&out);
        assert!(image.pixels.iter().flatten().all(|c| c.is_finite()));
        assert!(image.pixels.iter().flatten().any(|&c| c > 0.0), "{scene}");
    }
}

#[test]
fn a_time_limit_ends_the_photon_mapper_between_iterations() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("c.pfm");
    let output = render_to(
        &workspace().join("examples/caustic.toml"),
        &["--width", "32", "--height", "24", "--time-limit", "0.5"],
        &out,
    );
    assert_success(&output);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("spp in the time limit"), "{stdout}");
    assert!(read_pfm(&out).pixels.iter().flatten().any(|&c| c > 0.0));
}

#[test]
fn classic_lights_fall_off_physically_and_filters_become_the_box() {
    let output = lucent()
        .args([
            "render",
            "--integrator",
            "sppm",
            "--width",
            "16",
            "--height",
            "12",
        ])
        .args(["--spp", "1", "--filter", "gaussian", "-o"])
        .arg(tempfile::tempdir().unwrap().path().join("w.png"))
        .output()
        .unwrap();
    assert_success(&output);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(
        stderr.contains("2 lights without falloff fall off as 1/d² under the sppm integrator"),
        "{stderr}"
    );
    assert!(
        stderr.contains("the gaussian filter is rendered as the box"),
        "{stderr}"
    );
}

#[test]
fn what_photon_mapping_cannot_do_is_refused() {
    let scene = workspace().join("examples/caustic.toml");
    let scene = scene.to_str().unwrap();
    for (args, message) in [
        (
            vec![scene, "--shard", "0/2", "-o", "part.exr"],
            "cannot be split into shards",
        ),
        (
            vec![scene, "--checkpoint-every", "5", "-o", "x.png"],
            "cannot be checkpointed or resumed",
        ),
        (
            vec![scene, "--aa", "adaptive"],
            "need a deterministic integrator",
        ),
    ] {
        let output = lucent().arg("render").args(&args).output().unwrap();
        assert_eq!(output.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains(message), "{args:?}: {stderr}");
    }
}

#[cfg(unix)]
#[test]
fn a_stopped_photon_mapper_writes_its_image() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("caustic.pfm");
    let (output, stopping) = signal_after(
        lucent()
            .arg("render")
            .arg(workspace().join("examples/caustic.toml"))
            .args(["--width", "40", "--height", "30", "--spp", "100000", "-o"])
            .arg(&out),
        Duration::from_millis(800),
        "TERM",
    );
    assert!(stopping < Duration::from_secs(10));
    assert_eq!(output.status.code(), Some(130));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("cannot be resumed"), "{stderr}");
    let image = read_pfm(&out);
    assert!(image.pixels.iter().flatten().any(|&c| c > 0.0));
    assert!(!dir.path().join("caustic.pfm.checkpoint").exists());
}
