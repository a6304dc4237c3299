//! `lucent render`: read, override, build, render with progress, write, report.

use crate::cli::{IntegratorArg, RenderArgs, TriangleTestArg};
use crate::output::{ImageFormat, write_image};
use anyhow::Context;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use lucent::render::{RenderStats, render};
use lucent_scene::SceneFile;
use lucent_scene::Spanned;
use lucent_scene::desc::IntegratorName;
use lucent_scene::desc::settings::TriangleTestName;
use std::path::Path;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// Exit status of a render stopped by Ctrl-C (128 + SIGINT), after the partial image is written.
const INTERRUPTED: u8 = 130;

/// The scene file at `path`, or the built-in default scene.
pub fn read_scene(path: Option<&Path>) -> anyhow::Result<SceneFile> {
    Ok(match path {
        Some(p) => SceneFile::read(p)?,
        None => SceneFile::default_scene(),
    })
}

/// Applies the command line's overrides to the scene description. An overridden value loses
/// its place in the file, so an error about it does not point at the file's value.
fn apply_overrides(file: &mut SceneFile, args: &RenderArgs) {
    let from_flag = |v| Spanned::new(0..0, v);
    let d = &mut file.desc;
    if let Some(w) = args.width {
        d.image.width = from_flag(w);
    }
    if let Some(h) = args.height {
        d.image.height = from_flag(h);
    }
    if let Some(n) = args.spp {
        d.image.samples = from_flag(n);
    }
    if let Some(i) = args.integrator {
        d.render.integrator = match i {
            IntegratorArg::Raycast => IntegratorName::Raycast,
            IntegratorArg::Whitted => IntegratorName::Whitted,
        };
    }
    if let Some(m) = args.max_depth {
        d.render.max_depth = from_flag(m);
    }
    if let Some(s) = args.seed {
        d.render.seed = s;
    }
    if let Some(a) = args.accel {
        d.render.accelerator = Spanned::new(0..0, a.name().to_string());
    }
    if let Some(t) = args.triangle_test {
        d.render.triangle_test = match t {
            TriangleTestArg::Watertight => TriangleTestName::Watertight,
            TriangleTestArg::Projection => TriangleTestName::Projection,
        };
    }
}

/// Renders and writes the image; exits 130 after writing a partial image on Ctrl-C.
pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    // Check the output name before spending time on the render.
    let format = ImageFormat::from_path(&args.output)?;
    let mut file = read_scene(args.scene.as_deref())?;
    apply_overrides(&mut file, args);
    let loaded = file.build()?;
    let mut settings = loaded.settings;
    settings.threads = usize::from(args.threads);

    let cancel = Arc::new(AtomicBool::new(false));
    let handler_flag = Arc::clone(&cancel);
    ctrlc::set_handler(move || {
        if handler_flag.swap(true, Ordering::SeqCst) {
            // A second Ctrl-C: the user does not want to wait for the partial image.
            std::process::exit(i32::from(INTERRUPTED));
        }
    })
    .context("cannot install the Ctrl-C handler")?;

    let (w, h) = (loaded.scene.camera.width(), loaded.scene.camera.height());
    let bar = ProgressBar::with_draw_target(
        Some(u64::from(w) * u64::from(h)),
        ProgressDrawTarget::stderr(),
    );
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {wide_bar} {percent:>3}% ETA {eta}",
        )
        .expect("a valid progress template"),
    );
    let progress = |done: u64, _total: u64| bar.set_position(done);
    let rendered = render(&loaded.scene, &settings, &cancel, &progress)?;
    bar.finish_and_clear();

    write_image(&rendered.film, &args.output, format)
        .with_context(|| format!("cannot write {}", args.output.display()))?;
    println!(
        "{}",
        summary(&args.output, w, h, settings.spp, &rendered.stats)
    );
    if rendered.stats.rays.nonfinite > 0 {
        eprintln!(
            "warning: {} samples were NaN or infinite and were left out",
            rendered.stats.rays.nonfinite
        );
    }
    if rendered.complete {
        Ok(ExitCode::SUCCESS)
    } else {
        eprintln!(
            "interrupted: wrote the partial image to {}",
            args.output.display()
        );
        Ok(ExitCode::from(INTERRUPTED))
    }
}

/// The one statistics line printed after a render.
fn summary(output: &Path, w: u32, h: u32, spp: u32, s: &RenderStats) -> String {
    let r = &s.rays;
    format!(
        "{}: {w}×{h}, {spp} spp, {} rays (camera {}, shadow {}, reflected {}, refracted {}), {:.3} s, {:.3} Mrays/s, {} threads",
        output.display(),
        r.total(),
        r.camera,
        r.shadow,
        r.reflected,
        r.refracted,
        s.elapsed.as_secs_f64(),
        s.mrays_per_second(),
        s.threads
    )
}
