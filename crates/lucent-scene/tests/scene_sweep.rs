//! A randomised sweep of valid scenes with extreme values: every scene either renders with
//! finite pixels only, or is refused with one line naming the file and the place; none
//! panics.
//!
//! [`generate`] writes each scene from a seed (splitmix64; no entropy): every section and key
//! of `docs/scene-format.md`, numbers drawn from ordinary values and from extremes the format
//! accepts — 0, f32 subnormals, 1e-30, 1e20, 3e38, `f32::MAX`, negatives, far positions, a thin
//! lens of aperture and focus 1e-30. Scenes are tiny (at most 8 × 8 pixels, 1–4 samples) and
//! each is loaded and rendered under `whitted`, `path` and `sppm`.
//!
//! [`SCENES`] = 200 scenes (600 renders; about two thirds render, the rest are refused) take
//! about 15 s in the test profile (opt-level 3) on two cores. `SCENE_SWEEP_SCENES` and
//! `SCENE_SWEEP_SEED` run more, or replay one: a failure names the seed of its scene, and
//! `SCENE_SWEEP_SEED=S SCENE_SWEEP_SCENES=1` renders that scene alone. Each failing scene is
//! also written to `target/tmp/scene_sweep/failing/`. (3,000 scenes take about 8 minutes.)
//!
//! A panic is caught by `catch_unwind` around the load and the render. Renders run on one
//! thread: a panic in a rayon worker would reach the caller too (rayon re-raises it), but one
//! thread keeps the order, and the panic hook's note of where it happened, simple. The test
//! profile keeps debug assertions, so the renderer's `debug_assert!`s on finite BSDF values
//! count as panics here.

#[path = "scene_sweep/generate.rs"]
mod generate;
#[path = "scene_sweep/materials.rs"]
mod materials;
#[path = "scene_sweep/values.rs"]
mod values;

use lucent::render::{Hooks, RenderSettings, render};
use lucent_scene::{LoadError, SceneFile};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;

/// Scenes in a plain `cargo test` run.
const SCENES: u64 = 400;
/// The first scene's seed (each next scene's is one more).
const SEED: u64 = 0x5eed_5ce0e;
const INTEGRATORS: [&str; 3] = ["whitted", "path", "sppm"];

/// What became of one scene under one integrator.
enum Outcome {
    /// Refused by the load, with this error.
    Refused(LoadError),
    /// Rendered; the first pixel that is not finite, if any.
    Rendered(Option<(u32, u32, [f32; 3])>),
    /// The render itself returned an error.
    RenderError(String),
}

/// A scene that broke the rule.
struct Failure {
    seed: u64,
    integrator: &'static str,
    class: &'static str,
    detail: String,
    text: String,
}

/// The message and place of the last panic, as the hook saw it (the payload alone has no
/// place). Only this file's one test sets it.
static LAST_PANIC: Mutex<String> = Mutex::new(String::new());

/// The folder of the textures and meshes the scenes name, written once.
fn assets() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("scene_sweep");
    std::fs::create_dir_all(&dir).unwrap();
    // A 2 × 2 RGBA texture (alpha for `channel = "a"`) and a 4 × 2 sky.
    let tex = image::RgbaImage::from_fn(2, 2, |x, y| {
        image::Rgba([
            255 * (x as u8),
            128,
            255 * (y as u8),
            64 + 128 * ((x + y) as u8 % 2),
        ])
    });
    tex.save(dir.join("tex.png")).unwrap();
    let sky = image::RgbImage::from_fn(4, 2, |x, y| image::Rgb([60 * x as u8, 200, 100 * y as u8]));
    sky.save(dir.join("sky.png")).unwrap();
    std::fs::write(
        dir.join("tri.obj"),
        "v -1 0 0\nv 1 0 0\nv 0 1.5 0\nvt 0 0\nvt 1 0\nvt 0.5 1\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\nv 0.5 0.5 0.5 1 0 0\nf 1/1/1 2/2/2 3/3/3\nf 1 3 4\n",
    )
    .unwrap();
    dir
}

/// Loads `text` as the file `name` in `dir` and renders it on one thread.
fn run(name: &Path, dir: &Path, text: &str) -> Outcome {
    let loaded = SceneFile::parse(name.to_path_buf(), dir.to_path_buf(), text.to_string())
        .and_then(|f| f.build());
    let loaded = match loaded {
        Ok(l) => l,
        Err(e) => return Outcome::Refused(e),
    };
    let hooks = Hooks::none();
    let settings = RenderSettings {
        threads: 1,
        ..loaded.settings
    };
    let film = match render(&loaded.scene, &settings, None, &hooks) {
        Ok(r) => r.film,
        Err(e) => return Outcome::RenderError(e.to_string()),
    };
    for y in 0..film.height() {
        for x in 0..film.width() {
            let p = film.pixel(x, y).to_array();
            if !p.iter().all(|c| c.is_finite()) {
                return Outcome::Rendered(Some((x, y, p)));
            }
        }
    }
    Outcome::Rendered(None)
}

