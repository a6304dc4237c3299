//! `--up` and `--view`, the framing of scenes without a camera: a model turned to any up axis
//! and framed with that axis renders as the +y original (camera and light turned alike), the
//! flags' errors list the choices, the up axis guessed for a mesh file is a note, a scene with
//! its own camera keeps it with a warning, and `lucent convert` writes the chosen framing.

mod common;

use common::{Image, assert_success, lucent, read_pfm};
use std::path::{Path, PathBuf};
use std::process::Output;

const AXES: [&str; 6] = ["x", "y", "z", "-x", "-y", "-z"];
const VIEWS: [&str; 4] = ["front", "side", "top", "iso"];

/// The model frame (right, up, back) of each of [`AXES`], as docs/import.md gives it: a +y up
/// point `(x, y, z)` of the model is `x·right + y·up + z·back` in a file with that up axis.
fn frame(axis: &str) -> [[f32; 3]; 3] {
    let (x, y, z) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    let neg = |v: [f32; 3]| v.map(|c: f32| -c);
    match axis {
        "y" => [x, y, z],
        "z" => [x, z, neg(y)],
        "-y" => [x, neg(y), neg(z)],
        "-z" => [x, neg(z), y],
        "x" => [neg(y), x, z],
        "-x" => [y, neg(x), z],
        _ => unreachable!(),
    }
}

/// An octahedron: no face of it is near flat, so no flat base shows the up axis.
fn diamond(obj: &mut Vec<[f32; 3]>, faces: &mut Vec<[usize; 3]>, c: [f32; 3], h: [f32; 3]) {
    let n = obj.len();
    for i in 0..6 {
        let mut p = c;
        p[i % 3] += if i < 3 { h[i % 3] } else { -h[i % 3] };
        obj.push(p);
    }
    for x in [0, 3] {
        for y in [1, 4] {
            for z in [2, 5] {
                // Outward winding: an odd number of negative corners flips it.
                let flip = (x == 3) ^ (y == 4) ^ (z == 5);
                let t = if flip { [x, z, y] } else { [x, y, z] };
                faces.push(t.map(|i| n + i));
            }
        }
    }
}

/// A lopsided figure, +y up, facing +z, standing clear of the origin: a body, a head to the
/// front right and a tail behind, so that every view and every turn shows differently.
fn figure() -> (Vec<[f32; 3]>, Vec<[usize; 3]>) {
    let (mut p, mut f) = (Vec::new(), Vec::new());
    diamond(&mut p, &mut f, [0.3, 1.2, -0.4], [0.6, 1.0, 0.4]);
    diamond(&mut p, &mut f, [0.9, 2.0, 0.2], [0.3, 0.35, 0.3]);
    diamond(&mut p, &mut f, [-0.2, 0.6, -1.1], [0.15, 0.2, 0.5]);
    (p, f)
}

