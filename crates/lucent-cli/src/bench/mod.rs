//! `lucent bench`: every accelerator on the same rays, in one run, in one table.
//!
//! For each scene and accelerator: build time, nodes, bytes per primitive, and million rays
//! per second for camera rays (1024×1024), incoherent rays (random origins in the scene's
//! bounds, random directions) and occlusion segments (random pairs of points in the bounds),
//! on each requested thread count. The flat structures (brute force, bounding volumes) test
//! every primitive for every ray, so they trace a subset of each set, sized to about 2^30
//! primitive tests (at least 256 rays), and their rate is measured on that subset. On a
//! scene of meshes alone the `wide` scene query is timed in turn with the triangle kernel and
//! the peers ([`single_ray`]), the way the ratios between them are read.

mod beam;
#[cfg(any(feature = "bench-embree", feature = "bench-obvhs"))]
mod peers;
mod rays;
mod report;
mod sampling;
mod shadow;
mod single_ray;

use crate::cli::BenchArgs;
use anyhow::{Context, bail};
use lucent::accel::AccelKind;
use lucent::scene::Scene;
use lucent_scene::{SceneFile, Spanned};
use rays::RaySet;
use report::{Measurement, Row, SETS};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Side of the square image the camera rays cover.
const CAMERA_SIDE: u32 = 1024;

/// Runs the benchmark.
pub fn run(args: &BenchArgs) -> anyhow::Result<ExitCode> {
    if args.sampling {
        let threads = args.threads.iter().copied().max().map_or(0, usize::from);
        return sampling::run(
            args.scenes.first().map(PathBuf::as_path),
            args.size,
            threads,
        );
    }
    let scenes = if args.scenes.is_empty() {
        default_scenes()?
    } else {
        args.scenes.clone()
    };
    let kinds: Vec<AccelKind> = if args.accel.is_empty() {
        AccelKind::ALL.to_vec()
    } else {
        args.accel.clone()
    };
    let threads: Vec<usize> = args.threads.iter().map(|&t| usize::from(t)).collect();
    let mut rows = Vec::new();
    let mut beam_rows = Vec::new();
    for path in &scenes {
        eprintln!("{}:", path.display());
        let name = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        let mut peer_job = None;
        // The `wide` scene and its row, when its queries are to be timed in turn with the
        // kernel and the peers (a scene of meshes alone).
        let mut in_turn: Option<(Scene, usize)> = None;
        for &kind in &kinds {
            let scene = load(path, kind)?;
            let report = scene.accel_report();
            let counts = scene.counts();
            let sets = [
                rays::camera_rays(&scene),
                rays::incoherent_rays(&scene, args.rays, args.seed),
                rays::occlusion_rays(&scene, args.rays, args.seed),
            ];
            let mut row = Row {
                scene: name.clone(),
                primitives: counts.triangles + counts.spheres,
                accel: kind.name().to_string(),
                build_ms: report.build_time.as_secs_f64() * 1e3,
                nodes: Some(report.nodes),
                depth: Some(report.depth),
                bytes_per_prim: Some(report.bytes as f64 / report.primitives.max(1) as f64),
                measurements: vec![],
            };
            let flat = matches!(kind, AccelKind::BruteForce | AccelKind::BoundingVolumes);
            let meshes_only = counts.spheres == 0 && counts.planes == 0 && counts.triangles > 0;
            let later = kind == AccelKind::Wide && meshes_only;
            for (name, set) in SETS.iter().zip(&sets).filter(|_| !later) {
                // Flat structures test every primitive as rendered (every instance's triangles).
                let rendered = counts.triangles + counts.spheres;
                let budget = if flat {
                    ((1usize << 30) / rendered.max(1)).clamp(256, set.rays.len())
                } else {
                    set.rays.len()
                };
                for &t in &threads {
                    let m = measure(&scene, set, budget, t, *name == "occlusion")?;
                    row.measurements.push((name, t, m));
                }
            }
            if !later {
                eprintln!("  {}", row.summary());
            }
            rows.push(row);
            if kind == AccelKind::Wide {
                for tile in beam::TILES {
                    for &t in &threads {
                        let (per_pixel, beam, packets) = beam::measure(&scene, tile, t)?;
                        eprintln!(
                            "  beam {tile}×{tile}/{t}t: per-pixel {:.3}, beam {:.3}, packets {:.3} Mrays/s",
                            per_pixel.mrays(),
                            beam.mrays(),
                            packets.mrays()
                        );
                        let shadow = shadow::measure(&scene, tile, t)?;
                        if let Some((p, b)) = &shadow {
                            eprintln!(
                                "  shadow beam {tile}×{tile}/{t}t: per-pixel {:.3}, beam {:.3} Mrays/s",
                                p.mrays(),
                                b.mrays()
                            );
                        }
                        beam_rows.push(beam::BeamRow {
                            scene: name.clone(),
                            tile,
                            threads: t,
                            per_pixel,
                            beam,
                            packets,
                            shadow,
                        });
                    }
                }
            }
            // Peers take a triangle soup: only scenes of meshes alone.
            if peer_job.is_none() && meshes_only {
                peer_job = Some((scene.world_triangles(), sets));
            }
            if later {
                in_turn = Some((scene, rows.len() - 1));
            }
        }
        if let Some((triangles, sets)) = &peer_job {
            // The scene query, the kernel and the peers (those compiled in), in turn.
            let mut contenders = vec![];
            if let Some((scene, row)) = &in_turn {
                let row = &rows[*row];
                contenders.push(single_ray::Contender {
                    name: row.accel.clone(),
                    build_ms: row.build_ms,
                    info: row
                        .nodes
                        .zip(row.depth)
                        .zip(row.bytes_per_prim)
                        .map(|((n, d), b)| (n, d, b)),
                    tracer: Box::new(single_ray::SceneQuery(scene)),
                });
            }
            contenders.push(single_ray::kernel(triangles));
            contenders.extend(build_peers(triangles)?);
            let mut measured =
                single_ray::measure_in_turn(&name, triangles.len(), &contenders, sets, &threads)?;
            if let Some((_, row)) = in_turn {
                rows[row].measurements = measured.remove(0).measurements;
            }
            rows.extend(measured);
        }
    }
    println!("{}", report::table(&rows, &threads));
    if !beam_rows.is_empty() {
        println!("{}", beam::table(&beam_rows));
    }
    if let Some(csv) = &args.csv {
        std::fs::write(csv, report::csv(&rows))
            .with_context(|| format!("cannot write {}", csv.display()))?;
    }
    if let Some(json) = &args.json {
        std::fs::write(json, report::json(&rows))
            .with_context(|| format!("cannot write {}", json.display()))?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The peers compiled in, built over the world-space `triangles`.
#[cfg(any(feature = "bench-embree", feature = "bench-obvhs"))]
fn build_peers(
    triangles: &[[glam::Vec3; 3]],
) -> anyhow::Result<Vec<single_ray::Contender<'static>>> {
    peers::build(triangles)
}

/// No peers: none is compiled in (see the `bench-peers` feature).
#[cfg(not(any(feature = "bench-embree", feature = "bench-obvhs")))]
fn build_peers(_: &[[glam::Vec3; 3]]) -> anyhow::Result<Vec<single_ray::Contender<'static>>> {
    Ok(vec![])
}

