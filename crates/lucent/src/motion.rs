//! Motion: a world-space transform as a function of time, for scenes that move.
//!
//! A [`Motion`] has up to three parts, composed in this order (the first applied first):
//!
//! 1. **keyframes**: translate, rotate and scale given at increasing times, interpolated
//!    linearly between keys (rotations as quaternions, by slerp: the shortest way round, so
//!    keys must be less than 180° apart to turn the way they read); before the first key and
//!    after the last, [`Repeat`] says what happens;
//! 2. **oscillate**: a translation by `offset · sin(2π t / period + phase)`;
//! 3. **orbit**: a turn about an axis through a centre, one turn per `period` seconds
//!    (counter-clockwise seen from the tip of the axis), starting at angle `phase`.
//!
//! So `M(t) = orbit(t) · oscillate(t) · keys(t)`, and an object placed by `P` is at
//! `M(t) · P` at time `t`. Each key is itself `translate · rotate · scale` (scale first, then
//! rotate about x, then y, then z, then translate), as placements in scene files are.
//!
//! Times are seconds in `f64`, so that a display running for hours keeps its precision; the
//! transform is `f32`, as the scene is. Angles are radians here (degrees in files).

use glam::{Affine3A, DVec3, Quat, Vec3};
use std::f64::consts::TAU;
use std::fmt;
use thiserror::Error;

/// What happens before the first key and after the last.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Repeat {
    /// Stay at the first key before it and at the last after it.
    #[default]
    Hold,
    /// Start again from the first key: the keys' span repeats forever, both ways.
    Loop,
    /// Run the keys forward, then backward, then forward…
    Bounce,
}

impl Repeat {
    /// The name in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Repeat::Hold => "hold",
            Repeat::Loop => "loop",
            Repeat::Bounce => "bounce",
        }
    }
}

/// One keyframe: where the object is at `time`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Key {
    /// Seconds.
    pub time: f64,
    /// Moved by this, after rotating.
    pub translate: Vec3,
    /// Turned by this (a unit quaternion), after scaling.
    pub rotate: Quat,
    /// Scaled by this first; positive on every axis.
    pub scale: Vec3,
}

impl Key {
    /// The key at `time` that leaves the object where it is.
    pub fn new(time: f64) -> Self {
        Self {
            time,
            translate: Vec3::ZERO,
            rotate: Quat::IDENTITY,
            scale: Vec3::ONE,
        }
    }

    /// This key moved by `v`.
    pub fn with_translate(mut self, v: Vec3) -> Self {
        self.translate = v;
        self
    }

    /// This key turned by `degrees` about x, then y, then z.
    pub fn with_rotate_degrees(mut self, degrees: Vec3) -> Self {
        self.rotate = rotation_degrees(degrees);
        self
    }

    /// This key scaled by `s` (per axis).
    pub fn with_scale(mut self, s: Vec3) -> Self {
        self.scale = s;
        self
    }

    fn affine(&self) -> Affine3A {
        Affine3A::from_scale_rotation_translation(self.scale, self.rotate, self.translate)
    }
}

/// The rotation by `degrees` about x, then y, then z (as placements in scene files turn).
pub fn rotation_degrees(degrees: Vec3) -> Quat {
    let r = degrees.map(f32::to_radians);
    Quat::from_rotation_z(r.z) * Quat::from_rotation_y(r.y) * Quat::from_rotation_x(r.x)
}

/// A turn about the line through `center` along `axis`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orbit {
    /// A point on the axis.
    pub center: Vec3,
    /// The axis's direction (not zero; its length does not matter).
    pub axis: Vec3,
    /// Seconds per turn, positive.
    pub period: f64,
    /// The angle at `t = 0`, in radians.
    pub phase: f64,
}

impl Orbit {
    /// The turn at time `t`: `T(center) · R(axis, 2π t / period + phase) · T(−center)`.
    pub fn at(&self, t: f64) -> Affine3A {
        let angle = TAU * (t / self.period).rem_euclid(1.0) + self.phase;
        let r = Quat::from_axis_angle(self.axis.normalize(), angle as f32);
        let m = glam::Mat3A::from_quat(r);
        Affine3A {
            matrix3: m,
            translation: glam::Vec3A::from(self.center) - m * glam::Vec3A::from(self.center),
        }
    }
}

/// A swing to and fro along `offset`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Oscillate {
    /// The largest displacement.
    pub offset: Vec3,
    /// Seconds per swing, positive.
    pub period: f64,
    /// The phase at `t = 0`, in radians.
    pub phase: f64,
}

