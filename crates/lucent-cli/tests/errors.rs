//! Bad input through the command line: one line naming file, line, column and cause, a
//! non-zero exit, no panic and no output file.

mod common;

use common::lucent;

const CAMERA: &str = "[camera]\neye = [0, 0, 5]\nlook_at = [0, 0, 0]\n";
const MATERIAL: &str = "[[material]]\nname = \"m\"\nkd = 0.5\n";

/// Renders `scene` from a file named `bad.toml`; returns stderr after checking the failure.
fn refused(scene: &str, args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(&path, scene).unwrap();
    let out = dir.path().join("out.png");
    let output = lucent()
        .current_dir(dir.path())
        .args(["render", "bad.toml", "-o", "out.png"])
        .args(args)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    assert!(!output.status.success(), "accepted: {scene}");
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(
        !stderr.contains("panicked") && !stderr.contains("internal error"),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "one line: {stderr}");
    assert!(!out.exists(), "no image is written on bad input");
    stderr
}

fn sphere(center: &str, radius: &str, material: &str) -> String {
    format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncenter = {center}\nradius = {radius}\nmaterial = \"{material}\"\n"
    )
}

#[test]
fn unknown_key() {
    let e = refused(
        &format!("{CAMERA}{MATERIAL}[[object]]\ntype = \"sphere\"\ncentre = [0, 0, 0]\n"),
        &[],
    );
    assert!(
        e.starts_with("error: bad.toml:9:1: unknown field `centre`"),
        "{e}"
    );
}

#[test]
fn wrong_type() {
    let e = refused(&sphere("[0, 0, 0]", "\"big\"", "m"), &[]);
    assert!(
        e.starts_with(
            "error: bad.toml:10:10: invalid type: string \"big\", expected a finite number"
        ),
        "{e}"
    );
}

#[test]
fn unknown_material() {
    let e = refused(&sphere("[0, 0, 0]", "1", "gold"), &[]);
    assert!(
        e.starts_with("error: bad.toml:11:12: unknown material `gold`"),
        "{e}"
    );
}

#[test]
fn negative_radius() {
    let e = refused(&sphere("[0, 0, 0]", "-2.5", "m"), &[]);
    assert!(
        e.starts_with("error: bad.toml:10:10: a sphere's radius must be positive, got -2.5"),
        "{e}"
    );
}

#[test]
fn zero_normal() {
    let scene = format!(
        "{CAMERA}{MATERIAL}[[object]]\ntype = \"plane\"\npoint = [0, 0, 0]\nnormal = [0, 0, 0]\nmaterial = \"m\"\n"
    );
    let e = refused(&scene, &[]);
    assert!(
        e.starts_with("error: bad.toml:10:10: a plane's normal must not be zero"),
        "{e}"
    );
}

#[test]
fn nan() {
    let e = refused(&sphere("[nan, 0, 0]", "1", "m"), &[]);
    assert!(
        e.starts_with("error: bad.toml:9:11: expected a finite number, found NaN"),
        "{e}"
    );
}

#[test]
fn broken_toml() {
    let e = refused(&format!("{CAMERA}[world\n"), &[]);
    assert!(e.starts_with("error: bad.toml:4:"), "{e}");
}

#[test]
fn missing_scene_file() {
    let output = lucent()
        .args(["render", "no-such-scene.toml"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr.starts_with("error: no-such-scene.toml: no such scene file"),
        "{stderr}"
    );
}

#[test]
fn unknown_output_format() {
    let output = lucent()
        .args(["render", "-o", "picture.gif"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1));
    assert!(
        stderr.contains("picture.gif: unknown image format (use .png, .pfm or .exr)"),
        "{stderr}"
    );
}

#[test]
fn bad_flag_values_are_usage_errors() {
    for args in [
        ["--width", "0"],
        ["--spp", "many"],
        ["--integrator", "radiosity"],
    ] {
        let output = lucent().arg("render").args(args).output().unwrap();
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.starts_with("error: invalid value"), "{stderr}");
    }
}

#[test]
fn info_reports_the_same_errors() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("bad.toml"), sphere("[0, 0, 0]", "-1", "m")).unwrap();
    let output = lucent()
        .current_dir(dir.path())
        .args(["info", "bad.toml"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&output.stderr)
            .starts_with("error: bad.toml:10:10: a sphere's radius must be positive")
    );
}
