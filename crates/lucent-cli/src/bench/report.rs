//! The benchmark's results: one row per scene and accelerator, as a table, CSV or JSON.

use lucent::accel::{AccelKind, TraversalStats};
use lucent::scene::{AccelReport, Scene};
use std::fmt::Write;
use std::path::Path;

/// One timed run over a ray set.
#[derive(Clone, Copy, Debug)]
pub struct Measurement {
    /// Rays traced.
    pub rays: u64,
    /// Wall time.
    pub seconds: f64,
    /// Rays that hit (closest hit) or were blocked (occlusion).
    pub hits: u64,
    /// Accelerator work.
    pub stats: TraversalStats,
}

impl Measurement {
    /// Million rays per second.
    pub fn mrays(&self) -> f64 {
        self.rays as f64 / self.seconds.max(1e-9) / 1e6
    }
}

/// One scene with one accelerator.
pub struct Row {
    /// The scene's file name.
    pub scene: String,
    /// Primitives of the scene: triangles as rendered, plus spheres.
    pub triangles: usize,
    /// The accelerator's size and build time.
    pub accel: AccelReport,
    /// (ray set, threads, result).
    pub measurements: Vec<(&'static str, usize, Measurement)>,
}

impl Row {
    /// A row with no measurements yet.
    pub fn new(path: &Path, scene: &Scene, accel: AccelReport) -> Self {
        let name = path.file_name().map_or_else(
            || path.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        );
        let c = scene.counts();
        Self {
            scene: name,
            triangles: c.triangles + c.spheres,
            accel,
            measurements: vec![],
        }
    }

    fn rate(&self, set: &str, threads: usize) -> Option<f64> {
        self.measurements
            .iter()
            .find(|(s, t, _)| *s == set && *t == threads)
            .map(|(_, _, m)| m.mrays())
    }

    fn bytes_per_prim(&self) -> f64 {
        self.accel.bytes as f64 / self.accel.primitives.max(1) as f64
    }

    /// One line for the progress log.
    pub fn summary(&self) -> String {
        let rates: Vec<String> = self
            .measurements
            .iter()
            .map(|(s, t, m)| format!("{s}/{t}t {:.2}", m.mrays()))
            .collect();
        format!(
            "{:<7} build {:>8.2} ms  {}",
            self.accel.kind.name(),
            self.accel.build_time.as_secs_f64() * 1e3,
            rates.join("  ")
        )
    }
}

/// The results as a text table: rates in million rays per second, and the speed-up over brute
/// force on the same scene and rays.
pub fn table(rows: &[Row], threads: &[usize]) -> String {
    let mut out = String::new();
    let sets = ["camera", "incoherent", "occlusion"];
    let mut header = format!(
        "{:<22} {:>9} {:<7} {:>10} {:>8} {:>6} {:>7}",
        "scene", "prims", "accel", "build ms", "nodes", "depth", "B/prim"
    );
    for set in sets {
        for t in threads {
            let _ = write!(header, " {:>12}", format!("{set} {t}t"));
        }
    }
    let _ = write!(header, " {:>10}", "vs brute");
    let _ = writeln!(out, "{header}");
    for row in rows {
        let mut line = format!(
            "{:<22} {:>9} {:<7} {:>10.2} {:>8} {:>6} {:>7.1}",
            truncate(&row.scene, 22),
            row.triangles,
            row.accel.kind.name(),
            row.accel.build_time.as_secs_f64() * 1e3,
            row.accel.nodes,
            row.accel.depth,
            row.bytes_per_prim()
        );
        for set in sets {
            for &t in threads {
                let _ = write!(
                    line,
                    " {:>12}",
                    row.rate(set, t).map_or("-".into(), |r| format!("{r:.3}"))
                );
            }
        }
        // Speed-up on incoherent rays with the most threads, against brute force on this scene.
        let t = threads.iter().copied().max().unwrap_or(1);
        let brute = rows
            .iter()
            .find(|r| r.scene == row.scene && r.accel.kind == AccelKind::BruteForce);
        let speedup =
            brute.and_then(|b| Some(row.rate("incoherent", t)? / b.rate("incoherent", t)?));
        let _ = write!(
            line,
            " {:>10}",
            speedup.map_or("-".into(), |s| format!("{s:.1}×"))
        );
        let _ = writeln!(out, "{line}");
    }
    out
}

fn truncate(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        s.chars().take(n - 1).chain(['…']).collect()
    }
}

/// One CSV line per scene, accelerator, ray set and thread count.
pub fn csv(rows: &[Row]) -> String {
    let mut out = String::from(
        "scene,primitives,accel,build_ms,nodes,depth,bytes_per_prim,rays_kind,threads,rays,seconds,mrays_per_s,hits,nodes_visited,primitives_tested\n",
    );
    for r in rows {
        for (set, threads, m) in &r.measurements {
            let _ = writeln!(
                out,
                "{},{},{},{:.3},{},{},{:.2},{set},{threads},{},{:.6},{:.4},{},{},{}",
                r.scene,
                r.triangles,
                r.accel.kind.name(),
                r.accel.build_time.as_secs_f64() * 1e3,
                r.accel.nodes,
                r.accel.depth,
                r.bytes_per_prim(),
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
    let mut items = Vec::new();
    for r in rows {
        for (set, threads, m) in &r.measurements {
            items.push(format!(
                "{{\"scene\":{:?},\"primitives\":{},\"accel\":\"{}\",\"build_ms\":{:.3},\"nodes\":{},\"depth\":{},\"bytes_per_prim\":{:.2},\"rays_kind\":\"{set}\",\"threads\":{threads},\"rays\":{},\"seconds\":{:.6},\"mrays_per_s\":{:.4},\"hits\":{},\"nodes_visited\":{},\"primitives_tested\":{}}}",
                r.scene,
                r.triangles,
                r.accel.kind.name(),
                r.accel.build_time.as_secs_f64() * 1e3,
                r.accel.nodes,
                r.accel.depth,
                r.bytes_per_prim(),
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
