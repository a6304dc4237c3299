//! `lucent merge`: the partial films of a sharded render, combined into the image a single
//! process would have made, bit for bit — or a clear refusal.

use crate::cli::MergeArgs;
use crate::film_file::{FilmMeta, read_film};
use crate::output::{ImageFormat, write_image};
use anyhow::{Context, bail};
use lucent::film::Film;
use lucent::render::Shard;
use lucent::schedule::tiles;
use std::collections::HashMap;
use std::path::Path;
use std::process::ExitCode;

/// Checks that the parts belong together, that each is finished and holds only its own
/// tiles, and that they cover the work exactly once; then writes the image. Parts are read one
/// at a time, so merging needs the memory of two films, whatever the number of shards.
pub fn run(args: &MergeArgs) -> anyhow::Result<ExitCode> {
    let format = ImageFormat::from_path(&args.output)?;
    // Before any work: the merged image must not replace a shard, which would be lost (and a
    // later merge with it refused).
    if let Some(part) = args.parts.iter().find(|p| same_file(p, &args.output)) {
        bail!(
            "{} is one of the partial films being merged: give the merged image another name",
            part.display()
        );
    }
    crate::output::check_writable(&args.output)?;
    let limits = crate::cli::limits_of(&args.limits);
    let mut merged: Option<(Film, FilmMeta, &Path)> = None;
    let mut seen: HashMap<u32, &Path> = HashMap::new();
    for path in &args.parts {
        let (film, meta) = read_film(path, &limits)?;
        if let Some((total, first, first_path)) = &merged {
            let same = meta.fingerprint == first.fingerprint
                && (meta.spp, meta.tile, meta.shard.count)
                    == (first.spp, first.tile, first.shard.count)
                && (film.width(), film.height()) == (total.width(), total.height());
            if !same {
                bail!(
                    "{} is from another render than {} (scene, settings or shard count differ): refusing to merge",
                    path.display(),
                    first_path.display()
                );
            }
        }
        if let Some(other) = seen.insert(meta.shard.index, path) {
            bail!(
                "shard {}/{} is given twice: {} and {}",
                meta.shard.index,
                meta.shard.count,
                other.display(),
                path.display()
            );
        }
        check_part(path, &film, &meta)?;
        match &mut merged {
            Some((total, _, _)) => total.merge(&film),
            None => merged = Some((film, meta, path)),
        }
    }
    let Some((film, first, _)) = merged else {
        bail!("no partial films given");
    };
    let count = first.shard.count;
    let missing: Vec<String> = (0..count)
        .filter(|i| !seen.contains_key(i))
        .take(10)
        .map(|i| format!("{i}/{count}"))
        .collect();
    if !missing.is_empty() {
        let more = if count as usize - seen.len() > missing.len() {
            ", …"
        } else {
            ""
        };
        bail!(
            "shard{} {}{more} missing",
            if missing.len() > 1 { "s" } else { "" },
            missing.join(", ")
        );
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

/// A part must hold every sample of its own tiles and nothing elsewhere.
fn check_part(path: &Path, film: &Film, meta: &FilmMeta) -> anyhow::Result<()> {
    let shard = Shard {
        index: meta.shard.index,
        count: meta.shard.count,
    };
    for (i, t) in tiles(film.width(), film.height(), meta.tile)
        .iter()
        .enumerate()
    {
        let want = if shard.owns(i) { meta.spp } else { 0 };
        for y in t.y0..t.y1 {
            for x in t.x0..t.x1 {
                let n = film.samples(x, y);
                if n != want && want > 0 {
                    bail!(
                        "{} (shard {}/{}) is unfinished: pixel ({x}, {y}) has {n} of {} samples; finish it with `lucent render --resume` on its checkpoint",
                        path.display(),
                        shard.index,
                        shard.count,
                        meta.spp
                    );
                } else if n != want {
                    bail!(
                        "{} (shard {}/{}) holds samples outside its tiles, at pixel ({x}, {y}): it is not a shard's partial film",
                        path.display(),
                        shard.index,
                        shard.count
                    );
                }
            }
        }
    }
    Ok(())
}

/// Whether `a` and `b` name the same existing file (through links and `..` too).
fn same_file(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}
