//! `[[object]]` tables.

use super::{Finite, Scale, Vector};
use serde::Deserialize;
use toml::Spanned;

/// The kinds of object.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ObjectKind {
    /// `center`, `radius`.
    Sphere,
    /// `point`, `normal`.
    Plane,
    /// `vertices` (three points).
    Triangle,
    /// `file` (an OBJ file), and optionally `translate`, `rotate`, `scale`.
    Mesh,
}

impl ObjectKind {
    /// The name used in files.
    pub fn name(self) -> &'static str {
        match self {
            ObjectKind::Sphere => "sphere",
            ObjectKind::Plane => "plane",
            ObjectKind::Triangle => "triangle",
            ObjectKind::Mesh => "mesh",
        }
    }
}

/// One `[[object]]`. Which keys apply depends on `type`; the others are refused in build.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObjectDesc {
    /// What it is.
    #[serde(rename = "type")]
    pub kind: ObjectKind,
    /// The name of its material.
    pub material: Spanned<String>,
    /// Sphere: centre.
    #[serde(default)]
    pub center: Option<Spanned<Vector>>,
    /// Sphere: radius, > 0.
    #[serde(default)]
    pub radius: Option<Spanned<Finite>>,
    /// Plane: a point on it.
    #[serde(default)]
    pub point: Option<Spanned<Vector>>,
    /// Plane: its normal (non-zero; the front side).
    #[serde(default)]
    pub normal: Option<Spanned<Vector>>,
    /// Triangle: three corners, counter-clockwise seen from the front.
    #[serde(default)]
    pub vertices: Option<Spanned<[Vector; 3]>>,
    /// Mesh: an OBJ file, relative to the scene file's folder.
    #[serde(default)]
    pub file: Option<Spanned<String>>,
    /// Mesh: moved by this after rotating.
    #[serde(default)]
    pub translate: Option<Spanned<Vector>>,
    /// Mesh: rotated by these angles in degrees about x, then y, then z, after scaling.
    #[serde(default)]
    pub rotate: Option<Spanned<Vector>>,
    /// Mesh: scaled by this first (a number or per axis).
    #[serde(default)]
    pub scale: Option<Spanned<Scale>>,
}
