//! The `[image]`, `[world]` and `[render]` tables.

use super::{Color, Finite};
use serde::{Deserialize, Serialize};
use toml::Spanned;

/// `[image]`.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct ImageDesc {
    /// Width in pixels (default 800).
    pub width: Spanned<u32>,
    /// Height in pixels (default 600).
    pub height: Spanned<u32>,
    /// Samples per pixel (default 1: through the pixel's centre; more: stratified jitter).
    pub samples: Spanned<u32>,
    /// The gamma of the colours' space: `v^gamma` is linear light (POV-Ray's
    /// `assumed_gamma`; default 1, linear).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gamma: Option<Spanned<Finite>>,
    /// The pixels written as the values are, without gamma correction (POV-Ray's scenes
    /// before 3.7 without `assumed_gamma`; default false).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub raw: Option<bool>,
}

impl Default for ImageDesc {
    fn default() -> Self {
        Self {
            width: Spanned::new(0..0, 800),
            height: Spanned::new(0..0, 600),
            samples: Spanned::new(0..0, 1),
            gamma: None,
            raw: None,
        }
    }
}

/// `[world]`.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct WorldDesc {
    /// Colour of rays that hit nothing (default black).
    pub background: Color,
    /// The ambient light `Ia` (default 0).
    pub ambient: Color,
}

impl Default for WorldDesc {
    fn default() -> Self {
        Self {
            background: Color(lucent::Rgb::BLACK),
            ambient: Color(lucent::Rgb::BLACK),
        }
    }
}

/// The integrators a scene file can name.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorName {
    /// Ray casting: flat diffuse colours.
    Raycast,
    /// Whitted ray tracing.
    #[default]
    Whitted,
    /// Path tracing: global illumination, area lights, soft shadows.
    Path,
    /// Stochastic progressive photon mapping: caustics.
    Sppm,
    /// Debug view: shading normals.
    #[serde(rename = "debug:normals")]
    DebugNormals,
    /// Debug view: distance.
    #[serde(rename = "debug:depth")]
    DebugDepth,
    /// Debug view: diffuse colour.
    #[serde(rename = "debug:albedo")]
    DebugAlbedo,
    /// Debug view: object ids.
    #[serde(rename = "debug:id")]
    DebugId,
    /// Debug view: barycentric weights.
    #[serde(rename = "debug:barycentrics")]
    DebugBarycentrics,
    /// Debug view: accelerator cost per ray.
    #[serde(rename = "debug:cost")]
    DebugCost,
}

/// The ray–triangle tests a scene file can name.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TriangleTestName {
    /// Woop, Benthin & Wald 2013.
    #[default]
    Watertight,
    /// The lecture notes' projection method.
    Projection,
}

/// How pixels are sampled (`[render] aa`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SamplingName {
    /// `[image] samples` stratified, jittered samples per pixel.
    #[default]
    Uniform,
    /// Whitted's adaptive supersampling at pixel corners.
    Adaptive,
    /// Corners of blocks of pixels first, then as `adaptive`.
    Quadtree,
}

/// Reconstruction filters (`[render] filter`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FilterName {
    /// One pixel, every sample weighted alike (default).
    #[default]
    Box,
    /// A tent (triangle) of radius 1.
    Tent,
    /// A Gaussian of standard deviation 0.5 and radius 2 (Mitsuba's default).
    Gaussian,
    /// Mitchell–Netravali, B = C = 1/3, radius 2.
    Mitchell,
}

/// How a filter other than the box weighs samples (`[render] filter_sampling`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FilterSamplingName {
    /// Into every pixel the filter reaches (default).
    #[default]
    Splat,
    /// Into its own pixel, placed in proportion to the filter.
    Importance,
}

/// `[render]`.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields, default)]
pub struct RenderDesc {
    /// `"raycast"` or `"whitted"` (default).
    pub integrator: IntegratorName,
    /// Deepest reflection/refraction bounce (default 10).
    pub max_depth: Spanned<u32>,
    /// Rays of smaller weight are not traced (default 1/256).
    pub min_weight: Spanned<Finite>,
    /// Seed of the random sample positions (default 0).
    pub seed: u64,
    /// Accelerator name (default: the fastest, `"wide"`).
    pub accelerator: Spanned<String>,
    /// `"watertight"` (default) or `"projection"`.
    pub triangle_test: TriangleTestName,
    /// Whitted: trace shadow rays (default true).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shadows: Option<Spanned<bool>>,
    /// `"uniform"` (default), `"adaptive"` or `"quadtree"`.
    pub aa: SamplingName,
    /// Adaptive and quadtree: the corners' difference that splits (default 0.1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aa_threshold: Option<Spanned<Finite>>,
    /// Adaptive and quadtree: how many times a pixel may be halved (default 3).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aa_depth: Option<Spanned<u32>>,
    /// Quadtree: blocks of 2^aa_block pixels a side (default 3).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aa_block: Option<Spanned<u32>>,
    /// The reconstruction filter: `"box"` (default), `"tent"`, `"gaussian"`, `"mitchell"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub filter: Option<Spanned<FilterName>>,
    /// The filter's radius in pixels (default: the filter's own).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub filter_radius: Option<Spanned<Finite>>,
    /// `"splat"` (default) or `"importance"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub filter_sampling: Option<Spanned<FilterSamplingName>>,
    /// Path: bounces before Russian roulette may end a path (default 5).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rr_depth: Option<Spanned<u32>>,
    /// Sppm: photons per iteration (default: one per pixel).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub photons: Option<Spanned<u32>>,
    /// Sppm: the first gather radius in scene units (default: three pixels at the scene's
    /// centre).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub photon_radius: Option<Spanned<Finite>>,
    /// Stop after this many seconds, whatever the samples (uniform sampling).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_limit: Option<Spanned<Finite>>,
}

impl Default for RenderDesc {
    fn default() -> Self {
        Self {
            integrator: IntegratorName::default(),
            max_depth: Spanned::new(0..0, 10),
            min_weight: Spanned::new(0..0, Finite(1.0 / 256.0)),
            seed: 0,
            accelerator: Spanned::new(0..0, lucent::accel::AccelKind::default().name().to_string()),
            triangle_test: TriangleTestName::default(),
            shadows: None,
            aa: SamplingName::default(),
            aa_threshold: None,
            aa_depth: None,
            aa_block: None,
            filter: None,
            filter_radius: None,
            filter_sampling: None,
            rr_depth: None,
            photons: None,
            photon_radius: None,
            time_limit: None,
        }
    }
}
