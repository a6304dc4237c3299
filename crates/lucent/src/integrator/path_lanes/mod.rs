//! Paths in lanes: the path tracer run on up to eight paths at once, bounce by bounce, with the
//! shading of the surfaces that lanes know ([`LaneMaterials`]: Lambertian surfaces, any albedo
//! texture, smooth conductors and smooth glass) done for all of them together in
//! [`wide::f32x8`] lanes, and everything else per path by the scalar path tracer's own steps
//! (`PathTracer::arrive`, the scalar scatter, `light_through`, `leave`, `PathTracer::go_on`).
//! `surfaces.rs` says which materials lanes know, `scatter.rs` how a group of paths scatters.
//!
//! The lane code is the scalar code: the shading frame, Lambert's value, density and sample, the
//! facing test, a triangle light's sample and the Sobol scrambles are written once (over
//! [`crate::lanes::Real`], or as loops over lanes) and run by the scalar path tracer too. A path traced in a
//! lane therefore gets exactly the bits it gets alone — the test
//! `lanes_give_the_scalar_paths_bits` holds the two to that — and an image is the same with
//! lanes or without, on any number of threads.

mod lobes;
mod rough;
mod scatter;
mod surfaces;
#[cfg(test)]
mod tests;

pub use surfaces::LaneMaterials;

use arrayvec::ArrayVec;

use super::path::{Arrival, Path, PathTracer};
use super::{RayStats, UNTRACEABLE};
use crate::Rgb;
use crate::lanes::LANES;
use crate::sampling::sobol::Sampler;
use crate::scene::{Beam, Scene};
use crate::shape::SurfaceHit;
use lucent_accel::Ray;
use surfaces::{LaneBsdf, bsdf_at};

/// A path of a lane group that arrived at a surface lanes know this bounce.
struct LaneHit {
    /// Its lane.
    lane: usize,
    hit: SurfaceHit,
    at: Arrival,
    bsdf: LaneBsdf,
    two_sided: bool,
}

impl PathTracer {
    /// [`PathTracer::radiance_in`] for up to [`LANES`] camera rays at once (`samplers[i]` is
    /// ray `i`'s): the same radiance for each, bit for bit.
    ///
    /// On a processor with AVX2 the lanes' code is compiled for it (eight lanes a register,
    /// the Sobol scrambles' multiplications in vectors); the arithmetic is the same IEEE
    /// arithmetic (no fused multiply–adds), so the bits are the same either way.
    pub fn radiance_lanes(
        &self,
        scene: &Scene,
        lanes: &LaneMaterials<'_>,
        beam: Option<&Beam>,
        rays: &[Ray],
        samplers: &mut [Sampler],
        stats: &mut RayStats,
    ) -> ArrayVec<Rgb, LANES> {
        #[cfg(target_arch = "x86_64")]
        if std::is_x86_feature_detected!("avx2") {
            // SAFETY: `radiance_lanes_avx2` is compiled for AVX2, which the processor has.
            #[allow(unsafe_code)]
            return unsafe { self.radiance_lanes_avx2(scene, lanes, beam, rays, samplers, stats) };
        }
        self.radiance_lanes_with(scene, lanes, beam, rays, samplers, stats)
    }

    /// [`PathTracer::radiance_lanes`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn radiance_lanes_avx2(
        &self,
        scene: &Scene,
        lanes: &LaneMaterials<'_>,
        beam: Option<&Beam>,
        rays: &[Ray],
        samplers: &mut [Sampler],
        stats: &mut RayStats,
    ) -> ArrayVec<Rgb, LANES> {
        self.radiance_lanes_with(scene, lanes, beam, rays, samplers, stats)
    }

    /// The body of [`PathTracer::radiance_lanes`], inlined into each instruction set's version.
    #[inline(always)]
    fn radiance_lanes_with(
        &self,
        scene: &Scene,
        lanes: &LaneMaterials<'_>,
        beam: Option<&Beam>,
        rays: &[Ray],
        samplers: &mut [Sampler],
        stats: &mut RayStats,
    ) -> ArrayVec<Rgb, LANES> {
        let n = rays.len();
        assert!(
            n <= LANES && samplers.len() == n,
            "{n} rays, {} samplers",
            samplers.len()
        );
        let mut paths: ArrayVec<Path, LANES> = rays.iter().map(Path::new).collect();
        let mut alive: u32 = (1 << n) - 1;
        // Lanes whose path met a ray it could not trace: their estimate is dropped.
        let mut untraceable = 0u32;
        while alive != 0 {
            let mut batch = ArrayVec::<LaneHit, LANES>::new();
            let bounce_alive = alive;
            for lane in (0..n).filter(|&i| bounce_alive & (1 << i) != 0) {
                let before = stats.untraceable;
                let sampler = &mut samplers[lane];
                let go_on = self.arrive(
                    scene,
                    beam,
                    &mut paths[lane],
                    sampler,
                    stats,
                    |path, hit, at, stats| match lanes.get(hit.material) {
                        Some(m) => {
                            batch.push(LaneHit {
                                lane,
                                bsdf: bsdf_at(scene, m, &hit, at.footprint),
                                two_sided: m.two_sided,
                                hit,
                                at,
                            });
                            true
                        }
                        None => self.scatter(scene, path, hit, at, stats),
                    },
                );
                if !go_on {
                    alive &= !(1 << lane);
                }
                if stats.untraceable != before {
                    untraceable |= 1 << lane;
                }
            }
            if !batch.is_empty() {
                alive &= !self.scatter_lanes(scene, &batch, &mut paths, &mut untraceable, stats);
            }
        }
        paths
            .iter()
            .enumerate()
            .map(|(i, p)| {
                if untraceable & (1 << i) != 0 {
                    UNTRACEABLE
                } else {
                    p.l
                }
            })
            .collect()
    }
}
