//! `lucent bench --sampling`: adaptive against uniform supersampling at equal image error.
//!
//! One scene (the built-in one by default) at one size: a 256-spp uniform reference (another
//! seed than the measured renders), then uniform renders at 1, 4, 16 and 64 spp and adaptive
//! renders at several thresholds (depth 3) and two quadtrees, each with its root-mean-square
//! error against the reference (linear radiance, every channel), camera rays per pixel and
//! wall time. The last line says what adaptive sampling needs to be as close as 16 uniform
//! samples per pixel.

use crate::cli::{AaArg, Overrides};
use crate::job::Job;
use lucent::film::Film;
use lucent::render::{Hooks, RenderSettings, Rendered, Sampling, render};
use lucent::schedule::adaptive::Adaptive;
use std::path::Path;
use std::process::ExitCode;
use std::sync::atomic::AtomicBool;

/// Uniform sample counts measured.
const UNIFORM_SPP: [u32; 4] = [1, 4, 16, 64];
/// Adaptive thresholds measured.
const THRESHOLDS: [f32; 5] = [0.4, 0.2, 0.1, 0.05, 0.02];
/// Samples per pixel of the reference.
const REFERENCE_SPP: u32 = 256;

struct Line {
    label: String,
    rays_per_pixel: f64,
    seconds: f64,
    rmse: f64,
}

/// Renders and compares; prints one table.
pub fn run(
    scene: Option<&Path>,
    (width, height): (u32, u32),
    threads: usize,
) -> anyhow::Result<ExitCode> {
    let overrides = Overrides {
        width: Some(width),
        height: Some(height),
        aa: Some(AaArg::Uniform),
        ..Overrides::default()
    };
    let job = Job::load(scene, &overrides)?;
    let base = RenderSettings {
        threads,
        ..job.loaded.settings
    };
    let scene = &job.loaded.scene;
    let go = |settings: RenderSettings| -> anyhow::Result<Rendered> {
        let cancel = AtomicBool::new(false);
        let hooks = Hooks {
            cancel: &cancel,
            progress: &|_, _| {},
            checkpoint: None,
        };
        Ok(render(scene, &settings, None, &hooks)?)
    };
    eprintln!("reference: {REFERENCE_SPP} spp …");
    let reference = go(RenderSettings {
        spp: REFERENCE_SPP,
        seed: base.seed.wrapping_add(0x5eed),
        ..base
    })?
    .film;
    let pixels = f64::from(width) * f64::from(height);
    let line = |label: String, r: Rendered| Line {
        label,
        rays_per_pixel: r.stats.rays.camera as f64 / pixels,
        seconds: r.stats.elapsed.as_secs_f64(),
        rmse: rmse(&r.film, &reference),
    };
    let mut uniform = Vec::new();
    for spp in UNIFORM_SPP {
        let r = go(RenderSettings { spp, ..base })?;
        uniform.push(line(format!("uniform {spp} spp"), r));
    }
    let adaptive_line = |a: Adaptive, label: String| -> anyhow::Result<Line> {
        let r = go(RenderSettings {
            spp: 1,
            sampling: Sampling::Adaptive(a),
            ..base
        })?;
        Ok(line(label, r))
    };
    let mut adaptive = Vec::new();
    for threshold in THRESHOLDS {
        let a = Adaptive {
            threshold,
            ..Adaptive::default()
        };
        adaptive.push(adaptive_line(
            a,
            format!("adaptive {threshold} (depth {})", a.depth),
        )?);
    }
    let mut quadtree = Vec::new();
    for block in [2, 3] {
        let a = Adaptive {
            block,
            ..Adaptive::default()
        };
        let side = 1 << block;
        quadtree.push(adaptive_line(
            a,
            format!("quadtree {side}×{side} {}", a.threshold),
        )?);
    }

    println!(
        "{}×{}, {} threads, error against {REFERENCE_SPP} spp (RMSE of linear radiance)",
        width, height, threads
    );
    println!(
        "{:<26} {:>12} {:>10} {:>10}",
        "sampling", "rays/pixel", "seconds", "RMSE"
    );
    for l in uniform.iter().chain(&adaptive).chain(&quadtree) {
        println!(
            "{:<26} {:>12.2} {:>10.3} {:>10.5}",
            l.label, l.rays_per_pixel, l.seconds, l.rmse
        );
    }
    let target = &uniform[2];
    match adaptive.iter().find(|l| l.rmse <= target.rmse) {
        Some(a) => println!(
            "equal error: {} reaches the RMSE of {} ({:.5}) with {:.2} camera rays per pixel ({:.0}% of {:.0}) in {:.3} s ({:.2}× faster)",
            a.label,
            target.label,
            target.rmse,
            a.rays_per_pixel,
            100.0 * a.rays_per_pixel / target.rays_per_pixel,
            target.rays_per_pixel,
            a.seconds,
            target.seconds / a.seconds.max(1e-9)
        ),
        None => println!(
            "equal error: no adaptive threshold measured reaches the RMSE of {} ({:.5})",
            target.label, target.rmse
        ),
    }
    Ok(ExitCode::SUCCESS)
}

/// Root-mean-square difference of two films' pixel values, over every channel.
fn rmse(a: &Film, b: &Film) -> f64 {
    let mut sum = 0.0;
    for y in 0..a.height() {
        for x in 0..a.width() {
            let (p, q) = (a.pixel(x, y).to_array(), b.pixel(x, y).to_array());
            sum += (0..3).map(|c| f64::from(p[c] - q[c]).powi(2)).sum::<f64>();
        }
    }
    (sum / (3.0 * f64::from(a.width()) * f64::from(a.height()))).sqrt()
}