/// The example scenes and the shared meshes that are here.
fn default_scenes() -> anyhow::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    for dir in [
        root.join("examples"),
        lucent_scene::data_dir().join("meshes"),
    ] {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut found: Vec<PathBuf> = entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.extension().is_some_and(|e| e == "toml")
                    || lucent_scene::mesh_file::is_mesh_file(p)
            })
            .collect();
        found.sort();
        out.extend(found);
    }
    if out.is_empty() {
        bail!("no scenes given and none found in examples/ or the shared data folder");
    }
    Ok(out)
}

/// A scene (any format lucent reads) with accelerator `kind`, its camera at 1024×1024.
fn load(path: &Path, kind: AccelKind) -> anyhow::Result<Scene> {
    let mut file = SceneFile::read(path)?;
    file.desc.image.width = Spanned::new(0..0, CAMERA_SIDE);
    file.desc.image.height = Spanned::new(0..0, CAMERA_SIDE);
    file.desc.render.accelerator = Spanned::new(0..0, kind.name().to_string());
    Ok(file.build()?.scene)
}

/// Traces `count` rays of `set`, spread evenly over it, on `threads` threads; closest hit, or
/// any hit for occlusion sets.
fn measure(
    scene: &Scene,
    set: &RaySet,
    count: usize,
    threads: usize,
    occlusion: bool,
) -> anyhow::Result<Measurement> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    // A subset is spread evenly over the set (camera rays are in reading order: the first
    // rows alone would be all sky).
    let stride = (set.rays.len() / count.max(1)).max(1);
    Ok(pool.install(|| {
        Measurement::timed(count, |k, stats| {
            let i = (k * stride) % set.rays.len();
            let ray = &set.rays[i];
            if occlusion {
                scene.occluded(ray, set.t_max[i], stats)
            } else {
                scene.intersect(ray, stats).is_some()
            }
        })
    }))
}
