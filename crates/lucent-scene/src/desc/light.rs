//! `[[light]]` tables.

use super::{Color, Vector};
use serde::Deserialize;
use toml::Spanned;

/// The kinds of light.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum LightKind {
    /// `position`, `intensity`, `falloff`.
    Point,
    /// `direction`, `intensity`.
    Directional,
}

/// How a point light falls off.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FalloffName {
    /// None: the classic model.
    #[default]
    None,
    /// `1 / d²`.
    Quadratic,
}

/// One `[[light]]`. Which keys apply depends on `type`; the others are refused in build.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LightDesc {
    /// `"point"` or `"directional"`.
    #[serde(rename = "type")]
    pub kind: LightKind,
    /// Intensity `I_j` (default 1).
    #[serde(default)]
    pub intensity: Option<Color>,
    /// Point: where it is.
    #[serde(default)]
    pub position: Option<Spanned<Vector>>,
    /// Point: `"none"` (default) or `"quadratic"`.
    #[serde(default)]
    pub falloff: Option<Spanned<FalloffName>>,
    /// Directional: the direction the light travels in (non-zero).
    #[serde(default)]
    pub direction: Option<Spanned<Vector>>,
}
