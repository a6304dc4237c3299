//! Stochastic progressive photon mapping (Hachisuka & Jensen 2009): caustics, even from point
//! lights through glass, which no path traced from the camera can find.
//!
//! Each iteration has two passes.
//!
//! 1. **Camera pass**: one path per pixel follows mirror and glass bounces to the first surface
//!    that is not a perfect mirror or perfect glass, its *visible point*; there direct light is
//!    gathered by light sampling (as the path tracer does, without MIS: the camera path ends),
//!    and what the path saw emitting along the way is added too.
//! 2. **Photon pass**: photons leave the lights ([`crate::light::emission`]) and scatter by the
//!    same BSDFs (in importance mode). Where one lands on a non-delta surface after at least one
//!    bounce — the first landing is direct light, already gathered — every visible point within
//!    its radius of the landing takes `Φ·f(wo, wi)`.
//!
//! Then each visible point's statistics are updated as the paper says: with `M` new photons,
//! `N' = N + αM`, `R' = R·√(N'/(N + M))`, `τ' = (τ + β·Φ)·R'²/R²` (α = 2/3), so the radius
//! shrinks and the estimate converges. After `K` iterations with `n` photons each, a pixel is
//! `Σ L_direct / K + τ / (K·n·π·R²)`.
//!
//! Unlike the other integrators this one is not a function of one camera ray: its estimate
//! depends on the visible points of every pixel: its state is an [`Estimate`] of the whole
//! image, whose iterations the renderer runs (`render/sppm.rs`). Deterministic: each camera path and each photon
//! draws from a [`Sampler`] keyed by (seed, pixel or photon, iteration), photons are traced in
//! fixed chunks whose deposits are added in chunk order, and the grid of visible points is
//! filled in pixel order — so the image does not depend on the number of threads.

use super::vertex::{Vertex, footprint_of_sample};
use super::{RayStats, UNTRACEABLE};
use crate::Rgb;
use crate::bsdf::Transport;
use crate::film::Film;
use crate::sampling::sobol::Sampler;
use crate::scene::Scene;
use glam::Vec3;
use rayon::prelude::*;

/// Settings of the photon mapper.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sppm {
    /// The deepest bounce of camera paths (through mirrors and glass) and of photons.
    pub max_depth: u32,
    /// Photons per iteration; 0 traces one per pixel.
    pub photons: u32,
    /// The visible points' first radius in scene units; 0 takes three pixels' width at the
    /// distance of the scene's centre.
    pub radius: f32,
}

impl Default for Sppm {
    fn default() -> Self {
        Self {
            max_depth: 10,
            photons: 0,
            radius: 0.0,
        }
    }
}

/// How fast the radius shrinks (the paper's α): the share of new photons kept.
const ALPHA: f32 = 2.0 / 3.0;
/// Photons traced together, whose deposits are added in order (fixed, for determinism).
const CHUNK: usize = 4096;

/// The most photons one iteration traces (2²⁴, a few seconds' work): more are clamped to it
/// (the scene reader refuses them). Within an iteration, each chunk checks for a stop request
/// and the time limit, so a long photon pass ends promptly; the interrupted iteration is
/// dropped whole, keeping the estimate that of complete iterations.
pub const MAX_PHOTONS_PER_ITERATION: u32 = 1 << 24;

/// One chunk's photon deposits (pixel, flux) and its rays.
type ChunkDeposits = (Vec<(u32, Rgb)>, RayStats);
/// Salt that keeps photon samplers apart from camera samplers.
const PHOTON_SALT: u64 = 0x5eed_f070_0f07_0f07;

/// A pixel's running estimate.
#[derive(Clone, Copy, Debug)]
struct PixelState {
    /// Sum of direct light over iterations.
    direct: Rgb,
    /// Accumulated flux (the paper's τ).
    tau: Rgb,
    /// Photon count (N).
    n: f32,
    /// Gather radius.
    radius: f32,
}