/// The number in environment variable `key` (decimal, or hex after `0x`), if set.
fn env_u64(key: &str) -> Option<u64> {
    let v = std::env::var(key).ok()?;
    let v = v.trim();
    match v.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16).ok(),
        None => v.parse().ok(),
    }
}

#[test]
fn random_scenes_render_finite_or_are_refused_in_one_line() {
    let scenes = env_u64("SCENE_SWEEP_SCENES").unwrap_or(SCENES);
    let first = env_u64("SCENE_SWEEP_SEED").unwrap_or(SEED);
    let dir = assets();
    let out = dir.join("failing");
    let _ = std::fs::remove_dir_all(&out);
    let began = Instant::now();

    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(|info| {
        *LAST_PANIC.lock().unwrap_or_else(|e| e.into_inner()) = info.to_string();
    }));
    let mut failures = Vec::new();
    // (integrator, outcome) → scenes; and the refusals' messages, counted.
    let mut tally: BTreeMap<(&str, &str), u32> = BTreeMap::new();
    let mut refusals: BTreeMap<String, u32> = BTreeMap::new();
    for seed in first..first + scenes {
        for integrator in INTEGRATORS {
            let text = generate::scene(seed, integrator);
            let name = PathBuf::from(format!("sweep-{seed:x}-{integrator}.toml"));
            let outcome = catch_unwind(AssertUnwindSafe(|| run(&name, &dir, &text)));
            let mut fail = |class: &'static str, detail: String| {
                failures.push(Failure {
                    seed,
                    integrator,
                    class,
                    detail,
                    text: text.clone(),
                });
            };
            let label = match outcome {
                Err(_) => {
                    let at =
                        std::mem::take(&mut *LAST_PANIC.lock().unwrap_or_else(|e| e.into_inner()));
                    fail("panic", at);
                    "panicked"
                }
                Ok(Outcome::RenderError(e)) => {
                    fail("render error", e);
                    "render error"
                }
                Ok(Outcome::Rendered(Some((x, y, p)))) => {
                    fail("non-finite pixel", format!("pixel ({x}, {y}) is {p:?}"));
                    "non-finite"
                }
                Ok(Outcome::Rendered(None)) => "rendered",
                Ok(Outcome::Refused(e)) => {
                    let line = e.to_string();
                    if line.contains('\n') {
                        fail("multi-line error", line);
                    } else if !line.starts_with(&*name.to_string_lossy()) {
                        fail("error not naming the file", line);
                    } else if e.position.is_none() {
                        fail("error without a line", line);
                    } else {
                        *refusals.entry(e.message.clone()).or_default() += 1;
                    }
                    "refused"
                }
            };
            *tally.entry((integrator, label)).or_default() += 1;
        }
    }
    std::panic::set_hook(previous);

    let elapsed = began.elapsed();
    println!("{scenes} scenes from seed {first:#x}, 3 integrators, {elapsed:.1?}");
    for ((integrator, label), n) in &tally {
        println!("  {integrator:8} {label:12} {n}");
    }
    println!("refusals:");
    for (message, n) in &refusals {
        println!("  {n:4} × {message}");
    }
    if failures.is_empty() {
        // A sweep whose scenes were mostly refused would test little.
        for integrator in INTEGRATORS {
            let rendered = tally.get(&(integrator, "rendered")).copied().unwrap_or(0);
            assert!(
                u64::from(rendered) * 3 > scenes,
                "{integrator}: only {rendered} of {scenes} scenes rendered"
            );
        }
        return;
    }
    let mut report = format!(
        "{} of {} renders broke the rule:\n",
        failures.len(),
        scenes * 3
    );
    std::fs::create_dir_all(&out).unwrap();
    let mut shown = std::collections::HashSet::new();
    for f in &failures {
        let file = out.join(format!("sweep-{:x}-{}.toml", f.seed, f.integrator));
        std::fs::write(&file, &f.text).unwrap();
        let _ = writeln!(
            report,
            "- {} (seed {:#x}, {}): {}\n  {}",
            f.class,
            f.seed,
            f.integrator,
            f.detail.replace('\n', "\n  "),
            file.display()
        );
        // The whole text of the first scene of each class (and place of a panic).
        if shown.insert((
            f.class,
            f.detail.lines().next().unwrap_or_default().to_string(),
        )) {
            let _ = writeln!(report, "```toml\n{}```", f.text);
        }
    }
    panic!("{report}");
}