impl Oscillate {
    /// The displacement at time `t`: `offset · sin(2π t / period + phase)`.
    pub fn at(&self, t: f64) -> Vec3 {
        let angle = TAU * (t / self.period).rem_euclid(1.0) + self.phase;
        self.offset * angle.sin() as f32
    }
}

/// The part of a motion an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MotionPart {
    /// Key `i` (from 0).
    Key(usize),
    /// The orbit.
    Orbit,
    /// The oscillation.
    Oscillate,
}

impl fmt::Display for MotionPart {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MotionPart::Key(i) => write!(f, "key {i}"),
            MotionPart::Orbit => f.write_str("the orbit"),
            MotionPart::Oscillate => f.write_str("the oscillation"),
        }
    }
}

/// Why a motion cannot be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum MotionError {
    /// Key times that do not increase strictly.
    #[error("{part}: key times must increase ({time} s comes after {previous} s)")]
    KeyOrder {
        /// The later key.
        part: MotionPart,
        /// Its time.
        time: f64,
        /// The time of the key before it.
        previous: f64,
    },
    /// A NaN or infinite value.
    #[error("{part}: `{what}` must be finite")]
    NotFinite {
        /// Where.
        part: MotionPart,
        /// Which value.
        what: &'static str,
    },
    /// A key's scale that is not positive on every axis.
    #[error(
        "{part}: the scale must be positive on every axis (a mirror belongs in the placement), got {scale}"
    )]
    Scale {
        /// Where.
        part: MotionPart,
        /// The scale given.
        scale: Vec3,
    },
    /// A period that is not positive and finite.
    #[error("{part}: the period must be a positive number of seconds, got {period}")]
    Period {
        /// Where.
        part: MotionPart,
        /// The period given.
        period: f64,
    },
    /// An orbit about a zero axis.
    #[error("the orbit's axis must not be zero")]
    ZeroAxis,
}

impl MotionError {
    /// The part of the motion at fault.
    pub fn part(&self) -> MotionPart {
        match self {
            MotionError::KeyOrder { part, .. }
            | MotionError::NotFinite { part, .. }
            | MotionError::Scale { part, .. }
            | MotionError::Period { part, .. } => *part,
            MotionError::ZeroAxis => MotionPart::Orbit,
        }
    }
}

/// A world-space transform as a function of time (see the module docs); the default stands
/// still.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Motion {
    keys: Vec<Key>,
    repeat: Repeat,
    oscillate: Option<Oscillate>,
    orbit: Option<Orbit>,
    /// The point the keys scale and rotate about (the origin unless a scene built relative to
    /// its camera says where the world's origin went).
    pivot: DVec3,
}

impl Motion {
    /// The motion of `keys` (times increasing; none: no keyframed part) repeated as `repeat`,
    /// then `oscillate`, then `orbit`; checked.
    pub fn new(
        keys: Vec<Key>,
        repeat: Repeat,
        oscillate: Option<Oscillate>,
        orbit: Option<Orbit>,
    ) -> Result<Self, MotionError> {
        for (i, k) in keys.iter().enumerate() {
            let part = MotionPart::Key(i);
            let finite = [
                ("time", k.time.is_finite()),
                ("translate", k.translate.is_finite()),
                ("rotate", k.rotate.is_finite()),
                ("scale", k.scale.is_finite()),
            ];
            if let Some((what, _)) = finite.iter().find(|(_, ok)| !ok) {
                return Err(MotionError::NotFinite { part, what });
            }
            if !k.scale.cmpgt(Vec3::ZERO).all() {
                return Err(MotionError::Scale {
                    part,
                    scale: k.scale,
                });
            }
            // Both times are finite (checked above), so `<=` also catches no order.
            if i > 0 && k.time <= keys[i - 1].time {
                return Err(MotionError::KeyOrder {
                    part,
                    time: k.time,
                    previous: keys[i - 1].time,
                });
            }
        }
        let period = |part, period: f64, phase: f64| {
            if !(period > 0.0 && period.is_finite()) {
                return Err(MotionError::Period { part, period });
            }
            if !phase.is_finite() {
                return Err(MotionError::NotFinite {
                    part,
                    what: "phase",
                });
            }
            Ok(())
        };
        if let Some(o) = &oscillate {
            period(MotionPart::Oscillate, o.period, o.phase)?;
            if !o.offset.is_finite() {
                let part = MotionPart::Oscillate;
                return Err(MotionError::NotFinite {
                    part,
                    what: "offset",
                });
            }
        }
        if let Some(o) = &orbit {
            period(MotionPart::Orbit, o.period, o.phase)?;
            let part = MotionPart::Orbit;
            if !o.center.is_finite() {
                return Err(MotionError::NotFinite {
                    part,
                    what: "center",
                });
            }
            if !o.axis.is_finite() {
                return Err(MotionError::NotFinite { part, what: "axis" });
            }
            if o.axis.try_normalize().is_none() {
                return Err(MotionError::ZeroAxis);
            }
        }
        let keys = keys
            .into_iter()
            .map(|k| Key {
                rotate: k.rotate.normalize(),
                ..k
            })
            .collect();
        Ok(Self {
            keys,
            repeat,
            oscillate,
            orbit,
            pivot: DVec3::ZERO,
        })
    }

