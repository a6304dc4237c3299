//! Where the viewer's camera is, and how the mouse and keys move it: orbit about the look-at
//! point, dolly towards it, fly (eye and look-at together), turn (look-at about the eye).
//!
//! A pose is the scene file's camera without a resolution; the workers build a
//! [`Camera`] from it at whatever size the window asks for.

use glam::{Quat, Vec3};
use lucent::camera::Camera;

/// A camera without its image size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// The eye point.
    pub eye: Vec3,
    /// The point seen at the centre, and the one orbits turn about.
    pub look_at: Vec3,
    /// The upright direction of the image (need not be unit or orthogonal to the view).
    pub up: Vec3,
    /// Vertical field of view in degrees.
    pub fov_degrees: f32,
    /// The thin lens: aperture radius (0: a pinhole) and focus distance.
    pub lens: (f32, f32),
}

/// The nearest the eye comes to the look-at point, as a share of the starting distance: a
/// dolly never passes through the point it looks at.
const MIN_DISTANCE_SHARE: f32 = 1e-3;

/// The closest the view comes to straight up or down, in radians: at the pole the up vector
/// would be parallel to the view, and the image's roll undefined.
const POLE_MARGIN: f32 = 0.02;

impl Pose {
    /// The camera of this pose at `width × height` pixels; `None` if the pose is degenerate
    /// (which the moves below never make of a valid one).
    pub fn camera(&self, width: u32, height: u32) -> Option<Camera> {
        let c = Camera::new(
            self.eye,
            self.look_at,
            self.up,
            self.fov_degrees,
            width,
            height,
        )
        .ok()?;
        c.with_lens(self.lens.0, self.lens.1).ok()
    }

    fn distance(&self) -> f32 {
        (self.look_at - self.eye).length()
    }

    fn forward(&self) -> Vec3 {
        (self.look_at - self.eye).normalize_or_zero()
    }

    fn right(&self) -> Vec3 {
        self.forward().cross(self.up).normalize_or_zero()
    }

    /// Turns the eye about the look-at point: `yaw` about the up vector, `pitch` about the
    /// image's horizontal (radians; positive pitch raises the eye).
    pub fn orbit(&mut self, yaw: f32, pitch: f32) {
        let offset = self.eye - self.look_at;
        self.eye = self.look_at + turn(offset, self.up, yaw, pitch);
    }

    /// Moves the eye towards the look-at point by `factor` of its distance (negative: away).
    pub fn dolly(&mut self, factor: f32) {
        let offset = self.eye - self.look_at;
        let d = offset.length();
        let near = d * MIN_DISTANCE_SHARE;
        let new = (d * (1.0 - factor)).max(near);
        self.eye = self.look_at + offset * (new / d);
    }

    /// Moves eye and look-at together: `right`, `up` and `forward` in units of the distance
    /// between them, so that a key press moves as far in a small scene as in a large one.
    pub fn fly(&mut self, right: f32, up: f32, forward: f32) {
        let d = self.distance();
        let up_dir = self.up.normalize_or_zero();
        let step = (self.right() * right + up_dir * up + self.forward() * forward) * d;
        self.eye += step;
        self.look_at += step;
    }

    /// Turns the view about the eye: `yaw` about the up vector, `pitch` about the image's
    /// horizontal (radians; positive pitch looks up).
    pub fn turn(&mut self, yaw: f32, pitch: f32) {
        let offset = self.look_at - self.eye;
        self.look_at = self.eye + turn(offset, self.up, yaw, pitch);
    }
}

/// `v` rotated by `yaw` about `up` and by `pitch` towards `up` (radians), the pitch limited
/// so that `v` stays `POLE_MARGIN` away from `±up`.
fn turn(v: Vec3, up: Vec3, yaw: f32, pitch: f32) -> Vec3 {
    let up = up.normalize_or_zero();
    // About `v × up`, a positive angle turns `v` towards `up` (Rodrigues: the term
    // `(v × up) × v` is up's part perpendicular to `v`).
    let axis = v.cross(up).normalize_or_zero();
    if axis == Vec3::ZERO {
        return v;
    }
    // The angle from up now, and the pitch that keeps it inside (margin, π − margin); a view
    // already outside may only come back.
    let from_up = v.normalize_or_zero().dot(up).clamp(-1.0, 1.0).acos();
    let most = (from_up - POLE_MARGIN).max(0.0);
    let least = (from_up - std::f32::consts::PI + POLE_MARGIN).min(0.0);
    let pitch = pitch.clamp(least, most);
    Quat::from_axis_angle(up, yaw) * Quat::from_axis_angle(axis, pitch) * v
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pose() -> Pose {
        Pose {
            eye: Vec3::new(0.0, 1.0, 5.0),
            look_at: Vec3::new(0.0, 1.0, 0.0),
            up: Vec3::Y,
            fov_degrees: 40.0,
            lens: (0.0, 5.0),
        }
    }

    #[test]
    fn orbit_keeps_the_distance_and_the_target() {
        let mut p = pose();
        p.orbit(0.7, 0.3);
        assert!(((p.eye - p.look_at).length() - 5.0).abs() < 1e-4);
        assert_eq!(p.look_at, Vec3::new(0.0, 1.0, 0.0));
        assert!(
            p.eye.y > 1.0,
            "a positive pitch raises the eye: {:?}",
            p.eye
        );
        assert!(p.camera(4, 3).is_some());
    }

    #[test]
    fn orbit_stops_short_of_the_pole() {
        let mut p = pose();
        for _ in 0..100 {
            p.orbit(0.0, 0.5);
        }
        let c = p.camera(4, 3);
        assert!(c.is_some(), "the view never becomes parallel to up");
        assert!(p.eye.y > 5.9 && p.eye.y < 6.0, "{:?}", p.eye);
    }

    #[test]
    fn dolly_never_passes_the_target() {
        let mut p = pose();
        p.dolly(0.5);
        assert!(((p.eye - p.look_at).length() - 2.5).abs() < 1e-5);
        p.dolly(5.0);
        assert!((p.eye - p.look_at).length() > 0.0);
        assert!(p.camera(4, 3).is_some());
    }

    #[test]
    fn fly_moves_both_points_and_turn_keeps_the_eye() {
        let mut p = pose();
        p.fly(1.0, 0.0, 0.0);
        assert!((p.eye - Vec3::new(5.0, 1.0, 5.0)).length() < 1e-4);
        assert!((p.look_at - Vec3::new(5.0, 1.0, 0.0)).length() < 1e-4);
        let eye = p.eye;
        p.turn(std::f32::consts::FRAC_PI_2, 0.0);
        assert_eq!(p.eye, eye);
        // A quarter turn left (counter-clockwise seen from above) from looking down −z.
        assert!(
            (p.look_at - Vec3::new(0.0, 1.0, 5.0)).length() < 1e-3,
            "{:?}",
            p.look_at
        );
        p.turn(0.0, 0.2);
        assert!(p.look_at.y > 1.0, "a positive pitch looks up");
    }
}
