//! `lucent study frameless`: the frameless study of [`lucent::study::frameless`] on a scene,
//! with a progress bar, a summary table, a CSV of every refresh and an SVG plot.

mod plot;

use crate::cli::FramelessStudyArgs;
use crate::job::Job;
use anyhow::{Context, bail};
use indicatif::{ProgressBar, ProgressStyle};
use lucent::schedule::frameless::DisplayMode;
use lucent::study::frameless::{StudyReport, StudySettings, run_study};
use lucent::study::scene_tracer::SceneTracer;
use plot::{Chart, Series};
use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// Runs the study and writes its table, CSV and plot.
pub fn frameless(args: &FramelessStudyArgs) -> anyhow::Result<ExitCode> {
    let job = match &args.scene {
        Some(p) => Job::load(Some(p), &args.overrides)?,
        None => Job::load_moving(&args.overrides)?,
    };
    let name = args
        .scene
        .as_ref()
        .map_or("the built-in moving scene".to_string(), |p| {
            p.display().to_string()
        });
    let integrator = job.loaded.settings.integrator;
    if integrator.is_stochastic() {
        bail!(
            "the study compares every sample with an ideal image, so it needs a deterministic integrator: {} draws random numbers (use --integrator whitted or raycast)",
            integrator.name()
        );
    }
    let scene = Arc::new(job.loaded.scene);
    if !scene.is_animated() {
        eprintln!(
            "warning: {name} does not move: every mode converges to the same picture (give objects or the camera a `motion`)"
        );
    }
    let settings = StudySettings {
        samples_per_second: args.samples_per_second,
        refresh_hz: args.refresh,
        duration: args.duration,
        warmup: args.warmup,
        rate_divisors: args.rate_divisors.clone(),
        seed: args.study_seed,
        capture_at: args.frames_at,
        ..StudySettings::default()
    };
    if let Some(at) = args.frames_at
        && !(at > 0.0 && at <= args.duration)
    {
        bail!(
            "--frames-at {at}: the study measures from 0 to {} s (--duration); pick an instant inside",
            args.duration
        );
    }
    for path in [&args.csv, &args.plot] {
        crate::output::check_writable(path)?;
    }
    let step = 1.0 / (settings.refresh_hz * f64::from(settings.substeps));
    let tracer = SceneTracer::new(scene.clone(), integrator, job.loaded.settings.seed, step);
    let (w, h) = (scene.camera.width(), scene.camera.height());
    eprintln!(
        "studying {name}: {w}×{h}, {} samples/s, {} Hz, {} s measured",
        args.samples_per_second, args.refresh, args.duration
    );
    let bar = ProgressBar::new(1);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} refreshes, {elapsed} (eta {eta})")
            .expect("a valid template"),
    );
    let start = std::time::Instant::now();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(usize::from(args.threads))
        .build()
        .context("starting the threads")?;
    // Ctrl-C stops the study after the refresh under way and writes what was measured; a
    // second one exits at once.
    let cancel = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&cancel);
    ctrlc::set_handler(move || {
        if flag.swap(true, Ordering::SeqCst) {
            std::process::exit(i32::from(INTERRUPTED));
        }
    })
    .context("cannot install the Ctrl-C handler")?;
    let report = pool.install(|| {
        run_study(&tracer, &settings, |done, total| {
            bar.set_length(total as u64);
            bar.set_position(done as u64);
            !cancel.load(Ordering::SeqCst)
        })
    });
    bar.finish_and_clear();
    let interrupted = cancel.load(Ordering::SeqCst);
    if interrupted && report.settings.duration == 0.0 {
        eprintln!("interrupted during the warm-up: nothing was measured, nothing written");
        return Ok(ExitCode::from(INTERRUPTED));
    }
    if interrupted {
        eprintln!(
            "interrupted: {:.2} s of the {} s were measured; writing those",
            report.settings.duration, args.duration
        );
    }
    print!("{}", summary(&report));
    println!(
        "({} rays in {:.1} s of wall time)",
        tracer.rays(),
        start.elapsed().as_secs_f64()
    );
    write_csv(&report, &args.csv)?;
    std::fs::write(&args.plot, plot_svg(&report))
        .with_context(|| format!("writing {}", args.plot.display()))?;
    eprintln!("wrote {} and {}", args.csv.display(), args.plot.display());
    if let (Some(dir), Some(at)) = (&args.frames_dir, args.frames_at) {
        if report.capture.is_some() || !interrupted {
            write_frames(&report, dir, at)?;
        } else {
            eprintln!("interrupted before t = {at} s: no pictures written");
        }
    }
    Ok(if interrupted {
        ExitCode::from(INTERRUPTED)
    } else {
        ExitCode::SUCCESS
    })
}

/// The exit status of a study stopped by Ctrl-C (128 + SIGINT, as shells report it).
const INTERRUPTED: u8 = 130;