/// The visible point of a pixel in the current iteration.
struct VisiblePoint<'a> {
    vertex: Vertex<'a>,
    /// Throughput from the camera.
    beta: Rgb,
}

/// The photon mapper's running estimate of the image: every pixel's statistics, and the photons
/// an iteration traces. The renderer runs its iterations ([`Estimate::iterate`], in
/// `render/sppm.rs`) and makes its film ([`Estimate::film`]).
pub struct Estimate {
    state: Vec<PixelState>,
    photons: usize,
    width: u32,
    height: u32,
}

impl Estimate {
    /// No iterations yet, for `scene`'s camera: every pixel at the first radius.
    pub fn new(scene: &Scene, sppm: &Sppm) -> Self {
        let (width, height) = (scene.camera.width(), scene.camera.height());
        let pixels = width as usize * height as usize;
        let radius = if sppm.radius > 0.0 {
            sppm.radius
        } else {
            let b = scene.bounds();
            let distance = if b.is_empty() {
                1.0
            } else {
                (b.center() - scene.camera.eye()).length().max(1e-3)
            };
            3.0 * scene.camera.pixel_size_at(distance)
        };
        let photons = if sppm.photons == 0 {
            pixels
        } else {
            sppm.photons as usize
        }
        .min(MAX_PHOTONS_PER_ITERATION as usize);
        let state = vec![
            PixelState {
                direct: Rgb::BLACK,
                tau: Rgb::BLACK,
                n: 0.0,
                radius,
            };
            pixels
        ];
        Self {
            state,
            photons,
            width,
            height,
        }
    }

