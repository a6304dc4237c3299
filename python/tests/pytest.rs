//! Runs the Python package's tests (`python/tests/*.py`) from `cargo test`: lays the package out
//! as its wheel holds it (the Python sources, the extension module that this `cargo test` built,
//! the metadata maturin writes), makes a virtual environment of its own with numpy and pytest
//! (from PyPI), and runs pytest against the `lucent` command built beside it.
//!
//! The module and the command are this build's (the test profile: optimised, assertions on), so
//! the tests cost no second compile of the tree; `pip install ./python` compiles the same code
//! with the release profile.
//!
//! Without Python 3.9+ or PyPI the test says why and passes, unless `LUCENT_REQUIRE_TOOLS=1`
//! (as CI sets): then it fails.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The packages the tests need besides lucent: maturin writes the package's metadata as its
/// wheel holds it, nbclient and ipykernel run the notebook, ipywidgets makes the teaching
/// widget's sliders.
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

/// The folder of this build's artifacts (`target/debug` for the test profile): this test
/// runs from its `deps` folder.
fn build_dir() -> PathBuf {
    let exe = std::env::current_exe().expect("the test knows its path");
    exe.parent()
        .and_then(Path::parent)
        .expect("the test runs from <target>/<profile>/deps")
        .to_path_buf()
}

/// The `lucent` command of this build, for the bit-for-bit comparisons. `cargo test --workspace`
/// has built it before any test runs; asking cargo again is then a no-op, and makes it right when
/// this package's tests run alone (`-p lucent-python`).
fn lucent_command(root: &Path) -> Result<PathBuf, String> {
    run(Command::new(env!("CARGO")).current_dir(root).args([
        "test",
        "--workspace",
        "--no-run",
        "--quiet",
    ]))?;
    let lucent = build_dir().join("lucent");
    if lucent.is_file() {
        Ok(lucent)
    } else {
        Err(format!("{} was not built", lucent.display()))
    }
}

/// The package as its wheel lays it out (see `pyproject.toml`: the sources of `python/lucent`,
/// the module `lucent._lucent`, and the metadata), in a folder for `PYTHONPATH`. The module is
/// this build's `lib_lucent.so`, hard-linked where the file system allows.
fn assembled_package(root: &Path, env: &Path) -> Result<PathBuf, String> {
    let site = Path::new(env!("CARGO_TARGET_TMPDIR")).join("python-package");
    let _ = std::fs::remove_dir_all(&site);
    let package = site.join("lucent");
    std::fs::create_dir_all(&package).map_err(|e| format!("{}: {e}", package.display()))?;
    let sources = root.join("python/lucent");
    for entry in std::fs::read_dir(&sources).map_err(|e| format!("{}: {e}", sources.display()))? {
        let from = entry.map_err(|e| e.to_string())?.path();
        if from.is_file() {
            let to = package.join(from.file_name().expect("a file has a name"));
            std::fs::copy(&from, &to).map_err(|e| format!("{}: {e}", to.display()))?;
        }
    }
    let module = build_dir().join("deps/lib_lucent.so");
    if !module.is_file() {
        return Err(format!("{} was not built", module.display()));
    }
    let installed = package.join("_lucent.abi3.so");
    if std::fs::hard_link(&module, &installed).is_err() {
        std::fs::copy(&module, &installed).map_err(|e| format!("{}: {e}", installed.display()))?;
    }
    // Validates pyproject.toml and the crate's metadata the way `pip install` would begin.
    run(Command::new(env.join("bin/maturin"))
        .current_dir(root.join("python"))
        .args(["pep517", "write-dist-info", "--metadata-directory"])
        .arg(&site))?;
    Ok(site)
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
    let lucent = lucent_command(&root).unwrap();
    let package = assembled_package(&root, &env).unwrap();
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
        .env("PYTHONPATH", &package)
        .output()
        .expect("pytest runs");
    print!("{}", String::from_utf8_lossy(&out.stdout));
    eprint!("{}", String::from_utf8_lossy(&out.stderr));
    assert!(out.status.success(), "the Python package's tests failed");
}
