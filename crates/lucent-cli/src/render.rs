//! `lucent render`: read, override, build, render with progress, write, report — and stop
//! cleanly on Ctrl-C or SIGTERM with a checkpoint, resume from one, or render one shard.

use crate::cli::RenderArgs;
use crate::film_file::{FilmMeta, read_film, write_film};
use crate::job::Job;
use crate::output::{ImageFormat, write_density_map, write_image_as};
use anyhow::{Context, anyhow, bail};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use lucent::film::Film;
use lucent::integrator::{DebugView, Integrator};
use lucent::render::{Checkpoints, Hooks, RenderStats, Sampling, Shard, render};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// Exit status of a render stopped by Ctrl-C or SIGTERM (128 + SIGINT), after its image and
/// checkpoint are written.
const INTERRUPTED: u8 = 130;

/// What this run renders, and where things go.
struct Plan {
    job: Job,
    shard: Shard,
    start: Option<Film>,
    output: PathBuf,
    format: ImageFormat,
    checkpoint: PathBuf,
}

/// Renders and writes the image; exits 130 after writing what it has on Ctrl-C or SIGTERM.
pub fn run(args: &RenderArgs) -> anyhow::Result<ExitCode> {
    let plan = if let Some(ckpt) = &args.resume {
        plan_resume(args, ckpt)?
    } else {
        plan_new(args)?
    };
    let mut settings = plan.job.loaded.settings;
    let adaptive = match settings.sampling {
        Sampling::Adaptive(a) => Some(a),
        Sampling::Uniform => None,
    };
    if let Some(map) = &args.density_map {
        if args.resume.is_some() || plan.shard.count > 1 {
            bail!(
                "--density-map needs the whole render in one run: a resumed or sharded render knows only its own pixels"
            );
        }
        if adaptive.is_none() {
            bail!(
                "--density-map shows where adaptive sampling went: add --aa adaptive or --aa quadtree"
            );
        }
        if ImageFormat::from_path(map)? != ImageFormat::Png {
            bail!("{}: the density map is written as PNG", map.display());
        }
        crate::output::check_writable(map)?;
    }
    settings.threads = usize::from(args.threads);
    settings.beam = args.beam == crate::cli::OnOff::On;
    settings.lanes = args.lanes == crate::cli::OnOff::On;
    settings.shard = plan.shard;
    if matches!(settings.integrator, Integrator::Sppm(_)) {
        if args.checkpoint_every.is_some() || args.resume.is_some() {
            bail!(
                "a photon-mapped render cannot be checkpointed or resumed: its photon statistics are not in the film"
            );
        }
        if plan.shard.count > 1 {
            bail!(
                "a photon-mapped render cannot be split into shards: every photon reaches every pixel"
            );
        }
    }
    if plan.shard.count > 1
        && settings.filter != lucent::film::filter::Filter::default()
        && settings.filter_sampling == lucent::film::splat::FilterSampling::Splat
    {
        bail!(
            "--shard needs every sample kept in its own pixel, so that shards merge bit for bit: use --filter box or --filter-sampling importance"
        );
    }
    let meta = FilmMeta {
        fingerprint: plan.job.fingerprint(),
        shard: plan.shard,
        spp: settings.spp,
        tile: settings.tile_size,
        scene: plan
            .job
            .scene_path
            .as_ref()
            .map(|p| absolute(p).display().to_string())
            .unwrap_or_default(),
        overrides: plan.job.overrides.to_pairs(),
        output: absolute(&plan.output).display().to_string(),
    };

    // The scene is built; the film and the files are still to come.
    let memory = plan.job.memory();
    if let Some(free) = crate::job::available_memory()
        && memory.film + memory.files > free
    {
        eprintln!(
            "warning: the film and its files need about {:.0} MB, more than the {:.0} MB available; the render may fail (a smaller --width/--height needs less)",
            (memory.film + memory.files) as f64 / 1e6,
            free as f64 / 1e6
        );
    }
    let cancel = Arc::new(AtomicBool::new(false));
    let handler_flag = Arc::clone(&cancel);
    ctrlc::set_handler(move || {
        if handler_flag.swap(true, Ordering::SeqCst) {
            // A second signal: the user does not want to wait for the image and checkpoint.
            crate::output::remove_temporaries();
            std::process::exit(i32::from(INTERRUPTED));
        }
    })
    .context("cannot install the Ctrl-C handler")?;

    let scene = &plan.job.loaded.scene;
    let bar = ProgressBar::with_draw_target(Some(0), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {wide_bar} {percent:>3}% ETA {eta}",
        )
        .expect("a valid progress template"),
    );
    let started = std::time::Instant::now();
    let progress = |done: u64, total: u64| match settings.time_limit {
        // Against a time limit, the time is the progress.
        Some(limit) => {
            let limit = limit.as_millis() as u64;
            bar.set_length(limit);
            bar.set_position((started.elapsed().as_millis() as u64).min(limit));
        }
        None => {
            bar.set_length(total);
            bar.set_position(done);
        }
    };
    let warned = AtomicBool::new(false);
    let save = |film: &Film| {
        // Said at once, and once: the render goes on, but without crash safety.
        if let Err(e) = write_film(&plan.checkpoint, film, &meta)
            && !warned.swap(true, Ordering::Relaxed)
        {
            bar.suspend(|| {
                eprintln!("warning: the periodic checkpoint could not be written: {e:#}")
            });
        }
    };
    let every = args.checkpoint_every.map(|s| Checkpoints {
        every: Duration::from_secs_f64(s),
        write: &save,
    });
    let hooks = Hooks {
        cancel: &cancel,
        progress: &progress,
        checkpoint: every,
    };
    let rendered = render(scene, &settings, plan.start, &hooks)?;
    bar.finish_and_clear();
    let rays = rendered.stats.rays;
    if rays.nonfinite > 0 {
        let untraced = if rays.untraceable > 0 {
            format!(
                " ({} rays could not be traced: a non-finite origin or direction)",
                rays.untraceable
            )
        } else {
            String::new()
        };
        eprintln!(
            "warning: {} samples were NaN or infinite and were left out{untraced}",
            rays.nonfinite
        );
    }
    let overflowed = rendered.film.overflowed_pixels();
    if overflowed > 0 {
        eprintln!(
            "warning: {overflowed} pixels summed past single precision (radiance near 3e38 in the inputs) and were clamped to the largest finite value"
        );
    }
    let (w, h) = (scene.camera.width(), scene.camera.height());
    let (least, most) = rendered.samples_range;

    if rendered.complete {
        if plan.shard.count > 1 {
            write_film(&plan.output, &rendered.film, &meta)
        } else {
            write_image_as(
                &rendered.film,
                &plan.output,
                plan.format,
                plan.job.loaded.display,
            )
        }
        .with_context(|| format!("cannot write {}", plan.output.display()))?;
        let sampled = match adaptive {
            Some(a) => format!(
                "{} (threshold {}, depth {}): {:.2} corner rays per pixel",
                if a.block > 0 {
                    format!("quadtree of {}×{} blocks", 1 << a.block, 1 << a.block)
                } else {
                    "adaptive".to_string()
                },
                a.threshold,
                a.depth,
                rendered.stats.rays.camera as f64 / rendered.stats.samples.max(1) as f64
            ),
            None if rendered.timed_out => format!("{least}..{most} spp in the time limit"),
            None => format!("{} spp", settings.spp),
        };
        println!("{}", summary(&plan.output, w, h, &sampled, &rendered.stats));
        if settings.integrator == Integrator::Debug(DebugView::Cost) {
            println!("cost scale: {}", lucent::integrator::debug::COST_LEGEND);
        }
        if let (Some(map), Some(a)) = (&args.density_map, adaptive) {
            write_density_map(&rendered.density, w, h, a.depth, map)
                .with_context(|| format!("cannot write {}", map.display()))?;
        }
        // A finished render needs its checkpoint no more (only ever ours: see `plan_new`).
        if plan.checkpoint.is_file() {
            let _ = std::fs::remove_file(&plan.checkpoint);
        }
        return Ok(ExitCode::SUCCESS);
    }

    if matches!(settings.integrator, Integrator::Sppm(_)) {
        // The photon statistics are not in a film: what there is, is the image.
        write_image_as(
            &rendered.film,
            &plan.output,
            plan.format,
            plan.job.loaded.display,
        )
        .with_context(|| format!("cannot write {}", plan.output.display()))?;
        let reached = format!("{least} of {} iterations", settings.spp);
        println!("{}", summary(&plan.output, w, h, &reached, &rendered.stats));
        eprintln!(
            "interrupted after {reached}: wrote the image to {} (a photon-mapped render cannot be resumed)",
            plan.output.display()
        );
        return Ok(ExitCode::from(INTERRUPTED));
    }
    // Stopped: the checkpoint first, since it is what lets the work go on. An unfinished
    // shard writes nothing under its final name, so a batch script can tell it from a
    // finished one.
    write_film(&plan.checkpoint, &rendered.film, &meta)
        .with_context(|| format!("cannot write the checkpoint {}", plan.checkpoint.display()))?;
    let reached = format!("{least}..{most} of {} spp", settings.spp);
    let image = if plan.shard.count > 1 {
        "no partial film (the shard is unfinished)".to_string()
    } else {
        write_image_as(
            &rendered.film,
            &plan.output,
            plan.format,
            plan.job.loaded.display,
        )
        .with_context(|| format!("cannot write {}", plan.output.display()))?;
        println!("{}", summary(&plan.output, w, h, &reached, &rendered.stats));
        format!("the partial image to {}", plan.output.display())
    };
    eprintln!(
        "interrupted at {reached}: wrote {image} and the checkpoint {}; continue with: lucent render --resume {}",
        plan.checkpoint.display(),
        plan.checkpoint.display()
    );
    Ok(ExitCode::from(INTERRUPTED))
}

fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

fn default_checkpoint(output: &Path) -> PathBuf {
    let mut name = output
        .file_name()
        .map(|n| n.to_os_string())
        .unwrap_or_default();
    // Not `.exr`: a glob like `part-*.exr` for `lucent merge` must not pick it up.
    name.push(".checkpoint");
    output.with_file_name(name)
}

fn plan_new(args: &RenderArgs) -> anyhow::Result<Plan> {
    let shard = match &args.shard {
        Some(spec) => parse_shard(spec)?,
        None => Shard::default(),
    };
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from("render.png"));
    let format = output_format(&output, shard)?;
    let checkpoint = args
        .checkpoint
        .clone()
        .unwrap_or_else(|| default_checkpoint(&output));
    if checkpoint.exists() {
        bail!(
            "{} exists: continue that render with `lucent render --resume {}`, or delete it to start over",
            checkpoint.display(),
            checkpoint.display()
        );
    }
    check_files(&output, &checkpoint, args.scene.as_deref())?;
    let job = Job::load(args.scene.as_deref(), &args.overrides)?;
    check_shard_count(&job, shard)?;
    Ok(Plan {
        job,
        shard,
        start: None,
        output,
        format,
        checkpoint,
    })
}

fn plan_resume(args: &RenderArgs, ckpt: &Path) -> anyhow::Result<Plan> {
    // `--limit` alone may come with it: a large checkpoint may need a larger `film` budget.
    let given = crate::cli::Overrides {
        limits: Vec::new(),
        ..args.overrides.clone()
    };
    if args.scene.is_some() || given != Default::default() || args.shard.is_some() {
        bail!(
            "--resume takes the scene and its settings from the checkpoint: give no scene, settings (but --limit) or --shard with it"
        );
    }
    let limits = crate::cli::limits_of(&args.overrides.limits);
    // A finished shard is its own output: said from the header, before its pixels are read.
    let meta = crate::film_file::read_meta(ckpt, &limits)?;
    if absolute(Path::new(&meta.output)) == absolute(ckpt) {
        bail!(
            "{}: this is shard {}/{}'s finished partial film, not a checkpoint: it holds all its samples, and nothing is left to resume (combine the shards with `lucent merge`)",
            ckpt.display(),
            meta.shard.index,
            meta.shard.count
        );
    }
    let (film, meta) = read_film(ckpt, &limits)?;
    let mut overrides = crate::cli::Overrides::from_pairs(&meta.overrides)
        .map_err(|e| anyhow!("{}: {e}", ckpt.display()))?;
    // Budgets given now are applied after the checkpoint's own.
    overrides
        .limits
        .extend(args.overrides.limits.iter().cloned());
    let scene = (!meta.scene.is_empty()).then(|| PathBuf::from(&meta.scene));
    let job = Job::load(scene.as_deref(), &overrides)?;
    if job.fingerprint() != meta.fingerprint {
        bail!(
            "{}: the scene, a mesh file or a setting changed since this checkpoint was written; it cannot be resumed",
            ckpt.display()
        );
    }
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(&meta.output));
    let format = output_format(&output, meta.shard)?;
    let checkpoint = args
        .checkpoint
        .clone()
        .unwrap_or_else(|| ckpt.to_path_buf());
    check_files(&output, &checkpoint, scene.as_deref())?;
    Ok(Plan {
        job,
        shard: meta.shard,
        start: Some(film),
        output,
        format,
        checkpoint,
    })
}

