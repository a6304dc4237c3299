//! `motion = { ... }` on `[[object]]` tables and on `[camera]`: keyframes, an orbit, a swing.
//!
//! ```toml
//! motion = { repeat = "loop", keys = [
//!     { time = 0, translate = [0, 0, 0] },
//!     { time = 2, translate = [3, 0, 0], rotate = [0, 90, 0] },
//! ] }
//! # or
//! motion = { orbit = { center = [0, 0, 0], axis = [0, 1, 0], period = 8 },
//!            oscillate = { offset = [0, 0.5, 0], period = 1.5 } }
//! ```
//!
//! Plain structs with optional keys (not tagged enums, which lose the place of an error);
//! checked, and turned into a [`lucent::motion::Motion`], in [`crate::build`].

use super::{Finite, Point, Scale, Vector};
use serde::{Deserialize, Serialize};
use toml::Spanned;

/// What happens before the first key and after the last.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RepeatName {
    /// Stay at the first or last key.
    #[default]
    Hold,
    /// Start again from the first key.
    Loop,
    /// Run the keys back and forth.
    Bounce,
}

/// A `motion` table.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MotionDesc {
    /// Outside the keys: `"hold"` (default), `"loop"` or `"bounce"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub repeat: Option<Spanned<RepeatName>>,
    /// Keyframes, times increasing.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub keys: Vec<Spanned<KeyDesc>>,
    /// A swing along `offset`, applied after the keys.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub oscillate: Option<Spanned<OscillateDesc>>,
    /// A turn about an axis, applied last.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orbit: Option<Spanned<OrbitDesc>>,
}

/// One keyframe.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct KeyDesc {
    /// Seconds.
    pub time: Spanned<Finite>,
    /// Moved by this after rotating (default none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translate: Option<Vector>,
    /// Degrees about x, then y, then z, after scaling (default none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotate: Option<Vector>,
    /// Scaled by this first: a number or per axis, positive (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<Spanned<Scale>>,
}

/// `orbit = { center, axis, period, phase }`.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OrbitDesc {
    /// A point on the axis (default the origin).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub center: Option<Point>,
    /// The axis's direction (default `[0, 1, 0]`); counter-clockwise seen from its tip.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub axis: Option<Spanned<Vector>>,
    /// Seconds per turn, positive.
    pub period: Spanned<Finite>,
    /// The angle at time 0, in degrees (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phase: Option<Finite>,
}

/// `oscillate = { offset, period, phase }`: a move by `offset · sin(360° · t / period + phase)`.
#[derive(Clone, Debug, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OscillateDesc {
    /// The largest displacement.
    pub offset: Vector,
    /// Seconds per swing, positive.
    pub period: Spanned<Finite>,
    /// The phase at time 0, in degrees (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phase: Option<Finite>,
}
