//! The benchmark's results: one row per scene and structure (ours or a peer's), as a table,
//! CSV or JSON.

use lucent::accel::TraversalStats;
use std::fmt::Write;

/// One timed run over a ray set.
#[derive(Clone, Copy, Debug, Default)]
pub struct Measurement {
    /// Rays traced.
    pub rays: u64,
    /// Wall time.
    pub seconds: f64,
    /// Rays that hit (closest hit) or were blocked (occlusion).
    pub hits: u64,
    /// Accelerator work (zero for peers, which do not report it).
    pub stats: TraversalStats,
}

impl Measurement {
    /// Times `count` queries on the current thread pool: `query(k, stats)` runs the `k`-th and
    /// says whether it hit (or was blocked).
    pub fn timed(
        count: usize,
        query: impl Fn(usize, &mut TraversalStats) -> bool + Sync,
    ) -> Measurement {
        use rayon::prelude::*;
        let start = std::time::Instant::now();
        let (hits, stats) = (0..count)
            .into_par_iter()
            .with_min_len(1024)
            .fold(
                || (0u64, TraversalStats::default()),
                |(hits, mut stats), k| {
                    let hit = query(k, &mut stats);
                    (hits + u64::from(hit), stats)
                },
            )
            .reduce(
                || (0, TraversalStats::default()),
                |(h1, mut s1), (h2, s2)| {
                    s1 += s2;
                    (h1 + h2, s1)
                },
            );
        Measurement {
            rays: count as u64,
            seconds: start.elapsed().as_secs_f64(),
            hits,
            stats,
        }
    }

    /// Two runs as one: rays, time, hits and work added.
    pub fn plus(mut self, other: Measurement) -> Measurement {
        self.rays += other.rays;
        self.seconds += other.seconds;
        self.hits += other.hits;
        self.stats += other.stats;
        self
    }

    /// Million rays per second.
    pub fn mrays(&self) -> f64 {
        self.rays as f64 / self.seconds.max(1e-9) / 1e6
    }
}

/// One scene with one structure.
pub struct Row {
    /// The scene's file name.
    pub scene: String,
    /// Primitives of the scene (triangles as rendered, plus spheres).
    pub primitives: usize,
    /// The structure: one of ours by its `--accel` name, or a peer's name.
    pub accel: String,
    /// Build time in milliseconds.
    pub build_ms: f64,
    /// Nodes, depth and bytes per primitive, where known.
    pub nodes: Option<usize>,
    /// See `nodes`.
    pub depth: Option<usize>,
    /// See `nodes`.
    pub bytes_per_prim: Option<f64>,
    /// (ray set, threads, result).
    pub measurements: Vec<(&'static str, usize, Measurement)>,
}

/// The ray sets, by name, in table order.
pub const SETS: [&str; 3] = ["camera", "incoherent", "occlusion"];

/// The peers, by row name.
pub const PEERS: [&str; 2] = ["embree3", "obvhs"];

/// Our structures compared with the peers: the default accelerator through the whole scene
/// query, and its triangle kernel alone (like for like with the peers' single-ray queries).
pub const OURS: [&str; 2] = ["wide", KERNEL];

/// The row name of the kernel alone.
pub const KERNEL: &str = "wide-kernel";

impl Row {
    /// The rate of a ray set on a thread count.
    pub fn rate(&self, set: &str, threads: usize) -> Option<f64> {
        self.measurements
            .iter()
            .find(|(s, t, _)| *s == set && *t == threads)
            .map(|(_, _, m)| m.mrays())
    }

