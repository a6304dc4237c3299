//! Debug views: what a camera ray finds, shown as a colour — to see the algorithms at work.
//!
//! Each view traces the camera ray only (no lights, no secondary rays):
//! - `normals`: the unit shading normal `n` as `(n + 1) / 2` (facing the camera: pale blue);
//! - `depth`: the distance to the hit, from the nearest point of the scene's bounds (black) to
//!   their farthest corner (white), seen from the ray's origin; beyond, and misses, white (a
//!   scene of planes alone, without finite bounds: `1 − e^(−t/10)`);
//! - `albedo`: the surface's diffuse colour (`kd`, its texture and vertex colour); misses black;
//! - `id`: a colour per scene object, the same in every run;
//! - `barycentrics`: a triangle's weights of its corners A, B, C as red, green, blue (other
//!   shapes black);
//! - `cost`: the accelerator's work for the ray — interior nodes visited plus primitives tested
//!   — on a logarithmic colour scale (see [`COST_LEGEND`]).

use super::RayStats;
use crate::Rgb;
use crate::scene::Scene;
use lucent_accel::Ray;

/// What a debug view shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DebugView {
    /// Shading normals.
    Normals,
    /// Distance along the ray.
    Depth,
    /// Diffuse colour.
    Albedo,
    /// Object identity.
    Id,
    /// Triangle barycentric weights.
    Barycentrics,
    /// Accelerator work per ray.
    Cost,
}

impl DebugView {
    /// The integrator's name in scene files and on the command line: `debug:` and the view.
    pub fn name(self) -> &'static str {
        match self {
            DebugView::Normals => "debug:normals",
            DebugView::Depth => "debug:depth",
            DebugView::Albedo => "debug:albedo",
            DebugView::Id => "debug:id",
            DebugView::Barycentrics => "debug:barycentrics",
            DebugView::Cost => "debug:cost",
        }
    }
}

/// The colours of the cost scale, at costs 0, 4, 16, 64, 256, 1024 and 4096 and more: black,
/// blue, cyan, green, yellow, red, white. Between them, colours blend on a logarithmic scale.
const COST_STOPS: [[f32; 3]; 7] = [
    [0.0, 0.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [0.0, 1.0, 0.0],
    [1.0, 1.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 1.0],
];

/// The cost scale, in words (printed with a `cost` render).
pub const COST_LEGEND: &str = "nodes visited + primitives tested per camera ray, log scale: \
    black 0, blue 4, cyan 16, green 64, yellow 256, red 1024, white 4096 or more";

/// The colour of `cost` on the scale of [`COST_LEGEND`].
pub fn cost_color(cost: u64) -> Rgb {
    // Stop k sits at cost 4^k: position log4(1 + cost) along the stops.
    let x = ((1.0 + cost as f32).log2() / 2.0).min((COST_STOPS.len() - 1) as f32);
    let k = (x.floor() as usize).min(COST_STOPS.len() - 2);
    let f = x - k as f32;
    let (a, b) = (COST_STOPS[k], COST_STOPS[k + 1]);
    Rgb::new(
        a[0] + f * (b[0] - a[0]),
        a[1] + f * (b[1] - a[1]),
        a[2] + f * (b[2] - a[2]),
    )
}

/// A colour for object `id`: bright enough to tell from a miss, the same in every run.
pub fn id_color(id: u32) -> Rgb {
    let mut h = u64::from(id).wrapping_add(0x9E37_79B9_7F4A_7C15);
    h = (h ^ (h >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    h = (h ^ (h >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    h ^= h >> 31;
    let channel = |shift: u32| 0.2 + 0.8 * ((h >> shift) & 0xFF) as f32 / 255.0;
    Rgb::new(channel(0), channel(8), channel(16))
}

/// The colour `view` shows for `ray`.
pub fn radiance(view: DebugView, scene: &Scene, ray: &Ray, stats: &mut RayStats) -> Rgb {
    let before = stats.traversal;
    let hit = scene.intersect(ray, &mut stats.traversal);
    match view {
        DebugView::Cost => {
            let t = stats.traversal;
            let work = (t.nodes_visited - before.nodes_visited)
                + (t.primitives_tested - before.primitives_tested);
            cost_color(work)
        }
        DebugView::Depth => {
            let b = scene.bounds();
            let o = ray.origin;
            let far = (o - b.min).abs().max((o - b.max).abs()).length();
            let near = (b.min - o).max(o - b.max).max(glam::Vec3::ZERO).length();
            let d = hit.map_or(1.0, |h| {
                let t = h.t * ray.dir.length();
                if far > near && far.is_finite() {
                    ((t - near) / (far - near)).clamp(0.0, 1.0)
                } else {
                    // No finite bounds (only planes): 1 − e^(−t/10), grey 0.63 at 10 units.
                    1.0 - (-t / 10.0).exp()
                }
            });
            Rgb::gray(d)
        }
        _ => match hit {
            None => Rgb::BLACK,
            Some(h) => match view {
                DebugView::Normals => {
                    let n = (h.shading_normal + glam::Vec3::ONE) * 0.5;
                    Rgb::new(n.x, n.y, n.z)
                }
                DebugView::Albedo => scene.diffuse(&scene.materials[h.material as usize], &h),
                DebugView::Id => id_color(h.object),
                DebugView::Barycentrics => Rgb::from(h.bary),
                DebugView::Cost | DebugView::Depth => unreachable!("handled above"),
            },
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cost_scale_passes_its_stops() {
        assert_eq!(cost_color(0), Rgb::BLACK);
        let near = |a: Rgb, b: [f32; 3]| {
            (a.r - b[0]).abs() + (a.g - b[1]).abs() + (a.b - b[2]).abs() < 0.05
        };
        assert!(near(cost_color(3), [0.0, 0.0, 1.0]));
        assert!(near(cost_color(15), [0.0, 1.0, 1.0]));
        assert!(near(cost_color(255), [1.0, 1.0, 0.0]));
        assert!(near(cost_color(1023), [1.0, 0.0, 0.0]));
        assert_eq!(cost_color(1 << 20), Rgb::WHITE);
        // Grows monotonically in "heat": never back to black.
        assert!((1..2000).all(|c| cost_color(c) != Rgb::BLACK));
    }

    #[test]
    fn id_colours_are_stable_and_distinct() {
        assert_eq!(id_color(7), id_color(7));
        let colours: Vec<Rgb> = (0..50).map(id_color).collect();
        for (i, a) in colours.iter().enumerate() {
            assert!(a.max_channel() >= 0.2);
            for b in &colours[i + 1..] {
                assert_ne!(a, b);
            }
        }
    }
}