    /// Iteration `k` on `scene`: its camera pass, its photon pass, and the radii shrunk where
    /// photons arrived. `stop` is asked before each chunk of photons; when it says yes the
    /// iteration is dropped whole. Returns whether the iteration was taken, and the rays traced
    /// (a dropped iteration's camera rays).
    pub fn iterate(
        &mut self,
        scene: &Scene,
        seed: u64,
        sppm: &Sppm,
        k: u32,
        stop: &(dyn Fn() -> bool + Sync),
    ) -> (bool, RayStats) {
        let (pixels, photons, width) = (self.state.len(), self.photons, self.width);
        let mut stats = RayStats::default();
        // 1. Camera pass: a visible point and the direct light per pixel.
        let camera: Vec<(Option<VisiblePoint<'_>>, Rgb, RayStats)> = (0..pixels)
            .into_par_iter()
            .map(|i| camera_path(scene, seed, sppm, i, k, width))
            .collect();
        let mut points = Vec::with_capacity(pixels);
        let mut directs = Vec::with_capacity(pixels);
        for (vp, direct, s) in camera {
            directs.push(direct);
            stats += s;
            points.push(vp);
        }
        // 2. Photon pass: deposits near the visible points, chunk by chunk in order.
        let state = &self.state;
        let grid = Grid::new(&points, state);
        let chunks: Vec<Option<ChunkDeposits>> = (0..photons.div_ceil(CHUNK))
            .into_par_iter()
            .map(|c| {
                if stop() {
                    return None;
                }
                let mut deposits = Vec::new();
                let mut s = RayStats::default();
                for p in c * CHUNK..((c + 1) * CHUNK).min(photons) {
                    trace_photon(
                        scene,
                        seed,
                        sppm,
                        p,
                        k,
                        &grid,
                        &points,
                        state,
                        &mut deposits,
                        &mut s,
                    );
                }
                Some((deposits, s))
            })
            .collect();
        let Some(chunks) = chunks.into_iter().collect::<Option<Vec<_>>>() else {
            return (false, stats);
        };
        for (st, direct) in self.state.iter_mut().zip(directs) {
            st.direct += direct;
        }
        let mut flux = vec![Rgb::BLACK; pixels];
        let mut count = vec![0u32; pixels];
        for (deposits, s) in chunks {
            stats += s;
            for (i, phi) in deposits {
                flux[i as usize] += phi;
                count[i as usize] += 1;
            }
        }
        // 3. Shrink the radii where photons arrived.
        for (i, st) in self.state.iter_mut().enumerate() {
            let m = count[i] as f32;
            if m == 0.0 {
                continue;
            }
            let beta = points[i].as_ref().map_or(Rgb::BLACK, |p| p.beta);
            let n = st.n + ALPHA * m;
            let r = st.radius * (n / (st.n + m)).sqrt();
            st.tau = (st.tau + beta * flux[i]) * ((r * r) / (st.radius * st.radius));
            st.n = n;
            st.radius = r;
        }
        (true, stats)
    }

    /// The film of `iterations` complete iterations: each pixel's estimate as that many samples
    /// of weight 1, and the number of pixels whose estimate is not finite (left out).
    pub fn film(&self, iterations: u32) -> (Film, u64) {
        let (width, height) = (self.width, self.height);
        let mut film = Film::new(width, height);
        let mut nonfinite = 0;
        let k = iterations.max(1) as f32;
        let photons_total = f64::from(iterations) * self.photons as f64;
        for y in 0..height {
            for x in 0..width {
                let st = &self.state[(y * width + x) as usize];
                let area = std::f64::consts::PI * f64::from(st.radius) * f64::from(st.radius);
                let indirect = if photons_total > 0.0 {
                    st.tau * (1.0 / (photons_total * area)) as f32
                } else {
                    Rgb::BLACK
                };
                let value = st.direct / k + indirect;
                let finite = value.is_finite();
                nonfinite += u64::from(!finite && iterations > 0);
                // The estimate as `iterations` samples of weight 1.
                if iterations > 0 {
                    film.add_sample(x, y, finite.then_some(value), k);
                    film.count_samples(x, y, iterations - 1);
                }
            }
        }
        (film, nonfinite)
    }
}

/// The fraction of the shutter at which iteration `k` sees the scene: `k`'s bits reversed
/// (so that every run of iterations from the first spreads evenly over the shutter), turned by
/// an offset from the seed.
pub fn iteration_time(seed: u64, k: u32) -> f32 {
    let spread = (f64::from(k.reverse_bits()) / 2f64.powi(32)) as f32;
    let u = spread + crate::sampling::uniform(seed, u64::MAX, 0, 4);
    if u >= 1.0 { u - 1.0 } else { u }
}

/// The camera path of pixel `i` in iteration `k`: its visible point (if it reaches one) and
/// the light it gathers directly.
fn camera_path<'a>(
    scene: &'a Scene,
    seed: u64,
    sppm: &Sppm,
    i: usize,
    k: u32,
    width: u32,
) -> (Option<VisiblePoint<'a>>, Rgb, RayStats) {
    let mut stats = RayStats::default();
    let mut sampler = Sampler::new(seed, i as u64, k);
    let (x, y) = ((i % width as usize) as f32, (i / width as usize) as f32);
    let u = sampler.next_2d();
    let lens = sampler.next_2d();
    let mut ray = scene.camera.ray_through_lens(x + u.x, y + u.y, lens);
    stats.camera += 1;
    if !ray.is_traceable() {
        // As for the other integrators: NaN, so that the pixel is dropped and counted.
        return (None, Rgb::gray(f32::NAN), stats);
    }
    let mut from = None;
    let mut beta = Rgb::WHITE;
    let mut direct = Rgb::BLACK;
    for depth in 0..=sppm.max_depth {
        let u_light = (sampler.next_1d(), sampler.next_2d());
        let u_bsdf = (sampler.next_1d(), sampler.next_2d());
        let Some(hit) = scene.intersect_opaque(&ray, from, &mut stats.traversal) else {
            direct += beta * scene.background_along(ray.dir);
            break;
        };
        let footprint = footprint_of_sample(sampler.index());
        let m = &scene.materials[hit.material as usize];
        if m.emits_towards(hit.normal, ray.dir) {
            direct += beta * m.emission(&scene.tex_coords(m, &hit, footprint), &scene.images);
        }
        let v = Vertex::new(scene, ray.dir, hit, footprint);
        // A visible point gathers the BSDF's non-delta lobes; its Dirac lobes (mirrors, glass,
        // a smooth coat) are followed. A mixture picks one by the BSDF's own sampling: the
        // point then stands for its share, 1 − P(delta).
        let p_delta = v.bsdf.delta_share(v.wo);
        let stop = |beta: Rgb, v: Vertex<'a>, direct: &mut Rgb, stats: &mut RayStats| {
            *direct += beta * v.direct_light(scene, u_light, false, stats);
            Some(VisiblePoint { vertex: v, beta })
        };
        if p_delta <= 0.0 {
            let vp = stop(beta, v, &mut direct, &mut stats);
            return untraceable_dropped(vp, direct, stats);
        }
        if depth == sppm.max_depth {
            break;
        }
        let Some(b) = v.bounce(u_bsdf, Transport::Radiance, &mut stats) else {
            break;
        };
        if !b.sample.delta {
            let vp = stop(beta / (1.0 - p_delta), v, &mut direct, &mut stats);
            return untraceable_dropped(vp, direct, stats);
        }
        beta *= b.sample.weight;
        ray = b.ray;
        from = Some(b.from);
    }
    untraceable_dropped(None, direct, stats)
}