/// Before any work: the output and the checkpoint are different files, neither is the scene,
/// and both folders take new files — so that no render's result is lost at its end.
fn check_files(output: &Path, checkpoint: &Path, scene: Option<&Path>) -> anyhow::Result<()> {
    let (out, ckpt) = (absolute(output), absolute(checkpoint));
    if out == ckpt {
        bail!(
            "the checkpoint and the output are the same file, {}: give --checkpoint another name",
            output.display()
        );
    }
    if let Some(scene) = scene.map(absolute)
        && (scene == out || scene == ckpt)
    {
        bail!(
            "{} is the scene file: it cannot also be the output or the checkpoint",
            scene.display()
        );
    }
    for path in [output, checkpoint] {
        crate::output::check_writable(path)?;
    }
    Ok(())
}

/// A shard count beyond the number of tiles would leave shards with nothing to do.
fn check_shard_count(job: &Job, shard: Shard) -> anyhow::Result<()> {
    let (c, s) = (&job.loaded.scene.camera, &job.loaded.settings);
    let tiles = c.width().div_ceil(s.tile_size) as u64 * c.height().div_ceil(s.tile_size) as u64;
    if u64::from(shard.count) > tiles {
        bail!(
            "--shard {}/{}: the image has only {tiles} tiles of {}×{} pixels to share out; use at most {tiles} shards",
            shard.index,
            shard.count,
            s.tile_size,
            s.tile_size
        );
    }
    Ok(())
}

