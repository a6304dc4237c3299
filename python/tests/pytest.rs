//! Runs the Python package's tests (`python/tests/*.py`) from `cargo test`: builds the package
//! with maturin into a virtual environment of its own, installs numpy and pytest there (from
//! PyPI), and runs pytest against the `lucent` command built beside it.
//!
//! Without Python 3.9+ or PyPI the test says why and passes, unless `LUCENT_REQUIRE_TOOLS=1`
//! (as CI sets): then it fails.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The packages the tests need besides lucent; nbclient and ipykernel run the notebook,
/// ipywidgets makes the teaching widget's sliders.
const PACKAGES: &[&str] = &[
    "maturin>=1.5,<2",
    "numpy",
    "pytest",
    "nbclient",
    "ipykernel",
    "ipywidgets",
];

fn required() -> bool {
    std::env::var_os("LUCENT_REQUIRE_TOOLS").is_some_and(|v| v == "1")
}

/// Skips (or fails, when the tools are required) with `why`.
fn missing(why: &str) {
    assert!(!required(), "LUCENT_REQUIRE_TOOLS=1 but {why}");
    eprintln!("skipped: {why}");
}

fn run(cmd: &mut Command) -> Result<(), String> {
    let shown = format!("{cmd:?}");
    let out = cmd.output().map_err(|e| format!("{shown}: {e}"))?;
    if out.status.success() {
        Ok(())
    } else {
        Err(format!(
            "{shown} failed ({}):\n{}\n{}",
            out.status,
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        ))
    }
}

/// The workspace's root (this crate is `python/`).
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("python/ has a parent")
        .to_path_buf()
}

/// A virtual environment with the packages, made once under the target folder.
fn venv() -> Result<PathBuf, String> {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("python-venv");
    let python = dir.join("bin/python");
    if !python.exists() {
        run(Command::new("python3").args(["-m", "venv"]).arg(&dir))?;
    }
    let have = Command::new(&python)
        .args([
            "-c",
            "import maturin, numpy, pytest, nbclient, ipykernel, ipywidgets",
        ])
        .output()
        .map_err(|e| e.to_string())?;
    if !have.status.success() {
        run(Command::new(&python)
            .args([
                "-m",
                "pip",
                "install",
                "--quiet",
                "--disable-pip-version-check",
            ])
            .args(PACKAGES))?;
    }
    Ok(dir)
}

#[test]
fn python_package_tests() {
    let python_ok = Command::new("python3")
        .args([
            "-c",
            "import sys, venv; sys.exit(sys.version_info < (3, 9))",
        ])
        .status()
        .is_ok_and(|s| s.success());
    if !python_ok {
        return missing("python3 (3.9 or newer, with venv) is not installed");
    }
    let env = match venv() {
        Ok(env) => env,
        Err(e) => return missing(&format!("the test environment could not be made: {e}")),
    };
    let root = root();
    // The `lucent` command, for the bit-for-bit comparisons, and the package, built with one
    // profile (so they share their crates) and installed as `pip install ./python` would.
    let profile = ["--profile", "python-test"];
    run(Command::new(env!("CARGO"))
        .current_dir(&root)
        .args([
            "build",
            "-p",
            "lucent-cli",
            "--bin",
            "lucent",
            "--no-default-features",
        ])
        .args(profile))
    .unwrap();
    let lucent = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .parent()
        .expect("target/tmp has a parent")
        .join("python-test/lucent");
    assert!(lucent.is_file(), "{} was not built", lucent.display());
    let wheels = Path::new(env!("CARGO_TARGET_TMPDIR")).join("python-wheels");
    let _ = std::fs::remove_dir_all(&wheels);
    run(Command::new(env.join("bin/maturin"))
        .current_dir(root.join("python"))
        .args(["build", "--quiet"])
        .args(profile)
        .arg("--out")
        .arg(&wheels))
    .unwrap();
    let wheel = std::fs::read_dir(&wheels)
        .unwrap()
        .filter_map(Result::ok)
        .map(|e| e.path())
        .find(|p| p.extension().is_some_and(|e| e == "whl"))
        .expect("maturin made a wheel");
    run(Command::new(env.join("bin/python"))
        .args([
            "-m",
            "pip",
            "install",
            "--quiet",
            "--force-reinstall",
            "--no-deps",
        ])
        .arg(&wheel))
    .unwrap();
    let out = Command::new(env.join("bin/python"))
        .current_dir(&root)
        .args([
            "-m",
            "pytest",
            "-q",
            "-p",
            "no:cacheprovider",
            "python/tests",
        ])
        .env("LUCENT_BIN", &lucent)
        .output()
        .expect("pytest runs");
    print!("{}", String::from_utf8_lossy(&out.stdout));
    eprint!("{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "the Python package's tests failed");
}