/// Writes `points` and `faces` as an OBJ file at `path`, each point turned to `axis` up.
fn write_obj(path: &Path, points: &[[f32; 3]], faces: &[[usize; 3]], axis: &str) {
    let [r, u, b] = frame(axis);
    let mut text = String::new();
    for p in points {
        let q: [f32; 3] = std::array::from_fn(|i| p[0] * r[i] + p[1] * u[i] + p[2] * b[i]);
        text += &format!("v {} {} {}\n", q[0], q[1], q[2]);
    }
    for t in faces {
        text += &format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    std::fs::write(path, text).unwrap();
}

fn run(args: &[&str], scene: &Path) -> Output {
    lucent().args(args).arg(scene).output().unwrap()
}

/// Renders `scene` at 64×48 with `args` and reads the image.
fn render(scene: &Path, args: &[&str]) -> (Image, String) {
    let out = scene.with_extension(format!("{}.pfm", args.join("_").replace('-', "m")));
    let output = lucent()
        .arg("render")
        .arg(scene)
        .args(["--width", "64", "--height", "48", "-o"])
        .arg(&out)
        .args(args)
        .output()
        .unwrap();
    assert_success(&output);
    (
        read_pfm(&out),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// The share of pixels that differ by more than 1 % in a channel.
fn differing(a: &Image, b: &Image) -> f32 {
    assert_eq!((a.width, a.height), (b.width, b.height));
    let n = a
        .pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(p, q)| (0..3).any(|c| (p[c] - q[c]).abs() > 0.01 * p[c].abs().max(0.01)))
        .count();
    n as f32 / a.pixels.len() as f32
}

/// The rows and columns the model covers (pixels other than the corner's background).
fn covered(img: &Image) -> (usize, usize) {
    let bg = img.at(0, 0);
    let rows = (0..img.height)
        .filter(|&y| (0..img.width).any(|x| img.at(x, y) != bg))
        .count();
    let cols = (0..img.width)
        .filter(|&x| (0..img.height).any(|y| img.at(x, y) != bg))
        .count();
    (rows, cols)
}

#[test]
fn a_model_turned_to_any_up_axis_renders_as_the_original_in_every_view() {
    let dir = tempfile::tempdir().unwrap();
    let (points, faces) = figure();
    let original = dir.path().join("y.obj");
    write_obj(&original, &points, &faces, "y");
    for view in VIEWS {
        let (want, _) = render(&original, &["--view", view]);
        let (rows, cols) = covered(&want);
        assert!(rows > 10 && cols > 10, "{view}: the figure shows");
        for axis in AXES {
            let turned = dir.path().join(format!("{}.obj", axis.replace('-', "neg")));
            write_obj(&turned, &points, &faces, axis);
            let up = format!("--up={axis}");
            let (got, _) = render(&turned, &[&up, "--view", view]);
            // The same picture, lit alike, up to rounding at a few edges.
            let share = differing(&want, &got);
            assert!(
                share < 0.01,
                "--up {axis} --view {view}: {share} of the pixels differ"
            );
        }
    }
    // The views differ from each other.
    let images: Vec<Image> = VIEWS
        .iter()
        .map(|v| render(&original, &["--view", v]).0)
        .collect();
    for i in 0..4 {
        for j in i + 1..4 {
            assert!(differing(&images[i], &images[j]) > 0.05, "{i} and {j}");
        }
    }
}

#[test]
fn up_turns_the_view_of_a_tall_model() {
    let dir = tempfile::tempdir().unwrap();
    // A spire along z, off the origin: no clue to its up axis, so +y is kept and it is seen
    // end on; with --up z it stands tall.
    let (mut p, mut f) = (Vec::new(), Vec::new());
    diamond(&mut p, &mut f, [2.0, 2.0, 5.0], [0.3, 0.3, 3.0]);
    let spire = dir.path().join("spire.obj");
    write_obj(&spire, &p, &f, "y");
    let (rows, cols) = covered(&render(&spire, &[]).0);
    assert!(rows.abs_diff(cols) <= 2, "end on: {rows}×{cols}");
    let (rows, cols) = covered(&render(&spire, &["--up", "z"]).0);
    assert!(rows > 4 * cols, "standing: {rows}×{cols}");
    let (rows, cols) = covered(&render(&spire, &["--up", "+Z", "--view", "top"]).0);
    assert!(rows.abs_diff(cols) <= 2, "from above: {rows}×{cols}");
    let (rows, cols) = covered(&render(&spire, &["--up", "-z", "--view", "side"]).0);
    assert!(rows > 4 * cols, "upside down, from the side: {rows}×{cols}");
}

#[test]
fn bad_axes_and_views_are_refused_with_the_choices() {
    let dir = tempfile::tempdir().unwrap();
    let model = dir.path().join("m.obj");
    let (p, f) = figure();
    write_obj(&model, &p, &f, "y");
    for command in ["render", "info", "convert", "view", "explain"] {
        for (flag, value, choices) in [
            ("--up", "w", "[possible values: x, y, z, -x, -y, -z]"),
            (
                "--view",
                "below",
                "[possible values: front, side, top, iso]",
            ),
        ] {
            let output = lucent()
                .args([command, flag, value])
                .arg(&model)
                .output()
                .unwrap();
            let stderr = String::from_utf8_lossy(&output.stderr);
            assert_eq!(output.status.code(), Some(2), "{command}: {stderr}");
            let placeholder = if flag == "--up" { "<AXIS>" } else { "<VIEW>" };
            assert!(
                stderr.starts_with(&format!(
                    "error: invalid value '{value}' for '{flag} {placeholder}'"
                )),
                "{command}: {stderr}"
            );
            assert!(stderr.contains(choices), "{command}: {stderr}");
        }
    }
    // Signs, either case, and a negative axis after a space all parse.
    for up in ["-z", "+z", "Z", "-X", "+Y"] {
        let output = run(&["info", "--up", up], &model);
        assert_success(&output);
    }
}

#[test]
fn the_guessed_up_axis_is_a_note_unless_up_is_given() {
    let dir = tempfile::tempdir().unwrap();
    let (p, f) = figure();
    let plain = dir.path().join("plain.obj");
    write_obj(&plain, &p, &f, "y");
    let output = run(&["info"], &plain);
    assert_success(&output);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(
        stderr.trim_end(),
        format!(
            "note: {}: up axis taken as +y, the default (neither a flat base nor a ground at the origin says otherwise); --up to choose another",
            plain.display()
        )
    );
    let output = run(&["info", "--up", "y"], &plain);
    assert_success(&output);
    assert!(output.stderr.is_empty(), "{output:?}");

    // Standing on the origin, turned to +z up: guessed, said, and drawn as the +y original.
    let mut grounded = Vec::new();
    let mut f = Vec::new();
    diamond(&mut grounded, &mut f, [0.0, 1.0, 0.0], [0.5, 1.0, 0.4]);
    diamond(&mut grounded, &mut f, [0.4, 1.7, 0.3], [0.2, 0.2, 0.2]);
    let y_up = dir.path().join("grounded-y.obj");
    let z_up = dir.path().join("grounded-z.obj");
    write_obj(&y_up, &grounded, &f, "y");
    write_obj(&z_up, &grounded, &f, "z");
    let (want, note) = render(&y_up, &[]);
    assert!(note.contains("up axis taken as +y (it stands on the plane y = 0"));
    let (got, note) = render(&z_up, &[]);
    assert_eq!(
        note.trim_end(),
        format!(
            "note: {}: up axis guessed as +z (it stands on the plane z = 0, centred over the origin); --up y to override",
            z_up.display()
        )
    );
    assert!(differing(&want, &got) < 0.01);
    let (overridden, note) = render(&z_up, &["--up", "y"]);
    assert!(note.is_empty(), "{note}");
    assert!(differing(&want, &overridden) > 0.05, "--up y overrides");
}

#[test]
fn a_scene_with_its_own_camera_keeps_it_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let scene = common::workspace().join("examples/whitted.toml");
    let out = |name: &str| dir.path().join(name);
    let args = ["--width", "32", "--height", "24"];
    let plain = lucent()
        .arg("render")
        .arg(&scene)
        .args(args)
        .arg("-o")
        .arg(out("a.pfm"))
        .output()
        .unwrap();
    assert_success(&plain);
    let flagged = lucent()
        .arg("render")
        .arg(&scene)
        .args(args)
        .args(["--up", "z", "--view", "top", "-o"])
        .arg(out("b.pfm"))
        .output()
        .unwrap();
    assert_success(&flagged);
    assert_eq!(
        String::from_utf8_lossy(&flagged.stderr).trim_end(),
        "warning: --up and --view have no effect: the scene has its own camera (they frame scenes without one)"
    );
    assert_eq!(read_pfm(&out("a.pfm")), read_pfm(&out("b.pfm")));
    // The built-in scene too, and `convert`.
    let output = lucent().args(["info", "--view", "iso"]).output().unwrap();
    assert_success(&output);
    assert!(String::from_utf8_lossy(&output.stderr).contains("--up and --view have no effect"));
    let output = lucent()
        .arg("convert")
        .arg(&scene)
        .arg(out("c.toml"))
        .args(["--up", "x"])
        .output()
        .unwrap();
    assert_success(&output);
    assert!(String::from_utf8_lossy(&output.stderr).contains("--up and --view have no effect"));
}

#[test]
fn convert_writes_the_chosen_framing() {
    let dir = tempfile::tempdir().unwrap();
    let (p, f) = figure();
    let model = dir.path().join("m.obj");
    write_obj(&model, &p, &f, "-x");
    let toml: PathBuf = dir.path().join("out/m.toml");
    std::fs::create_dir_all(toml.parent().unwrap()).unwrap();
    let output = lucent()
        .arg("convert")
        .arg(&model)
        .arg(&toml)
        .args(["--up", "-x", "--view", "iso"])
        .output()
        .unwrap();
    assert_success(&output);
    let (want, _) = render(&model, &["--up", "-x", "--view", "iso"]);
    let (got, note) = render(&toml, &[]);
    assert!(note.is_empty(), "a TOML scene has its camera: {note}");
    assert_eq!(want, got);
    let text = std::fs::read_to_string(&toml).unwrap();
    // The light turned with the camera.
    assert!(text.contains("type = \"directional\""), "{text}");
    assert!(!text.contains("direction = [0.4, -0.6, -0.7]"), "{text}");
    // From the front, −x up: the camera's up is −x, as written.
    let output = lucent()
        .arg("convert")
        .arg(&model)
        .arg(&toml)
        .args(["--up", "-x"])
        .output()
        .unwrap();
    assert_success(&output);
    let text = std::fs::read_to_string(&toml).unwrap();
    assert!(text.contains("up = [-1.0, 0.0, 0.0]"), "{text}");
    assert!(text.contains("direction = [0.6, 0.4, -0.7]"), "{text}");
}

#[test]
fn a_z_up_teapot_is_guessed_and_drawn_as_the_original() {
    let teapot = lucent_scene::data_dir().join("meshes/teapot.obj");
    if !teapot.is_file() {
        eprintln!("skipping: {} is not here", teapot.display());
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let original = dir.path().join("teapot.obj");
    std::fs::copy(&teapot, &original).unwrap();
    // Newell's own coordinates: z up, the spout along +x.
    let mut turned = String::new();
    for line in std::fs::read_to_string(&teapot).unwrap().lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        match words.as_slice() {
            [kind @ ("v" | "vn"), x, y, z, ..] => {
                let z: f32 = z.parse().unwrap();
                turned += &format!("{kind} {x} {} {y}\n", -z);
            }
            _ => turned += &format!("{line}\n"),
        }
    }
    let z_up = dir.path().join("teapot-z.obj");
    std::fs::write(&z_up, turned).unwrap();
    let (want, note) = render(&original, &[]);
    assert!(note.contains("up axis taken as +y ("), "{note}");
    let (got, note) = render(&z_up, &[]);
    assert!(
        note.contains("up axis guessed as +z (it stands on the plane z = 0, centred over the origin; a flat base at its lowest z); --up y to override"),
        "{note}"
    );
    assert!(differing(&want, &got) < 0.01);
}