/// A camera path's visible point and direct light, unless one of its rays could not be
/// traced: then no point, and NaN direct light, so that the pixel's sample is dropped and
/// counted as the other integrators' are.
fn untraceable_dropped(
    vp: Option<VisiblePoint<'_>>,
    direct: Rgb,
    stats: RayStats,
) -> (Option<VisiblePoint<'_>>, Rgb, RayStats) {
    if stats.untraceable == 0 {
        (vp, direct, stats)
    } else {
        (None, UNTRACEABLE, stats)
    }
}

/// Traces photon `p` of iteration `k`, recording `(pixel, Φ·f)` for every visible point it
/// lands near.
#[allow(clippy::too_many_arguments)]
fn trace_photon(
    scene: &Scene,
    seed: u64,
    sppm: &Sppm,
    p: usize,
    k: u32,
    grid: &Grid,
    points: &[Option<VisiblePoint<'_>>],
    state: &[PixelState],
    deposits: &mut Vec<(u32, Rgb)>,
    stats: &mut RayStats,
) {
    let mut sampler = Sampler::new(seed ^ PHOTON_SALT, p as u64, k);
    let (u_pick, u_pos, u_dir) = (sampler.next_1d(), sampler.next_2d(), sampler.next_2d());
    let Some(photon) = scene.emitters.sample_photon(
        &scene.lights,
        scene.bounds(),
        |d| scene.background_along(d),
        u_pick,
        u_pos,
        u_dir,
    ) else {
        return;
    };
    let mut beta = photon.power;
    let mut ray = lucent_accel::Ray::new(photon.origin, photon.dir);
    let mut from = None;
    for depth in 0..=sppm.max_depth {
        let u_bsdf = (sampler.next_1d(), sampler.next_2d());
        let u_rr = sampler.next_1d();
        stats.photons += 1;
        let Some(hit) = scene.intersect_opaque(&ray, from, &mut stats.traversal) else {
            return;
        };
        // Photons have no pixel: their textures are looked up at a point.
        let v = Vertex::new(scene, ray.dir, hit, 0.0);
        if depth > 0 && !v.bsdf.is_delta() {
            grid.gather(v.hit.point, |i| {
                let Some(vp) = &points[i as usize] else {
                    return;
                };
                let d2 = (vp.vertex.hit.point - v.hit.point).length_squared();
                let r = state[i as usize].radius;
                if d2 <= r * r {
                    let f = vp.vertex.bsdf_value(-ray.dir, Transport::Radiance);
                    if !f.is_black() {
                        deposits.push((i, beta * f));
                    }
                }
            });
        }
        if depth == sppm.max_depth {
            return;
        }
        // Photon bounces count as photon rays (at the next intersection), not as these; a
        // bounce that cannot be traced ends the photon, counted.
        let mut bounce_stats = RayStats::default();
        let bounce = v.bounce(u_bsdf, Transport::Importance, &mut bounce_stats);
        stats.untraceable += bounce_stats.untraceable;
        let Some(b) = bounce else {
            return;
        };
        let next = beta * b.sample.weight;
        // Russian roulette in proportion to what the bounce kept (pbrt's rule).
        let q = (1.0 - next.max_channel() / beta.max_channel().max(1e-30)).max(0.0f32);
        if u_rr < q {
            return;
        }
        beta = next / (1.0 - q);
        ray = b.ray;
        from = Some(b.from);
    }
}

/// A hashed grid over the visible points: each point is listed in every cell its radius
/// reaches, so a photon looks in one cell only.
struct Grid {
    cell: f32,
    origin: Vec3,
    buckets: Vec<Vec<u32>>,
}

impl Grid {
    fn new(points: &[Option<VisiblePoint<'_>>], state: &[PixelState]) -> Self {
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut r_max = 0.0f32;
        let mut n = 0usize;
        for (p, st) in points.iter().zip(state) {
            if let Some(p) = p {
                lo = lo.min(p.vertex.hit.point);
                r_max = r_max.max(st.radius);
                n += 1;
            }
        }
        let cell = (2.0 * r_max).max(1e-6);
        let mut grid = Self {
            cell,
            origin: if n > 0 { lo } else { Vec3::ZERO },
            buckets: vec![Vec::new(); (2 * n).next_power_of_two().max(1)],
        };
        for (i, (p, st)) in points.iter().zip(state).enumerate() {
            let Some(p) = p else { continue };
            let (a, b) = (
                grid.cell_of(p.vertex.hit.point - Vec3::splat(st.radius)),
                grid.cell_of(p.vertex.hit.point + Vec3::splat(st.radius)),
            );
            for z in a[2]..=b[2] {
                for y in a[1]..=b[1] {
                    for x in a[0]..=b[0] {
                        let h = grid.bucket([x, y, z]);
                        // Two cells of a point may share a bucket: list it once (points go in
                        // in order, so a repeat is the bucket's last entry).
                        if grid.buckets[h].last() != Some(&(i as u32)) {
                            grid.buckets[h].push(i as u32);
                        }
                    }
                }
            }
        }
        grid
    }

    fn cell_of(&self, p: Vec3) -> [i32; 3] {
        let c = ((p - self.origin) / self.cell).floor();
        [c.x as i32, c.y as i32, c.z as i32]
    }

    fn bucket(&self, c: [i32; 3]) -> usize {
        let h = (c[0] as u32).wrapping_mul(73_856_093)
            ^ (c[1] as u32).wrapping_mul(19_349_663)
            ^ (c[2] as u32).wrapping_mul(83_492_791);
        h as usize & (self.buckets.len() - 1)
    }

    /// Calls `visit` with every visible point listed in the cell of `p` (a superset of those
    /// whose radius reaches `p`).
    fn gather(&self, p: Vec3, mut visit: impl FnMut(u32)) {
        if !p.is_finite() {
            return;
        }
        for &i in &self.buckets[self.bucket(self.cell_of(p))] {
            visit(i);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_radius_shrinks_as_the_paper_says() {
        // N = 0, M = 3 photons: N' = 2, R' = R·√(2/3).
        let (n, m, r) = (0.0f32, 3.0f32, 1.0f32);
        let n2 = n + ALPHA * m;
        assert!((n2 - 2.0).abs() < 1e-6);
        assert!((r * (n2 / (n + m)).sqrt() - (2.0f32 / 3.0).sqrt()).abs() < 1e-6);
    }
}
