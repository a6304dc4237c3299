//! The command line's normal paths: formats, statistics, info, Ctrl-C.

mod common;

#[cfg(unix)]
use common::signal_after;
use common::{assert_success, lucent, read_pfm, workspace};

#[test]
fn writes_png_pfm_and_exr_of_the_same_image() {
    let dir = tempfile::tempdir().unwrap();
    for name in ["a.png", "a.pfm", "a.exr"] {
        let out = dir.path().join(name);
        let output = lucent()
            .args(["render", "--width", "40", "--height", "30", "-o"])
            .arg(&out)
            .output()
            .unwrap();
        assert_success(&output);
        assert!(out.is_file(), "{name}");
    }
    let pfm = read_pfm(&dir.path().join("a.pfm"));
    let exr = image::open(dir.path().join("a.exr")).unwrap().to_rgb32f();
    let png = image::open(dir.path().join("a.png")).unwrap().to_rgb8();
    assert_eq!((pfm.width, pfm.height), (40, 30));
    for y in 0..30 {
        for x in 0..40 {
            let p = pfm.at(x, y);
            assert_eq!(
                exr.get_pixel(x as u32, y as u32).0,
                p,
                "EXR and PFM hold the same floats"
            );
            let encoded = p.map(lucent::film::tonemap::srgb8);
            assert_eq!(
                png.get_pixel(x as u32, y as u32).0,
                encoded,
                "PNG is the sRGB encoding"
            );
        }
    }
    // No temporary files are left behind.
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 3);
}

#[test]
fn prints_one_statistics_line() {
    let dir = tempfile::tempdir().unwrap();
    let output = lucent()
        .current_dir(dir.path())
        .args([
            "render",
            "--width",
            "80",
            "--height",
            "60",
            "--threads",
            "2",
        ])
        .output()
        .unwrap();
    assert_success(&output);
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    for part in [
        "render.png: 80×60, 1 spp",
        "camera 4800",
        "shadow ",
        "reflected ",
        "refracted ",
        "Mrays/s",
        "2 threads",
    ] {
        assert!(stdout.contains(part), "`{part}` missing from: {stdout}");
    }
    // No progress bar when stderr is not a terminal.
    assert!(
        output.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(dir.path().join("render.png").is_file());
}

#[test]
fn same_image_on_1_2_and_8_threads_and_the_seed_matters() {
    let dir = tempfile::tempdir().unwrap();
    let render = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let output = lucent()
            .args(["render", "--width", "48", "--height", "32", "-o"])
            .arg(&out)
            .args(extra)
            .output()
            .unwrap();
        assert_success(&output);
        read_pfm(&out)
    };
    let one = render("1.pfm", &["--threads", "1", "--spp", "4"]);
    assert_eq!(one, render("2.pfm", &["--threads", "2", "--spp", "4"]));
    assert_eq!(one, render("8.pfm", &["--threads", "8", "--spp", "4"]));
    assert_ne!(
        one,
        render("s.pfm", &["--threads", "2", "--spp", "4", "--seed", "7"])
    );
}

#[test]
fn info_counts_the_default_scene() {
    let output = lucent().arg("info").output().unwrap();
    assert_success(&output);
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(
        stdout.contains("objects:     3 (2 spheres, 1 planes, 0 mesh instances of 0 meshes, 0 exact solids, 0 combinations)"),
        "{stdout}"
    );
    assert!(stdout.contains("lights:      2"), "{stdout}");
    assert!(stdout.contains("materials:   3"), "{stdout}");
    assert!(stdout.contains("bounds:      ["), "{stdout}");
}

#[test]
fn info_states_a_photometric_lights_flux() {
    let scene = workspace().join("examples/street-lamp.toml");
    let output = lucent().arg("info").arg(&scene).output().unwrap();
    assert_success(&output);
    let stdout = String::from_utf8(output.stdout).unwrap();
    let line = stdout
        .lines()
        .find(|l| l.starts_with("photometric: 1 (type C), "))
        .unwrap_or_else(|| panic!("{stdout}"));
    // The table integrated independently (bilinear, a 0.25° grid, outside lucent): 6,382 lm.
    let lumens: f32 = line
        .split(", ")
        .nth(1)
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert!((lumens - 6382.0).abs() < 64.0, "{line}");
}

