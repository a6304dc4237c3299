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
    /// `file` (an image of intensity over the sphere), `mapping`, `position`, `up`, `front`,
    /// `intensity`, `falloff`.
    Goniometric,
    /// `file` (an image), `position`, `direction`, `up`, `fov`, `intensity`, `falloff`: an
    /// image thrown through a frustum.
    Projection,
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
            LightKind::Goniometric => "goniometric light",
            LightKind::Projection => "projection light",
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

/// How a goniometric light's image lies on the sphere (`lucent::light::Mapping`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
pub enum MappingName {
    /// pbrt-v4's equal-area square.
    #[default]
    #[serde(rename = "equal-area")]
    EqualArea,
    /// Latitude and longitude.
    #[serde(rename = "latlong")]
    LatLong,
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
    /// Directional, spot, projection: the direction the light travels in (non-zero).
    /// Photometric: where the luminaire's nadir points (default `[0, −1, 0]`, straight down).
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
    /// Goniometric, projection: the image of intensities. Spot: an image across the cone.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub file: Option<Spanned<String>>,
    /// Environment: its orientation, a rotation (as a 4×4 matrix, row by row, whose
    /// translation is ignored): the image's +y and −z are turned to where it takes them.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotation: Option<Spanned<Matrix>>,
    /// Photometric: where the luminaire's length points (its `C = 0°` half-plane; default
    /// `[1, 0, 0]`, or `[0, 0, −1]` for a nadir along x), made perpendicular to `direction`.
    /// Goniometric: where the map's `+x` lies about `up` (default `[1, 0, 0]`, or `[0, 0, −1]`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub front: Option<Spanned<Vector>>,
    /// Environment: where the image's texels lie (default `"cells"`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub texels: Option<Spanned<TexelsName>>,
    /// Goniometric: how the image lies on the sphere (default `"equal-area"`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mapping: Option<Spanned<MappingName>>,
    /// Goniometric: the pole of the image's map (default `[0, 1, 0]`). Projection: the image's
    /// up (default `[0, 1, 0]`), made perpendicular to `direction`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub up: Option<Spanned<Vector>>,
    /// Projection: the vertical angle the image spans, in degrees (default 30).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fov: Option<Spanned<Finite>>,
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
            mapping: None,
            up: None,
            fov: None,
        }
    }
}
