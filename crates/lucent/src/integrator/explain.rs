//! The ray trees of one pixel's samples, as the lecture draws them: what `lucent explain` prints
//! and the Python package returns as nested dicts. Each sample is traced again by the Whitted
//! integrator with recording on, from the same camera ray the render traced.

use super::record::{RayNode, RayTree};
use super::{Integrator, RayStats};
use crate::Rgb;
use crate::render::{RenderSettings, Sampling};
use crate::sampling::pixel_offset;
use crate::scene::Scene;
use thiserror::Error;

/// Most samples whose trees are given at once (more would fill pages).
pub const MAX_EXPLAINED_SAMPLES: u32 = 64;

/// One sample's ray tree.
#[derive(Clone, Debug)]
pub struct ExplainedSample {
    /// Its index in the pixel.
    pub sample: u32,
    /// The film position its camera ray goes through.
    pub through: (f32, f32),
    /// The radiance it brings (NaN or infinite ones are left out of the film).
    pub radiance: Rgb,
    /// The camera ray and everything it spawned.
    pub root: RayNode,
}

/// Why a pixel cannot be explained.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ExplainError {
    /// Only the Whitted integrator records its rays.
    #[error("explain follows the Whitted integrator's rays; this scene uses `{0}`")]
    NotWhitted(&'static str),
    /// Adaptive sampling's corners are not samples of one pixel.
    #[error("explain follows uniform samples, not adaptive ones")]
    NotUniform,
    /// The pixel is not in the image.
    #[error("pixel {x},{y} is outside the {width}×{height} image")]
    Outside {
        /// Column asked for.
        x: u32,
        /// Row asked for.
        y: u32,
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
    },
    /// The sample is not among the pixel's.
    #[error("sample {sample} does not exist: the pixel has {spp} (0 to {})", spp - 1)]
    NoSuchSample {
        /// Sample asked for.
        sample: u32,
        /// Samples per pixel.
        spp: u32,
    },
    /// Too many samples to give every tree.
    #[error("the pixel has {0} samples, whose trees would fill pages")]
    TooManySamples(u32),
    /// The integrator recorded no tree (a bug).
    #[error("the ray tree of sample {0} was not recorded")]
    NotRecorded(u32),
}

/// The ray trees of pixel `(x, y)`'s samples (`Some(k)`: sample `k` alone), as `settings`
/// render them.
pub fn explain_pixel(
    scene: &Scene,
    settings: &RenderSettings,
    (x, y): (u32, u32),
    sample: Option<u32>,
) -> Result<Vec<ExplainedSample>, ExplainError> {
    let Integrator::Whitted(whitted) = settings.integrator else {
        return Err(ExplainError::NotWhitted(settings.integrator.name()));
    };
    if settings.sampling != Sampling::Uniform {
        return Err(ExplainError::NotUniform);
    }
    let (width, height) = (scene.camera.width(), scene.camera.height());
    if x >= width || y >= height {
        return Err(ExplainError::Outside {
            x,
            y,
            width,
            height,
        });
    }
    let spp = settings.spp;
    let samples = match sample {
        Some(k) if k >= spp => return Err(ExplainError::NoSuchSample { sample: k, spp }),
        Some(k) => k..k + 1,
        None if spp > MAX_EXPLAINED_SAMPLES => return Err(ExplainError::TooManySamples(spp)),
        None => 0..spp,
    };
    let pixel = u64::from(y) * u64::from(width) + u64::from(x);
    samples
        .map(|sample| {
            let (dx, dy) = pixel_offset(settings.seed, pixel, sample, spp);
            let through = (x as f32 + dx, y as f32 + dy);
            let ray = scene.camera.ray(through.0, through.1);
            let mut tree = RayTree::default();
            let radiance =
                whitted.radiance_recorded(scene, &ray, &mut RayStats::default(), &mut tree);
            Ok(ExplainedSample {
                sample,
                through,
                radiance,
                root: tree.root.ok_or(ExplainError::NotRecorded(sample))?,
            })
        })
        .collect()
}