#[test]
fn info_states_lights_from_images_and_the_shutter() {
    let info = |scene: &str, extra: &[&str]| {
        let output = lucent()
            .arg("info")
            .arg(workspace().join(scene))
            .args(extra)
            .output()
            .unwrap();
        assert_success(&output);
        String::from_utf8(output.stdout).unwrap()
    };
    let projector = info("examples/projector.toml", &[]);
    assert!(
        projector.contains("image light: 2 (projection 192×144; textured spot 128×128), flux "),
        "{projector}"
    );
    let lantern = info("examples/lantern.toml", &[]);
    assert!(
        lantern.contains("image light: 1 (goniometric, lat-long 1024×512)"),
        "{lantern}"
    );
    let car = info("examples/passing-car.toml", &[]);
    assert!(
        car.contains(
            "11 objects move, the camera stands still (blurred over the shutter, t = 0 to 0.04 s;"
        ),
        "{car}"
    );
    let instant = info("examples/passing-car.toml", &["--time", "0.01"]);
    assert!(instant.contains("(shown at t = 0.01 s;"), "{instant}");
}

#[test]
fn info_counts_the_bunny_triangles() {
    let bunny = workspace().join("examples/bunny.toml");
    if !workspace()
        .join("../shared/data/meshes/stanford-bunny.obj")
        .is_file()
    {
        eprintln!("skipped: ../shared/data is not here");
        return;
    }
    let output = lucent().arg("info").arg(bunny).output().unwrap();
    assert_success(&output);
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(
        stdout.contains("triangles:   69451 (69451 stored)"),
        "{stdout}"
    );
}

/// Ctrl-C (SIGINT) stops the render, writes the image so far and exits 130.
#[cfg(unix)]
#[test]
fn ctrl_c_writes_the_partial_image() {
    use std::time::Duration;
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("partial.pfm");
    // Large enough to take many seconds.
    let (output, stopping) = signal_after(
        lucent()
            .args([
                "render",
                "--width",
                "2000",
                "--height",
                "1500",
                "--spp",
                "64",
                "--threads",
                "1",
                "-o",
            ])
            .arg(&out),
        Duration::from_millis(700),
        "INT",
    );
    assert!(
        stopping < Duration::from_secs(2),
        "stopped within a second or so"
    );
    assert_eq!(
        output.status.code(),
        Some(130),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    assert!(String::from_utf8_lossy(&output.stderr).contains("wrote the partial image"));
    let img = read_pfm(&out);
    let rendered = img.pixels.iter().filter(|p| **p != [0.0; 3]).count();
    assert!(
        rendered > 0 && rendered < img.pixels.len(),
        "partly rendered: {rendered} pixels"
    );
    assert!(
        dir.path().join("partial.pfm.checkpoint").is_file(),
        "a checkpoint beside it"
    );
}

#[test]
fn time_renders_an_instant_of_a_moving_scene() {
    let dir = tempfile::tempdir().unwrap();
    let scene = workspace().join("examples/moving.toml");
    let render = |time: &str, name: &str| {
        let out = dir.path().join(name);
        let output = lucent()
            .args([
                "render", "--width", "64", "--height", "48", "--time", time, "-o",
            ])
            .arg(&out)
            .arg(&scene)
            .output()
            .unwrap();
        assert_success(&output);
        read_pfm(&out).pixels
    };
    let zero = render("0", "a.pfm");
    assert_eq!(
        zero,
        render("0.0", "b.pfm"),
        "the same instant, the same image"
    );
    assert_ne!(zero, render("1.5", "c.pfm"), "the scene moves");

    let output = lucent().arg("info").arg(&scene).output().unwrap();
    assert_success(&output);
    let stdout = String::from_utf8(output.stdout).unwrap();
    assert!(
        stdout.contains("motion:      4 objects move, the camera moves"),
        "{stdout}"
    );
    let bad = lucent()
        .args(["render", "--time", "soon"])
        .output()
        .unwrap();
    assert!(!bad.status.success());
}
