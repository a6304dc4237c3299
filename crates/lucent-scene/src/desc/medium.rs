//! `[[medium]]` tables: participating media (see `docs/media.md`).

use super::{Color, Finite, Point};
use serde::{Deserialize, Serialize};
use toml::Spanned;

/// One `[[medium]]`: a homogeneous medium, by its absorption and scattering coefficients
/// (`sigma_a`, `sigma_s`) or by its extinction and single-scattering albedo (`sigma_t`,
/// `albedo`: Mitsuba's terms), each a number or `[r, g, b]` per unit of scene length, times
/// `scale`; `g` is the Henyey–Greenstein mean cosine (0: isotropic). With `density` (a grid
/// file) the medium is heterogeneous: the coefficients are its values at density 1.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MediumDesc {
    /// The name objects and the camera refer to it by.
    pub name: Spanned<String>,
    /// Absorption per unit length (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_a: Option<Spanned<Color>>,
    /// Scattering per unit length (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_s: Option<Spanned<Color>>,
    /// Extinction per unit length, with `albedo` (instead of `sigma_a` and `sigma_s`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sigma_t: Option<Spanned<Color>>,
    /// The share of extinction that scatters, each channel in [0, 1] (default 0.8 with
    /// `sigma_t`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo: Option<Spanned<Color>>,
    /// Multiplies the coefficients (default 1): the density.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<Spanned<Finite>>,
    /// The phase function's mean cosine, in (−1, 1) (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub g: Option<Spanned<Finite>>,
    /// A heterogeneous medium's density: a Mitsuba `.vol` grid file of one channel, relative
    /// to the scene file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<Spanned<String>>,
    /// A heterogeneous medium's albedo at each point: a `.vol` file of one or three channels
    /// (each in [0, 1]) over the same box as `density`; it replaces `albedo` (or the share of
    /// `sigma_s` in `sigma_a + sigma_s`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub albedo_grid: Option<Spanned<String>>,
    /// The box `[min, max]` the grids span (default: the box the density file gives).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bounds: Option<Spanned<[Point; 2]>>,
}

impl MediumDesc {
    /// A medium named `name` with every coefficient missing.
    pub fn new(name: &str) -> Self {
        Self {
            name: Spanned::new(0..0, name.to_string()),
            sigma_a: None,
            sigma_s: None,
            sigma_t: None,
            albedo: None,
            scale: None,
            g: None,
            density: None,
            albedo_grid: None,
            bounds: None,
        }
    }
}