    /// One line for the progress log.
    pub fn summary(&self) -> String {
        let rates: Vec<String> = self
            .measurements
            .iter()
            .map(|(s, t, m)| format!("{s}/{t}t {}", rate(m.mrays())))
            .collect();
        format!(
            "{:<7} build {:>8.2} ms  {}",
            self.accel,
            self.build_ms,
            rates.join("  ")
        )
    }
}

fn opt<T: std::fmt::Display>(v: Option<T>) -> String {
    v.map_or("-".into(), |v| v.to_string())
}

/// The results as a text table (rates in million rays per second; the last column is the
/// speed-up over brute force on incoherent rays), followed by the ratios of our fastest
/// structure to each peer, where peers were measured.
pub fn table(rows: &[Row], threads: &[usize]) -> String {
    let mut out = String::new();
    let mut header = format!(
        "{:<22} {:>9} {:<11} {:>10} {:>8} {:>6} {:>7}",
        "scene", "prims", "accel", "build ms", "nodes", "depth", "B/prim"
    );
    for set in SETS {
        for t in threads {
            let _ = write!(header, " {:>12}", format!("{set} {t}t"));
        }
    }
    let _ = write!(header, " {:>10}", "vs brute");
    let _ = writeln!(out, "{header}");
    let t_max = threads.iter().copied().max().unwrap_or(1);
    for row in rows {
        let mut line = format!(
            "{:<22} {:>9} {:<11} {:>10.2} {:>8} {:>6} {:>7}",
            truncate(&row.scene, 22),
            row.primitives,
            row.accel,
            row.build_ms,
            opt(row.nodes),
            opt(row.depth),
            opt(row.bytes_per_prim.map(|b| format!("{b:.1}")))
        );
        for set in SETS {
            for &t in threads {
                let _ = write!(line, " {:>12}", opt(row.rate(set, t).map(rate)));
            }
        }
        let brute = rows
            .iter()
            .find(|r| r.scene == row.scene && r.accel == "brute");
        let speedup =
            brute.and_then(|b| Some(row.rate("incoherent", t_max)? / b.rate("incoherent", t_max)?));
        let _ = write!(line, " {:>10}", opt(speedup.map(|s| format!("{s:.1}×"))));
        let _ = writeln!(out, "{line}");
    }
    let ratios = peer_ratios(rows, threads);
    if !ratios.is_empty() {
        let _ = writeln!(
            out,
            "\nratios to each peer (above 1: lucent is faster), same rays, same run:"
        );
        out.push_str(&ratios);
    }
    out
}

fn peer_ratios(rows: &[Row], threads: &[usize]) -> String {
    let mut out = String::new();
    for ours in rows.iter().filter(|r| OURS.contains(&r.accel.as_str())) {
        for peer in rows
            .iter()
            .filter(|r| r.scene == ours.scene && PEERS.contains(&r.accel.as_str()))
        {
            let mut line = format!(
                "{:<22} {:<11} vs {:<8} build {:>6.2}×",
                truncate(&ours.scene, 22),
                ours.accel,
                peer.accel,
                peer.build_ms / ours.build_ms.max(1e-9)
            );
            for set in SETS {
                for &t in threads {
                    let ratio = ours.rate(set, t).zip(peer.rate(set, t)).map(|(a, b)| a / b);
                    let _ = write!(
                        line,
                        "  {set} {t}t {}",
                        opt(ratio.map(|r| format!("{r:.2}×")))
                    );
                }
            }
            let _ = writeln!(out, "{line}");
        }
    }
    out
}

/// A rate with three significant digits (the flat structures on large scenes run at a few
/// thousand rays per second).
fn rate(r: f64) -> String {
    if r >= 1.0 || r == 0.0 {
        format!("{r:.3}")
    } else {
        format!("{r:.3e}")
    }
}

fn truncate(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        s.chars().take(n - 1).chain(['…']).collect()
    }
}

const CSV_HEADER: &str = "scene,primitives,accel,build_ms,nodes,depth,bytes_per_prim,rays_kind,threads,rays,seconds,mrays_per_s,hits,nodes_visited,primitives_tested";

/// One CSV line per scene, structure, ray set and thread count.
pub fn csv(rows: &[Row]) -> String {
    let mut out = format!("{CSV_HEADER}\n");
    for r in rows {
        for (set, threads, m) in &r.measurements {
            let _ = writeln!(
                out,
                "{},{},{},{:.3},{},{},{},{set},{threads},{},{:.6},{:.6},{},{},{}",
                r.scene,
                r.primitives,
                r.accel,
                r.build_ms,
                r.nodes.map_or(String::new(), |n| n.to_string()),
                r.depth.map_or(String::new(), |n| n.to_string()),
                r.bytes_per_prim
                    .map_or(String::new(), |b| format!("{b:.2}")),
                m.rays,
                m.seconds,
                m.mrays(),
                m.hits,
                m.stats.nodes_visited,
                m.stats.primitives_tested
            );
        }
    }
    out
}

/// The same records as [`csv`], as a JSON array of objects.
pub fn json(rows: &[Row]) -> String {
    let num = |v: Option<String>| v.unwrap_or_else(|| "null".into());
    let mut items = Vec::new();
    for r in rows {
        for (set, threads, m) in &r.measurements {
            items.push(format!(
                "{{\"scene\":{:?},\"primitives\":{},\"accel\":{:?},\"build_ms\":{:.3},\"nodes\":{},\"depth\":{},\"bytes_per_prim\":{},\"rays_kind\":\"{set}\",\"threads\":{threads},\"rays\":{},\"seconds\":{:.6},\"mrays_per_s\":{:.6},\"hits\":{},\"nodes_visited\":{},\"primitives_tested\":{}}}",
                r.scene,
                r.primitives,
                r.accel,
                r.build_ms,
                num(r.nodes.map(|n| n.to_string())),
                num(r.depth.map(|n| n.to_string())),
                num(r.bytes_per_prim.map(|b| format!("{b:.2}"))),
                m.rays,
                m.seconds,
                m.mrays(),
                m.hits,
                m.stats.nodes_visited,
                m.stats.primitives_tested
            ));
        }
    }
    format!("[\n  {}\n]\n", items.join(",\n  "))
}