    /// This motion with its keys scaling and rotating about `pivot` instead of the origin:
    /// `T(pivot) · K(t) · T(−pivot)`, worked out in double precision so that a pivot far away
    /// (the world's origin, seen from a scene built relative to its camera) costs no detail.
    pub fn with_keys_about(mut self, pivot: DVec3) -> Self {
        self.pivot = pivot;
        self
    }

    /// Keyframes only.
    pub fn keyframes(keys: Vec<Key>, repeat: Repeat) -> Result<Self, MotionError> {
        Self::new(keys, repeat, None, None)
    }

    /// The keys.
    pub fn keys(&self) -> &[Key] {
        &self.keys
    }

    /// What happens outside the keys.
    pub fn repeat(&self) -> Repeat {
        self.repeat
    }

    /// The oscillation, if any.
    pub fn oscillate(&self) -> Option<&Oscillate> {
        self.oscillate.as_ref()
    }

    /// The orbit, if any.
    pub fn orbit(&self) -> Option<&Orbit> {
        self.orbit.as_ref()
    }

    /// Whether `at(t)` is the same for every `t` (no orbit, no swing, keys all alike).
    pub fn is_static(&self) -> bool {
        let alike =
            |a: &Key, b: &Key| (a.translate, a.rotate, a.scale) == (b.translate, b.rotate, b.scale);
        self.orbit.is_none()
            && self.oscillate.is_none_or(|o| o.offset == Vec3::ZERO)
            && self.keys.windows(2).all(|w| alike(&w[0], &w[1]))
    }

    /// Whether the keys scale alike on every axis (so that a sphere stays a sphere).
    pub fn scales_uniformly(&self) -> bool {
        self.keys
            .iter()
            .all(|k| k.scale.x == k.scale.y && k.scale.y == k.scale.z)
    }

    /// The transform at time `t` seconds (a `t` that is not finite is taken as 0).
    pub fn at(&self, t: f64) -> Affine3A {
        self.at_with_scale(t).0
    }

    /// [`Motion::at`] and [`Motion::scale_at`] together, the keys looked up once.
    pub fn at_with_scale(&self, t: f64) -> (Affine3A, Vec3) {
        let t = finite_time(t);
        let key = self.keyed(t);
        let mut m = key.affine();
        if self.pivot != DVec3::ZERO {
            let linear = glam::Mat3::from(m.matrix3).as_dmat3();
            let moved = m.translation.as_dvec3() + self.pivot - linear * self.pivot;
            m.translation = moved.as_vec3().into();
        }
        if let Some(o) = &self.oscillate {
            m = Affine3A::from_translation(o.at(t)) * m;
        }
        if let Some(o) = &self.orbit {
            m = o.at(t) * m;
        }
        (m, key.scale)
    }

    /// The scale at time `t` (the keys' alone: orbits and swings do not scale), exact where
    /// `at(t)`'s matrix carries rounding.
    pub fn scale_at(&self, t: f64) -> Vec3 {
        self.keyed(finite_time(t)).scale
    }