/// The table of the three modes at the full rate, and the matching rates.
pub fn summary(report: &StudyReport) -> String {
    let s = &report.settings;
    let mut out = String::new();
    let refresh_ms = 1000.0 / s.refresh_hz;
    let frame_ms = 1000.0 * f64::from(report.width * report.height) / s.samples_per_second;
    let _ = writeln!(
        out,
        "{}×{} at {:.0} samples/s, {} Hz (a refresh is {refresh_ms:.1} ms; a whole frame takes {frame_ms:.0} ms); {:.1} s measured after {:.1} s of warm-up",
        report.width,
        report.height,
        s.samples_per_second,
        s.refresh_hz,
        s.duration,
        s.warmup.unwrap_or(0.0)
    );
    let _ = writeln!(
        out,
        "{:<14} {:>10} {:>8} {:>12} {:>12} {:>8}",
        "mode", "mean RMSE", "stale", "latency ms", "p95 ms", "unseen"
    );
    for mode in DisplayMode::ALL {
        if let Some(r) = report.main_run(mode) {
            let _ = writeln!(
                out,
                "{:<14} {:>10.5} {:>7.1}% {:>12.1} {:>12.1} {:>8}",
                mode.name(),
                r.mean_rmse(),
                100.0 * r.mean_stale(),
                1000.0 * r.mean_latency(),
                1000.0 * r.latency_p95(),
                r.unseen
            );
        }
    }
    for mode in [DisplayMode::Frameless, DisplayMode::Adaptive] {
        let line = match report.matching_rate(mode) {
            Some((rate, false)) => format!(
                "{} matches double buffering's error at {rate:.0} samples/s: {:.1}× fewer samples",
                mode.name(),
                s.samples_per_second / rate
            ),
            Some((rate, true)) => format!(
                "{} still beats double buffering's error at {rate:.0} samples/s, the lowest rate tried: at least {:.1}× fewer samples",
                mode.name(),
                s.samples_per_second / rate
            ),
            None => format!(
                "{} does not reach double buffering's error even at the full rate",
                mode.name()
            ),
        };
        let _ = writeln!(out, "{line}");
    }
    out
}

/// The pictures of `--frames-at`: `ideal.png` and one per mode, sRGB.
fn write_frames(report: &StudyReport, dir: &Path, at: f64) -> anyhow::Result<()> {
    let Some(capture) = &report.capture else {
        bail!(
            "--frames-at {at}: no measured refresh at that instant (the study measures 0 to {} s)",
            report.settings.duration
        );
    };
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let pictures = std::iter::once(("ideal", &capture.ideal))
        .chain(capture.shown.iter().map(|(m, p)| (m.name(), p)));
    for (name, pixels) in pictures {
        let bytes: Vec<u8> = pixels
            .iter()
            .flat_map(|c| c.to_array().map(lucent::film::tonemap::srgb8))
            .collect();
        let path = dir.join(format!("{name}.png"));
        image::RgbImage::from_raw(report.width, report.height, bytes)
            .context("a picture of the screen's size")?
            .save(&path)
            .with_context(|| format!("writing {}", path.display()))?;
    }
    eprintln!(
        "wrote the pictures of t = {:.3} s in {}",
        capture.time,
        dir.display()
    );
    Ok(())
}

fn write_csv(report: &StudyReport, path: &Path) -> anyhow::Result<()> {
    let mut out = String::from("mode,samples_per_second,time_s,rmse,stale_fraction\n");
    for run in &report.runs {
        for r in &run.refreshes {
            let _ = writeln!(
                out,
                "{},{},{:.6},{:.6},{:.6}",
                run.mode.name(),
                run.samples_per_second,
                r.time,
                r.rmse,
                r.stale_fraction
            );
        }
    }
    std::fs::write(path, out).with_context(|| format!("writing {}", path.display()))
}

fn color(mode: DisplayMode) -> &'static str {
    match mode {
        DisplayMode::DoubleBuffer => "#d62728",
        DisplayMode::Frameless => "#1f77b4",
        DisplayMode::Adaptive => "#2ca02c",
    }
}

/// Error over time at the full rate, and mean error against the sample rate.
fn plot_svg(report: &StudyReport) -> String {
    let over_time = DisplayMode::ALL
        .iter()
        .filter_map(|&m| report.main_run(m))
        .map(|r| Series {
            name: r.mode.name().to_string(),
            color: color(r.mode),
            dashed: false,
            points: r.refreshes.iter().map(|f| (f.time, f.rmse)).collect(),
        })
        .collect();
    let mut by_rate: Vec<Series> = [DisplayMode::Frameless, DisplayMode::Adaptive]
        .iter()
        .map(|&m| {
            let mut points: Vec<(f64, f64)> = report
                .runs
                .iter()
                .filter(|r| r.mode == m)
                .map(|r| (r.samples_per_second, r.mean_rmse()))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            Series {
                name: m.name().to_string(),
                color: color(m),
                dashed: false,
                points,
            }
        })
        .collect();
    if let Some(db) = report.main_run(DisplayMode::DoubleBuffer) {
        let lowest = report
            .runs
            .iter()
            .map(|r| r.samples_per_second)
            .fold(f64::INFINITY, f64::min);
        let e = db.mean_rmse();
        by_rate.push(Series {
            name: "double-buffer at full rate".into(),
            color: color(DisplayMode::DoubleBuffer),
            dashed: true,
            points: vec![(lowest, e), (report.settings.samples_per_second, e)],
        });
    }
    plot::svg(&[
        Chart {
            title: &format!(
                "RMSE against the ideal image, {:.0} samples/s",
                report.settings.samples_per_second
            ),
            x_label: "time (s)",
            y_label: "RMSE",
            log_x: false,
            series: over_time,
        },
        Chart {
            title: "mean RMSE against sample rate",
            x_label: "samples per second",
            y_label: "mean RMSE",
            log_x: true,
            series: by_rate,
        },
    ])
}