/// The output's format; a shard's output must be a partial film (`.exr`).
fn output_format(output: &Path, shard: Shard) -> anyhow::Result<ImageFormat> {
    // Checked before the scene is read or rendered.
    let format = ImageFormat::from_path(output)?;
    if shard.count > 1 && format != ImageFormat::Exr {
        bail!(
            "a shard's output is a partial film for `lucent merge`: use -o PART.exr (got {})",
            output.display()
        );
    }
    Ok(format)
}

/// `I/N`, or `auto/N` with `I` from the batch system's task index.
pub fn parse_shard(spec: &str) -> anyhow::Result<Shard> {
    let bad = || anyhow!("--shard must be I/N with 0 ≤ I < N, or auto/N; got `{spec}`");
    let (i, n) = spec.split_once('/').ok_or_else(bad)?;
    let count: u32 = n.parse().map_err(|_| bad())?;
    let index: u32 = if i == "auto" {
        let (var, value) = ["SLURM_ARRAY_TASK_ID", "JOB_COMPLETION_INDEX"]
            .iter()
            .find_map(|v| std::env::var(v).ok().map(|x| (*v, x)))
            .ok_or_else(|| anyhow!("--shard auto/{n}: neither $SLURM_ARRAY_TASK_ID nor $JOB_COMPLETION_INDEX is set"))?;
        value
            .trim()
            .parse()
            .map_err(|_| anyhow!("--shard auto/{n}: ${var} is `{value}`, not a number"))?
    } else {
        i.parse().map_err(|_| bad())?
    };
    if count == 0 || index >= count {
        return Err(bad());
    }
    Ok(Shard { index, count })
}

/// The one statistics line printed after a render.
fn summary(output: &Path, w: u32, h: u32, samples: &str, s: &RenderStats) -> String {
    let r = &s.rays;
    let mut photons = String::new();
    if r.photons > 0 {
        photons += &format!(", photon {}", r.photons);
    }
    if r.scattered > 0 {
        photons += &format!(", scattered in media {}", r.scattered);
    }
    format!(
        "{}: {w}×{h}, {samples}, {} rays (camera {}, shadow {}, reflected {}, refracted {}{photons}), {:.3} s, {:.3} Mrays/s, {} threads",
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shard_specs() {
        assert_eq!(parse_shard("1/4").unwrap(), Shard { index: 1, count: 4 });
        for bad in ["4/4", "1/0", "x/3", "2", "-1/3"] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
    }
}