    /// The keyframed part at time `t`, as a key.
    fn keyed(&self, t: f64) -> Key {
        let (Some(first), Some(last)) = (self.keys.first(), self.keys.last()) else {
            return Key::new(t);
        };
        let span = last.time - first.time;
        let local = if span <= 0.0 {
            first.time
        } else {
            match self.repeat {
                Repeat::Hold => t.clamp(first.time, last.time),
                Repeat::Loop => first.time + (t - first.time).rem_euclid(span),
                Repeat::Bounce => {
                    let u = (t - first.time).rem_euclid(2.0 * span);
                    first.time + if u > span { 2.0 * span - u } else { u }
                }
            }
        };
        // The first key after `local`; keys before it and at it are `b − 1` and earlier.
        let b = self.keys.partition_point(|k| k.time <= local);
        if b == 0 {
            return *first;
        }
        if b == self.keys.len() {
            return *last;
        }
        let (k0, k1) = (&self.keys[b - 1], &self.keys[b]);
        let s = ((local - k0.time) / (k1.time - k0.time)) as f32;
        Key {
            time: local,
            translate: k0.translate.lerp(k1.translate, s),
            // Keys that only move or scale (the common case) need no slerp.
            rotate: if k0.rotate == k1.rotate {
                k0.rotate
            } else {
                k0.rotate.slerp(k1.rotate, s)
            },
            scale: k0.scale.lerp(k1.scale, s),
        }
    }
}

