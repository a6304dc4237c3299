//! Helpers of the command-line tests: run `lucent`, write scenes, read images back.
#![allow(dead_code)] // each test file uses a different subset

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The `lucent` binary under test.
pub fn lucent() -> Command {
    Command::new(env!("CARGO_BIN_EXE_lucent"))
}

/// The workspace's root folder.
pub fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A linear float image, rows from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    pub width: usize,
    pub height: usize,
    pub pixels: Vec<[f32; 3]>,
}

impl Image {
    pub fn at(&self, x: usize, y: usize) -> [f32; 3] {
        self.pixels[y * self.width + x]
    }

    pub fn center(&self) -> [f32; 3] {
        self.at(self.width / 2, self.height / 2)
    }
}

/// Reads a PFM file (little- or big-endian, colour), flipping rows so that row 0 is the top.
pub fn read_pfm(path: &Path) -> Image {
    let bytes = std::fs::read(path).unwrap();
    let mut fields = Vec::new();
    let mut pos = 0;
    while fields.len() < 4 {
        let start = pos;
        while !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        fields.push(String::from_utf8(bytes[start..pos].to_vec()).unwrap());
        pos += 1;
    }
    assert_eq!(fields[0], "PF", "a colour PFM");
    let (width, height): (usize, usize) = (fields[1].parse().unwrap(), fields[2].parse().unwrap());
    let scale: f32 = fields[3].parse().unwrap();
    let data = &bytes[pos..];
    assert_eq!(data.len(), width * height * 12);
    let read = |i: usize| {
        let b: [u8; 4] = data[4 * i..4 * i + 4].try_into().unwrap();
        if scale < 0.0 {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        }
    };
    let mut pixels = Vec::with_capacity(width * height);
    for y in (0..height).rev() {
        for x in 0..width {
            let i = 3 * (y * width + x);
            pixels.push([read(i), read(i + 1), read(i + 2)]);
        }
    }
    Image {
        width,
        height,
        pixels,
    }
}

/// Runs `lucent render SCENE ARGS… -o OUT` to the end.
pub fn render_to(scene: &Path, args: &[&str], out: &Path) -> Output {
    lucent()
        .arg("render")
        .arg(scene)
        .args(args)
        .arg("-o")
        .arg(out)
        .output()
        .unwrap()
}

/// Writes `scene` into a fresh folder, renders it to PFM with `args`, and reads the image.
pub fn render_scene(scene: &str, args: &[&str]) -> Image {
    let dir = tempfile::tempdir().unwrap();
    let scene_path = dir.path().join("scene.toml");
    std::fs::write(&scene_path, scene).unwrap();
    let out = dir.path().join("out.pfm");
    let output = lucent()
        .arg("render")
        .arg(&scene_path)
        .arg("-o")
        .arg(&out)
        .args(args)
        .output()
        .unwrap();
    assert_success(&output);
    read_pfm(&out)
}

/// Panics with the process's stderr unless it succeeded.
pub fn assert_success(output: &Output) {
    assert!(
        output.status.success(),
        "lucent failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
}

/// Asserts that two colours agree within a relative tolerance (per channel, of the larger).
pub fn assert_close(got: [f32; 3], want: [f32; 3], rel: f32) {
    for c in 0..3 {
        let tol = rel * want[c].abs().max(got[c].abs()).max(1e-6);
        assert!(
            (got[c] - want[c]).abs() <= tol,
            "got {got:?}, want {want:?} (±{rel})"
        );
    }
}

/// Runs `command` (its output captured), sends it `signal` (as `kill -INT`: "INT", "TERM")
/// after `wait`, and returns its output and how long it took to exit after the signal.
#[cfg(unix)]
pub fn signal_after(
    command: &mut Command,
    wait: std::time::Duration,
    signal: &str,
) -> (Output, std::time::Duration) {
    let child = command
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(wait);
    let status = Command::new("kill")
        .args([&format!("-{signal}"), &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success(), "kill -{signal}");
    let sent = std::time::Instant::now();
    let output = child.wait_with_output().unwrap();
    (output, sent.elapsed())
}
