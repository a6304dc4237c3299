//! `lucent merge`: the partial films of a sharded render, combined into the image a single
//! process would have made, bit for bit — or a clear refusal.

use crate::cli::MergeArgs;
use crate::film_file::read_film;
use crate::output::{ImageFormat, write_image};
use anyhow::{Context, bail};
use std::process::ExitCode;

/// Checks that the parts belong together and cover the work exactly once, then writes the image.
pub fn run(args: &MergeArgs) -> anyhow::Result<ExitCode> {
    let format = ImageFormat::from_path(&args.output)?;
    let mut parts = Vec::new();
    for path in &args.parts {
        let (film, meta) = read_film(path)?;
        parts.push((path, film, meta));
    }
    let (first_path, first_film, first) = &parts[0];
    let count = first.shard.count;
    let mut seen: Vec<Option<&std::path::Path>> = vec![None; count as usize];
    for (path, film, meta) in &parts {
        let same = meta.fingerprint == first.fingerprint
            && meta.spp == first.spp
            && meta.shard.count == count;
        if !same || (film.width(), film.height()) != (first_film.width(), first_film.height()) {
            bail!(
                "{} is from another render than {} (scene, settings or shard count differ): refusing to merge",
                path.display(),
                first_path.display()
            );
        }
        let slot = &mut seen[meta.shard.index as usize];
        if let Some(other) = slot {
            bail!(
                "shard {}/{count} is given twice: {} and {}",
                meta.shard.index,
                other.display(),
                path.display()
            );
        }
        *slot = Some(path.as_path());
    }
    let missing: Vec<String> = seen
        .iter()
        .enumerate()
        .filter(|(_, s)| s.is_none())
        .map(|(i, _)| format!("{i}/{count}"))
        .collect();
    if !missing.is_empty() {
        bail!(
            "shard{} {} missing",
            if missing.len() > 1 { "s" } else { "" },
            missing.join(", ")
        );
    }
    let mut film = first_film.clone();
    for (_, f, _) in &parts[1..] {
        film.merge(f);
    }
    // Every pixel belongs to exactly one shard; each must have finished its samples.
    for y in 0..film.height() {
        for x in 0..film.width() {
            let n = film.samples(x, y);
            if n != first.spp {
                bail!(
                    "pixel ({x}, {y}) has {n} of {} samples: a shard stopped early (resume it with `lucent render --resume` on its checkpoint) or overlaps another",
                    first.spp
                );
            }
        }
    }
    write_image(&film, &args.output, format)
        .with_context(|| format!("cannot write {}", args.output.display()))?;
    println!(
        "{}: merged {count} shards, {}×{}, {} spp",
        args.output.display(),
        film.width(),
        film.height(),
        first.spp
    );
    Ok(ExitCode::SUCCESS)
}