fn finite_time(t: f64) -> f64 {
    if t.is_finite() { t } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Affine3A, b: Affine3A) -> bool {
        a.abs_diff_eq(b, 1e-5)
    }

    fn slide() -> Vec<Key> {
        vec![
            Key::new(0.0),
            Key::new(2.0).with_translate(Vec3::new(4.0, 0.0, 0.0)),
        ]
    }

    #[test]
    fn keys_are_met_and_interpolated_linearly() {
        let m = Motion::keyframes(slide(), Repeat::Hold).unwrap();
        assert_eq!(m.at(0.0), Affine3A::IDENTITY);
        assert!(close(m.at(2.0), Affine3A::from_translation(Vec3::X * 4.0)));
        assert!(close(m.at(0.5), Affine3A::from_translation(Vec3::X)));
        let scaled = Motion::keyframes(
            vec![Key::new(1.0), Key::new(3.0).with_scale(Vec3::splat(3.0))],
            Repeat::Hold,
        )
        .unwrap();
        assert!(close(
            scaled.at(2.0),
            Affine3A::from_scale(Vec3::splat(2.0))
        ));
    }

    #[test]
    fn rotations_slerp_halfway() {
        let keys = vec![
            Key::new(0.0),
            Key::new(1.0).with_rotate_degrees(Vec3::new(0.0, 90.0, 0.0)),
        ];
        let m = Motion::keyframes(keys, Repeat::Hold).unwrap();
        let half = Affine3A::from_quat(Quat::from_rotation_y(45f32.to_radians()));
        assert!(close(m.at(0.5), half));
        // A slerp keeps the rotation rigid: no shrinking halfway, as a matrix lerp would.
        assert!((m.at(0.5).matrix3.x_axis.length() - 1.0).abs() < 1e-6);
    }

    #[test]
    fn rotations_turn_about_x_then_y_then_z() {
        let q = rotation_degrees(Vec3::new(90.0, 90.0, 0.0));
        // x first takes +y to +z; then y takes +z to +x.
        assert!((q * Vec3::Y - Vec3::X).length() < 1e-6);
    }

    #[test]
    fn hold_loop_and_bounce_outside_the_keys() {
        let at = |repeat, t| {
            Motion::keyframes(slide(), repeat)
                .unwrap()
                .at(t)
                .translation
                .x
        };
        assert_eq!(at(Repeat::Hold, -1.0), 0.0);
        assert_eq!(at(Repeat::Hold, 9.0), 4.0);
        assert!((at(Repeat::Loop, 2.5) - 1.0).abs() < 1e-6);
        assert!((at(Repeat::Loop, -0.5) - 3.0).abs() < 1e-6);
        assert!((at(Repeat::Bounce, 2.5) - 3.0).abs() < 1e-6);
        assert!((at(Repeat::Bounce, 4.5) - 1.0).abs() < 1e-6);
        assert!((at(Repeat::Bounce, -0.5) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn an_orbit_returns_after_one_period() {
        let orbit = Orbit {
            center: Vec3::new(1.0, 0.0, 0.0),
            axis: Vec3::Y * 3.0,
            period: 8.0,
            phase: 0.0,
        };
        let m = Motion::new(vec![], Repeat::Hold, None, Some(orbit)).unwrap();
        let p = Vec3::new(3.0, 1.0, 0.0);
        for t in [0.0, 8.0, 16.0, 8000.0] {
            assert!((m.at(t).transform_point3(p) - p).length() < 1e-5, "t = {t}");
        }
        // A quarter turn, counter-clockwise seen from +y: +x goes to −z.
        let quarter = m.at(2.0).transform_point3(p);
        assert!(
            (quarter - Vec3::new(1.0, 1.0, -2.0)).length() < 1e-5,
            "{quarter}"
        );
        assert!(!m.is_static());
    }

    #[test]
    fn parts_compose_keys_then_oscillate_then_orbit() {
        let oscillate = Oscillate {
            offset: Vec3::new(0.0, 0.0, 1.0),
            period: 4.0,
            phase: 0.0,
        };
        let orbit = Orbit {
            center: Vec3::ZERO,
            axis: Vec3::Y,
            period: 4.0,
            phase: 0.0,
        };
        let keys = vec![Key::new(0.0).with_translate(Vec3::X)];
        let m = Motion::new(keys, Repeat::Hold, Some(oscillate), Some(orbit)).unwrap();
        // At t = 1: keys put the origin at +x, the swing adds +z, the quarter turn takes
        // (1, 0, 1) to (1, 0, −1).
        let p = m.at(1.0).transform_point3(Vec3::ZERO);
        assert!((p - Vec3::new(1.0, 0.0, -1.0)).length() < 1e-5, "{p}");
    }

    #[test]
    fn keys_about_a_far_pivot_turn_points_about_it() {
        // A quarter turn about y through the world's origin, seen from a scene whose own origin
        // is 1e7 out along x: the world's origin is at x = −1e7 there.
        let turn = vec![Key::new(0.0).with_rotate_degrees(Vec3::new(0.0, 90.0, 0.0))];
        let m = Motion::keyframes(turn, Repeat::Hold)
            .unwrap()
            .with_keys_about(DVec3::new(-1e7, 0.0, 0.0));
        // The point at world (1e7 + 1, 0, 0), scene (1, 0, 0), goes to world (0, 0, −1e7 − 1),
        // scene (−1e7, 0, −1e7 − 1): exact in double precision, rounded once to single.
        let p = m.at(0.0).transform_point3(Vec3::X);
        let want = Vec3::new(-1e7, 0.0, -1e7 - 1.0);
        assert!((p - want).abs().max_element() <= 1.0, "{p}");
        // About the origin (the default) nothing changes.
        let plain = Motion::keyframes(vec![Key::new(0.0).with_translate(Vec3::Y)], Repeat::Hold)
            .unwrap()
            .with_keys_about(DVec3::ZERO);
        assert_eq!(plain.at(0.0), Affine3A::from_translation(Vec3::Y));
    }

    #[test]
    fn still_motions_are_static() {
        assert!(Motion::default().is_static());
        let one = Motion::keyframes(vec![Key::new(3.0).with_translate(Vec3::Y)], Repeat::Loop);
        let one = one.unwrap();
        assert!(one.is_static());
        assert!(close(one.at(-7.0), Affine3A::from_translation(Vec3::Y)));
        assert!(
            !Motion::keyframes(slide(), Repeat::Hold)
                .unwrap()
                .is_static()
        );
    }

    #[test]
    fn bad_motions_are_refused() {
        let order = Motion::keyframes(vec![Key::new(1.0), Key::new(1.0)], Repeat::Hold);
        assert!(matches!(
            order,
            Err(MotionError::KeyOrder {
                part: MotionPart::Key(1),
                ..
            })
        ));
        let nan = Motion::keyframes(vec![Key::new(f64::NAN)], Repeat::Hold);
        assert!(matches!(
            nan,
            Err(MotionError::NotFinite { what: "time", .. })
        ));
        let flat = Motion::keyframes(
            vec![Key::new(0.0).with_scale(Vec3::new(1.0, 0.0, 1.0))],
            Repeat::Hold,
        );
        assert!(matches!(flat, Err(MotionError::Scale { .. })));
        let orbit = |period, axis| Orbit {
            center: Vec3::ZERO,
            axis,
            period,
            phase: 0.0,
        };
        for p in [0.0, -1.0, f64::INFINITY, f64::NAN] {
            let e = Motion::new(vec![], Repeat::Hold, None, Some(orbit(p, Vec3::Y)));
            assert!(matches!(
                e,
                Err(MotionError::Period {
                    part: MotionPart::Orbit,
                    ..
                })
            ));
        }
        let e = Motion::new(vec![], Repeat::Hold, None, Some(orbit(1.0, Vec3::ZERO)));
        assert_eq!(e, Err(MotionError::ZeroAxis));
        let swing = Oscillate {
            offset: Vec3::X,
            period: 0.0,
            phase: 0.0,
        };
        let e = Motion::new(vec![], Repeat::Hold, Some(swing), None).unwrap_err();
        assert_eq!(e.part(), MotionPart::Oscillate);
        assert!(e.to_string().contains("period"), "{e}");
    }
}
