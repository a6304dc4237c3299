//! `[[light]]` tables.

use super::{Color, Finite, Matrix, Point, Vector};
use serde::{Deserialize, Serialize};
use toml::Spanned;

/// The kinds of light. Area lights are objects whose material has an `emission`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LightKind {
    /// `position`, `intensity`, `falloff`.
    Point,
    /// `position`, `direction`, `intensity`, `falloff`, `cutoff`, `cutoff_start`: a point light
    /// shining into a cone.
    Spot,
    /// `direction`, `intensity`.
    Directional,
    /// `intensity`, `file`: light from every direction at infinity, constant or a lat-long
    /// image.
    Environment,
    /// `file` (an IES photometric file), `position`, `direction`, `front`, `intensity`,
    /// `falloff`: a point light as strong in each direction as the file's candela table says.
    Photometric,
}

impl LightKind {
    /// The name used in files.
    pub fn name(self) -> &'static str {
        match self {
            LightKind::Point => "point light",
            LightKind::Spot => "spot light",
            LightKind::Directional => "directional light",
            LightKind::Environment => "environment light",
            LightKind::Photometric => "photometric light",
        }
    }
}

/// Where an environment image's texels lie on the sphere (`lucent::texture::image::LatLongTexels`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum TexelsName {
    /// Centred in the cells of a `w × h` grid (lucent's default).
    #[default]
    Cells,
    /// Columns centred in their cells, rows from pole to pole (Mitsuba's `envmap`).
    Poles,
}

/// How a point light falls off.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum FalloffName {
    /// None: the classic model.
    #[default]
    None,
    /// `1 / d²`.
    Quadratic,
}

/// One `[[light]]`. Which keys apply depends on `type`; the others are refused in build.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LightDesc {
    /// `"point"`, `"spot"`, `"directional"` or `"environment"`.
    #[serde(rename = "type")]
    pub kind: LightKind,
    /// Intensity `I_j` (default 1); an environment's radiance (or its image's multiplier).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub intensity: Option<Color>,
    /// Point, spot: where it is.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub position: Option<Spanned<Point>>,
    /// Point, spot: `"none"` (default) or `"quadratic"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub falloff: Option<Spanned<FalloffName>>,
    /// Directional, spot: the direction the light travels in (non-zero). Photometric: where
    /// the luminaire's nadir points (default `[0, −1, 0]`, straight down).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<Spanned<Vector>>,
    /// Spot: the cone's half-angle in degrees, in (0, 90].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cutoff: Option<Spanned<Finite>>,
    /// Spot: the half-angle where the edge's smooth falloff starts (default `cutoff`: a hard
    /// edge).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cutoff_start: Option<Spanned<Finite>>,
    /// Environment: a lat-long (equirectangular) image, relative to the scene file's folder;
    /// +y is up, the image's centre column looks along −z. Photometric: an IES file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<Spanned<String>>,
    /// Environment: its orientation, a rotation (as a 4×4 matrix, row by row, whose
    /// translation is ignored): the image's +y and −z are turned to where it takes them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation: Option<Spanned<Matrix>>,
    /// Photometric: where the luminaire's length points (its `C = 0°` half-plane; default
    /// `[1, 0, 0]`, or `[0, 0, −1]` for a nadir along x), made perpendicular to `direction`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub front: Option<Spanned<Vector>>,
    /// Environment: where the image's texels lie (default `"cells"`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub texels: Option<Spanned<TexelsName>>,
}

impl LightDesc {
    /// A light of `kind` with every key missing.
    pub fn new(kind: LightKind) -> Self {
        Self {
            kind,
            intensity: None,
            position: None,
            falloff: None,
            direction: None,
            cutoff: None,
            cutoff_start: None,
            file: None,
            rotation: None,
            front: None,
            texels: None,
        }
    }
}
