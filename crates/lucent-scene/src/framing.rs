//! The camera and light of a scene without a camera: which axis of the file is up, which side
//! the camera looks from, and a guess of the up axis for mesh files, which do not say.
//!
//! Conventions. A [`Frame`] is orthonormal and right-handed, `right × up = back`, and `back`
//! points from the model towards its viewer. A Y-up file's model frame is `(x, y, z)`: seen
//! from the front, the camera is on +z looking along −z with +x to its right. Another up
//! axis takes the least rotation of that frame bringing +y onto it: about x for ±z and −y
//! (+z up: the front is −y, as in Blender), about z for ±x.
//!
//! ```text
//! --up y --view front   eye on +z (a little above), image up +y, image right +x
//! --up z --view front   eye on −y (a little above), image up +z, image right +x
//! --up z --view top     eye on +z,                  image up +y, image right +x
//! ```

use crate::desc::{CameraDesc, Finite, Point, Vector};
use glam::Vec3;
use lucent::accel::Aabb;
use std::fmt;
use std::str::FromStr;

/// Vertical field of view of a framing camera, in degrees.
pub const FRAMING_FOV: f32 = 40.0;

/// An axis of the file's coordinates, with its sign: the model's up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Axis {
    /// +x.
    X,
    /// +y: glTF's, and the usual reading of OBJ and PLY files.
    #[default]
    Y,
    /// +z: CAD, Blender's and 3ds Max's world, many scans.
    Z,
    /// −x.
    NegX,
    /// −y.
    NegY,
    /// −z.
    NegZ,
}

impl Axis {
    /// Every axis, positive ones first.
    pub const ALL: [Axis; 6] = [
        Axis::X,
        Axis::Y,
        Axis::Z,
        Axis::NegX,
        Axis::NegY,
        Axis::NegZ,
    ];

    /// The name on the command line: `x`, `y`, `z`, `-x`, `-y`, `-z`.
    pub fn name(self) -> &'static str {
        self.signed_name().trim_start_matches('+')
    }

    /// The name with its sign always written: `+x` … `-z` (how notes name it).
    pub fn signed_name(self) -> &'static str {
        match self {
            Axis::X => "+x",
            Axis::Y => "+y",
            Axis::Z => "+z",
            Axis::NegX => "-x",
            Axis::NegY => "-y",
            Axis::NegZ => "-z",
        }
    }

    /// The positive axis of coordinate `i` (0: x, 1: y, 2: z).
    fn positive(i: usize) -> Axis {
        [Axis::X, Axis::Y, Axis::Z][i]
    }

    /// The unit vector.
    pub fn vector(self) -> Vec3 {
        match self {
            Axis::X => Vec3::X,
            Axis::Y => Vec3::Y,
            Axis::Z => Vec3::Z,
            Axis::NegX => Vec3::NEG_X,
            Axis::NegY => Vec3::NEG_Y,
            Axis::NegZ => Vec3::NEG_Z,
        }
    }
}

impl fmt::Display for Axis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.signed_name())
    }
}

impl FromStr for Axis {
    type Err = String;

    /// `x`, `+x` or `-x` (any case), and the same for y and z.
    fn from_str(s: &str) -> Result<Self, String> {
        let lower = s.to_ascii_lowercase();
        let (negative, letter) = match lower.strip_prefix('-') {
            Some(rest) => (true, rest),
            None => (false, lower.strip_prefix('+').unwrap_or(&lower)),
        };
        let i = ["x", "y", "z"]
            .iter()
            .position(|l| *l == letter)
            .ok_or_else(|| format!("`{s}` is not an axis (x, y, z, -x, -y or -z)"))?;
        Ok(Axis::ALL[i + if negative { 3 } else { 0 }])
    }
}

/// Where the framing camera looks from, relative to the model's frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum View {
    /// From the front, a little above (about 5°).
    #[default]
    Front,
    /// From the model's right (the front view turned +90° about up), a little above.
    Side,
    /// Straight down the up axis; the image's up is the model's back, so its front is at the
    /// bottom of the image and its right on the right, as in a plan.
    Top,
    /// A three-quarter view from the front right and above, along `right + back + up`
    /// (35.3° above the horizon, as an isometric drawing's).
    Iso,
}

impl View {
    /// Every view.
    pub const ALL: [View; 4] = [View::Front, View::Side, View::Top, View::Iso];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            View::Front => "front",
            View::Side => "side",
            View::Top => "top",
            View::Iso => "iso",
        }
    }
}

impl fmt::Display for View {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for View {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        View::ALL
            .into_iter()
            .find(|v| v.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("`{s}` is not a view (front, side, top or iso)"))
    }
}

/// An orthonormal right-handed frame: `right × up = back`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// To the right.
    pub right: Vec3,
    /// Upwards.
    pub up: Vec3,
    /// Towards the viewer.
    pub back: Vec3,
}

impl Frame {
    /// The frame with `back` and the `up` nearest to `up_hint` (not parallel to `back`).
    fn looking(back: Vec3, up_hint: Vec3) -> Frame {
        let right = up_hint.cross(back).normalize();
        Frame {
            right,
            up: back.cross(right),
            back,
        }
    }
}

/// How a scene without a camera is framed: the file's up axis and the side it is seen from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Framing {
    /// The model's up.
    pub up: Axis,
    /// Where the camera looks from.
    pub view: View,
}

impl Framing {
    /// The model's frame: the least rotation of `(x, y, z)` taking +y to the up axis.
    pub fn model_frame(self) -> Frame {
        let (right, up, back) = match self.up {
            Axis::Y => (Vec3::X, Vec3::Y, Vec3::Z),
            Axis::Z => (Vec3::X, Vec3::Z, Vec3::NEG_Y),
            Axis::NegY => (Vec3::X, Vec3::NEG_Y, Vec3::NEG_Z),
            Axis::NegZ => (Vec3::X, Vec3::NEG_Z, Vec3::Y),
            Axis::X => (Vec3::NEG_Y, Vec3::X, Vec3::Z),
            Axis::NegX => (Vec3::Y, Vec3::NEG_X, Vec3::Z),
        };
        Frame { right, up, back }
    }

    /// The camera's frame (image right, image up, towards the eye), leaving out the small
    /// elevation of the front and side views: the frame the default light is placed in.
    pub fn view_frame(self) -> Frame {
        let m = self.model_frame();
        match self.view {
            View::Front => m,
            View::Side => Frame::looking(m.right, m.up),
            // Looking down: the model's up cannot be the image's; its back is.
            View::Top => Frame::looking(m.up, -m.back),
            View::Iso => Frame::looking((m.right + m.back + m.up).normalize(), m.up),
        }
    }

    /// A camera that looks at the centre of `bounds` from this framing's side, far enough back
    /// that the bounding sphere fits the narrower field of view (vertical [`FRAMING_FOV`]).
    /// The front and side views are raised by a quarter of the sphere's radius.
    pub fn camera(self, bounds: Aabb, width: u32, height: u32) -> CameraDesc {
        let (center, radius) = if bounds.is_empty() {
            (Vec3::ZERO, 1.0)
        } else {
            (bounds.center(), (0.5 * bounds.extent().length()).max(1e-6))
        };
        let aspect = width as f32 / height as f32;
        let half = (0.5 * FRAMING_FOV).to_radians().tan();
        let half_fov = half.min(aspect * half);
        let distance = radius / half_fov.atan().sin();
        let v = self.view_frame();
        let lift = match self.view {
            View::Front | View::Side => (0.25 * radius) * self.model_frame().up,
            View::Top | View::Iso => Vec3::ZERO,
        };
        CameraDesc {
            eye: Point::from_single(center + (distance * v.back + lift)),
            look_at: Point::from_single(center),
            up: Vector(v.up),
            fov: Finite(FRAMING_FOV),
            aperture: None,
            focus_distance: None,
            orthographic: None,
            motion: None,
            shutter: None,
            medium: None,
        }
    }

    /// Where the default light travels: from the upper left behind the camera, the same in
    /// every framing (`[0.4, -0.6, -0.7]` for +y up seen from the front).
    pub fn light_direction(self) -> Vec3 {
        let v = self.view_frame();
        0.4 * v.right - 0.6 * v.up - 0.7 * v.back
    }
}

/// The up axis of a mesh file that does not say, and what in its geometry says so.
///
/// The rule keeps +y, the usual reading of OBJ and PLY files, unless the geometry points at
/// another positive axis and nothing points at +y. Two things count:
///
/// - **ground**: the lowest point along an axis is at the origin (within
///   [`GROUND_TOLERANCE`] of the bounds' diagonal) while the model straddles the origin along
///   the other two, and rises at least [`GROUND_MIN_HEIGHT`] of the diagonal — modelling tools
///   put a model's origin at its feet;
/// - **flat base**: at least [`BASE_MIN_SHARE`] (and at most [`BASE_MAX_SHARE`]) of the surface
///   area lies flat (within [`BASE_ANGLE_DEGREES`]) within [`BASE_SLAB`] of the diagonal from
///   the lowest point along an axis, and at least [`BASE_DOMINANCE`] times the share along
///   either other axis — what a model stands on.
///
/// Negative axes are never guessed: a flat top (a table, a hat) must not turn a model upside
/// down. On the shared test meshes, all +y up, the ground finds the teapot and the ogre and the
/// flat base the teapot and the bunny; on copies of them turned to +z (or +x) up the rule
/// follows those three and leaves the rest at +y.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UpGuess {
    /// The axis taken as up.
    pub up: Axis,
    /// The axis the model stands on the origin along, if any.
    pub ground: Option<Axis>,
    /// The axis with a flat base at its lowest end, if any.
    pub base: Option<Axis>,
}

/// How close to the origin a model's lowest point must be to stand on it, as a share of the
/// bounds' diagonal (the ogre's is 0.02 %).
pub const GROUND_TOLERANCE: f32 = 0.005;
/// How tall a model standing on the origin must be, as a share of the bounds' diagonal (flat
/// models lie on every plane they are in).
pub const GROUND_MIN_HEIGHT: f32 = 0.1;
/// The least share of the surface area a flat base holds (the bunny's is 4.4 %; no other axis
/// of a shared mesh has more than 1.3 %).
pub const BASE_MIN_SHARE: f64 = 0.025;
/// The most: beyond it the flat side is more likely a back (a relief) or the whole model (a
/// plane) than what it stands on.
pub const BASE_MAX_SHARE: f64 = 0.3;
/// How far a base's faces may tilt from flat, in degrees.
pub const BASE_ANGLE_DEGREES: f32 = 15.0;
/// How thick the slab of a base is, as a share of the bounds' diagonal.
pub const BASE_SLAB: f32 = 0.02;
/// How many times the other axes' share a base's must be (the bunny's is 7.6 times).
pub const BASE_DOMINANCE: f64 = 3.0;

/// Guesses the up axis of the triangles (vertex indices into `positions`; a triangle with an
/// index out of range is left out), as [`UpGuess`] says. Empty and flat meshes are +y up.
pub fn guess_up(positions: &[Vec3], triangles: &[[u32; 3]]) -> UpGuess {
    let corners = || {
        triangles.iter().filter_map(|t| {
            let [p, q, r] = t.map(|i| positions.get(i as usize).copied());
            Some([p?, q?, r?])
        })
    };
    let bounds = corners().flatten().fold(Aabb::EMPTY, Aabb::grow);
    let diagonal = bounds.extent().length();
    let nothing = UpGuess {
        up: Axis::Y,
        ground: None,
        base: None,
    };
    if bounds.is_empty() || !(diagonal.is_finite() && diagonal > 0.0) {
        return nothing;
    }
    let (lo, hi) = (bounds.min.to_array(), bounds.max.to_array());
    let tol = GROUND_TOLERANCE * diagonal;
    let stands = |a: usize| {
        lo[a].abs() <= tol
            && hi[a] - lo[a] >= GROUND_MIN_HEIGHT * diagonal
            && (0..3).all(|b| b == a || (lo[b] < -tol && hi[b] > tol))
    };
    // Straddling the origin along the other two axes leaves one axis at most.
    let ground = (0..3).find(|&a| stands(a)).map(Axis::positive);

    // Twice the area of each triangle, in f64: hundreds of thousands are summed.
    let cos_flat = BASE_ANGLE_DEGREES.to_radians().cos();
    let slab = BASE_SLAB * diagonal;
    let (mut total, mut flat) = (0.0f64, [0.0f64; 3]);
    for [p, q, r] in corners() {
        let n = (q - p).cross(r - p);
        let area = n.length();
        if !(area.is_finite() && area > 0.0) {
            continue;
        }
        total += f64::from(area);
        let top = p.max(q).max(r).to_array();
        for a in 0..3 {
            if n[a].abs() >= cos_flat * area && top[a] <= lo[a] + slab {
                flat[a] += f64::from(area);
            }
        }
    }
    let base = (total > 0.0)
        .then(|| {
            let share = flat.map(|f| f / total);
            (0..3).find(|&a| {
                (BASE_MIN_SHARE..=BASE_MAX_SHARE).contains(&share[a])
                    && (0..3).all(|b| b == a || share[a] >= BASE_DOMINANCE * share[b])
            })
        })
        .flatten()
        .map(Axis::positive);

    let up = match (ground, base) {
        (Some(a), None) | (None, Some(a)) => a,
        (Some(a), Some(b)) if a == b => a,
        // No evidence, or evidence that disagrees.
        _ => Axis::Y,
    };
    UpGuess { up, ground, base }
}

impl fmt::Display for UpGuess {
    /// `up axis guessed as +z (…why…)`, or `taken as +y` with why, or that nothing said.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut why = Vec::new();
        if let Some(a) = self.ground {
            let l = a.name();
            why.push(format!(
                "it stands on the plane {l} = 0, centred over the origin"
            ));
        }
        if let Some(a) = self.base {
            why.push(format!("a flat base at its lowest {}", a.name()));
        }
        let why = why.join("; ");
        if self.up != Axis::Y {
            write!(f, "up axis guessed as {} ({why})", self.up)
        } else if self.ground.is_none() && self.base.is_none() {
            write!(
                f,
                "up axis taken as +y, the default (neither a flat base nor a ground at the origin says otherwise)"
            )
        } else if self.ground.is_some_and(|a| a != Axis::Y)
            || self.base.is_some_and(|a| a != Axis::Y)
        {
            write!(
                f,
                "up axis taken as +y, the default (the clues disagree: {why})"
            )
        } else {
            write!(f, "up axis taken as +y ({why})")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lucent::camera::Camera;

    const EPS: f32 = 1e-5;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < EPS
    }

    fn every_framing() -> impl Iterator<Item = Framing> {
        Axis::ALL
            .into_iter()
            .flat_map(|up| View::ALL.into_iter().map(move |view| Framing { up, view }))
    }

    /// A box off the origin, longer along x: the centre and the fit are not trivial.
    fn bounds() -> Aabb {
        Aabb::new(Vec3::new(1.0, -2.0, 3.0), Vec3::new(5.0, 0.0, 4.0))
    }

    fn camera_of(f: Framing, width: u32, height: u32) -> Camera {
        let c = f.camera(bounds(), width, height);
        Camera::new(
            c.eye.0.as_vec3(),
            c.look_at.0.as_vec3(),
            c.up.0,
            c.fov.0,
            width,
            height,
        )
        .unwrap()
    }

    #[test]
    fn axis_names_parse_back() {
        for a in Axis::ALL {
            assert_eq!(a.name().parse::<Axis>(), Ok(a));
            assert_eq!(a.signed_name().parse::<Axis>(), Ok(a));
            assert_eq!(a.to_string().to_uppercase().parse::<Axis>(), Ok(a));
        }
        assert_eq!(Axis::NegZ.name(), "-z");
        assert_eq!(Axis::Z.name(), "z");
        for bad in ["w", "", "+", "--x", "+-x", "xy"] {
            assert!(bad.parse::<Axis>().is_err(), "{bad}");
        }
        for v in View::ALL {
            assert_eq!(v.name().parse::<View>(), Ok(v));
        }
        assert!("below".parse::<View>().is_err());
    }

    #[test]
    fn every_frame_is_orthonormal_and_right_handed() {
        for f in every_framing() {
            for fr in [f.model_frame(), f.view_frame()] {
                for v in [fr.right, fr.up, fr.back] {
                    assert!((v.length() - 1.0).abs() < EPS, "{f:?}");
                }
                assert!(close(fr.right.cross(fr.up), fr.back), "{f:?}: {fr:?}");
            }
            let m = f.model_frame();
            assert_eq!(m.up, f.up.vector(), "{f:?}");
        }
    }

    #[test]
    fn y_up_front_is_the_camera_and_light_of_before() {
        let f = Framing::default();
        let b = bounds();
        let radius = 0.5 * b.extent().length();
        let half = (20.0f32).to_radians().tan();
        let distance = radius / half.min(800.0 / 600.0 * half).atan().sin();
        let c = f.camera(b, 800, 600);
        assert_eq!(
            c.eye.0.as_vec3(),
            b.center() + Vec3::new(0.0, 0.25 * radius, distance)
        );
        assert_eq!(c.up.0, Vec3::Y);
        assert_eq!(f.light_direction(), Vec3::new(0.4, -0.6, -0.7));
    }

    #[test]
    fn the_camera_looks_at_the_centre_and_fits_the_bounding_sphere() {
        let b = bounds();
        let radius = 0.5 * b.extent().length();
        for (w, h) in [(800, 600), (300, 900)] {
            for f in every_framing() {
                let cam = camera_of(f, w, h);
                let to_centre = b.center() - cam.eye();
                assert!(close(cam.forward(), to_centre.normalize()), "{f:?}");
                // The sphere's angular radius is the narrower half field of view (less for
                // the raised views, which stand a little further off).
                let half_v = (0.5 * FRAMING_FOV).to_radians();
                let half_h = (half_v.tan() * w as f32 / h as f32).atan();
                let seen = (radius / to_centre.length()).asin();
                assert!(seen <= half_v.min(half_h) + EPS, "{f:?}");
                assert!(seen >= 0.97 * half_v.min(half_h), "{f:?}: too far");
            }
        }
    }

    #[test]
    fn the_image_up_is_the_up_axis_projected_except_from_above() {
        for f in every_framing() {
            let cam = camera_of(f, 800, 600);
            let m = f.model_frame();
            let fwd = cam.forward();
            let expected = match f.view {
                // Down the up axis: the model's back is the image's up.
                View::Top => -m.back,
                _ => (m.up - m.up.dot(fwd) * fwd).normalize(),
            };
            assert!(close(cam.up_dir(), expected), "{f:?}: {}", cam.up_dir());
            assert!(cam.up_dir().is_finite());
        }
    }

    #[test]
    fn each_view_looks_from_its_side() {
        for up in Axis::ALL {
            let m = Framing {
                up,
                view: View::Front,
            }
            .model_frame();
            let from = |view| -camera_of(Framing { up, view }, 800, 600).forward();
            let front = from(View::Front);
            // Front: from the front, about 5° above the horizon.
            let elevation = front.dot(m.up).asin().to_degrees();
            assert!((4.0..6.0).contains(&elevation), "{up:?}: {elevation}");
            assert!(front.dot(m.back) > 0.99, "{up:?}");
            // Side: from the model's right, as high.
            let side = from(View::Side);
            assert!(side.dot(m.right) > 0.99, "{up:?}");
            assert!((side.dot(m.up) - front.dot(m.up)).abs() < EPS, "{up:?}");
            // Top: straight down the up axis, with the model's right on the image's right.
            assert!(close(from(View::Top), m.up), "{up:?}");
            let top = camera_of(
                Framing {
                    up,
                    view: View::Top,
                },
                800,
                600,
            );
            assert!(close(top.forward().cross(top.up_dir()), m.right), "{up:?}");
            // Iso: equally from the right, the front and above.
            let iso = from(View::Iso);
            for v in [m.right, m.back, m.up] {
                assert!((iso.dot(v) - 1.0 / 3.0f32.sqrt()).abs() < EPS, "{up:?}");
            }
        }
    }

    #[test]
    fn named_axes_frame_as_documented() {
        let front = |up| Framing {
            up,
            view: View::Front,
        };
        // +z up: seen from −y with +x on the right, as Blender's front view.
        let z = front(Axis::Z).model_frame();
        assert_eq!((z.right, z.back), (Vec3::X, Vec3::NEG_Y));
        // Negative axes turn the model over: −y is +y upside down, seen from −z.
        let ny = front(Axis::NegY).model_frame();
        assert_eq!(
            (ny.right, ny.up, ny.back),
            (Vec3::X, Vec3::NEG_Y, Vec3::NEG_Z)
        );
        let nz = front(Axis::NegZ).model_frame();
        assert_eq!((nz.up, nz.back), (Vec3::NEG_Z, Vec3::Y));
        let x = front(Axis::X).model_frame();
        assert_eq!((x.right, x.back), (Vec3::NEG_Y, Vec3::Z));
        let nx = front(Axis::NegX).model_frame();
        assert_eq!((nx.right, nx.back), (Vec3::Y, Vec3::Z));
        // +z up from the top: looking down −z, +y up the image.
        let top = camera_of(
            Framing {
                up: Axis::Z,
                view: View::Top,
            },
            800,
            600,
        );
        assert!(close(top.forward(), Vec3::NEG_Z));
        assert!(close(top.up_dir(), Vec3::Y));
    }

    #[test]
    fn the_light_keeps_its_place_in_every_view() {
        for f in every_framing() {
            let v = f.view_frame();
            let d = f.light_direction();
            // Travelling right, down and away from the camera: from the upper left behind it.
            assert!(d.dot(v.right) > 0.0 && d.dot(v.up) < 0.0 && d.dot(v.back) < 0.0);
            let canonical = Framing::default().light_direction();
            assert!((d.length() - canonical.length()).abs() < EPS, "{f:?}");
            // And it lights the model from above whenever the camera is not below it.
            assert!(d.dot(f.model_frame().up) < 0.0, "{f:?}");
        }
    }

    #[test]
    fn empty_and_degenerate_bounds_still_make_a_camera() {
        for f in every_framing() {
            for b in [Aabb::EMPTY, Aabb::new(Vec3::ONE, Vec3::ONE)] {
                let c = f.camera(b, 800, 600);
                Camera::new(
                    c.eye.0.as_vec3(),
                    c.look_at.0.as_vec3(),
                    c.up.0,
                    c.fov.0,
                    800,
                    600,
                )
                .unwrap();
            }
        }
    }

    /// A box of `lo` to `hi`: its six faces, two triangles each.
    fn boxed(lo: Vec3, hi: Vec3) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let p = (0..8)
            .map(|i| {
                Vec3::new(
                    if i & 1 == 0 { lo.x } else { hi.x },
                    if i & 2 == 0 { lo.y } else { hi.y },
                    if i & 4 == 0 { lo.z } else { hi.z },
                )
            })
            .collect();
        let faces = [
            [0, 2, 6, 4],
            [1, 5, 7, 3],
            [0, 4, 5, 1],
            [2, 3, 7, 6],
            [0, 1, 3, 2],
            [4, 6, 7, 5],
        ];
        let t = faces
            .iter()
            .flat_map(|[a, b, c, d]| [[*a, *b, *c], [*a, *c, *d]])
            .collect();
        (p, t)
    }

    /// An octahedron around `center` reaching `half` along each axis: no face is within 50° of
    /// flat, so it has no base; its lowest points are vertices.
    fn diamond(center: Vec3, half: Vec3) -> (Vec<Vec3>, Vec<[u32; 3]>) {
        let p = (0..6)
            .map(|i| {
                let mut d = Vec3::ZERO;
                d[i % 3] = if i < 3 { half[i % 3] } else { -half[i % 3] };
                center + d
            })
            .collect();
        let mut t = Vec::new();
        for x in [0, 3] {
            for y in [1, 4] {
                for z in [2, 5] {
                    t.push([x, y, z]);
                }
            }
        }
        (p, t)
    }

    /// Adds the square of corners `c` (in order) as two triangles.
    fn add_square(p: &mut Vec<Vec3>, t: &mut Vec<[u32; 3]>, c: [Vec3; 4]) {
        let n = p.len() as u32;
        p.extend(c);
        t.extend([[n, n + 1, n + 2], [n, n + 2, n + 3]]);
    }

    #[test]
    fn a_model_standing_on_the_origin_is_guessed_up_that_way() {
        for axis in [Axis::X, Axis::Y, Axis::Z] {
            let (p, t) = diamond(axis.vector(), Vec3::ONE);
            let g = guess_up(&p, &t);
            assert_eq!((g.up, g.ground, g.base), (axis, Some(axis), None));
        }
        // Beside the origin rather than over it: no ground.
        let (p, t) = diamond(Vec3::new(2.0, 1.0, 0.0), Vec3::ONE);
        assert_eq!(guess_up(&p, &t).ground, None);
        // In the corner of the positive octant: every axis ties, none wins.
        let (p, t) = diamond(Vec3::ONE, Vec3::ONE);
        assert_eq!(guess_up(&p, &t).ground, None);
        // Nothing at all: +y.
        let g = guess_up(&p, &[]);
        assert_eq!((g.up, g.ground, g.base), (Axis::Y, None, None));
        assert!(g.to_string().contains("the default"), "{g}");
    }

    #[test]
    fn a_flat_base_is_guessed_as_the_bottom_unless_it_is_the_whole_model() {
        // A box stands on any face: no base wins.
        let (p, t) = boxed(Vec3::new(3.0, 3.0, 3.0), Vec3::new(4.0, 5.0, 6.0));
        assert_eq!(guess_up(&p, &t), guess_up(&[], &[]));
        // A plate lying in z = 0 (off the origin): flat everywhere, so no clue.
        let p = vec![
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(2.0, 1.0, 0.0),
            Vec3::new(2.0, 2.0, 0.0),
        ];
        assert_eq!(guess_up(&p, &[[0, 1, 2]]), guess_up(&[], &[]));
        // A tall diamond along z on a square foot at its lowest z (8 % of the area).
        let (mut p, mut t) = diamond(Vec3::new(2.0, 2.0, 10.0), Vec3::new(1.0, 1.0, 8.0));
        let foot =
            [(1.0, 1.0), (3.0, 1.0), (3.0, 3.0), (1.0, 3.0)].map(|(x, y)| Vec3::new(x, y, 2.0));
        add_square(&mut p, &mut t, foot);
        let g = guess_up(&p, &t);
        assert_eq!((g.up, g.base, g.ground), (Axis::Z, Some(Axis::Z), None));
        assert!(
            g.to_string()
                .starts_with("up axis guessed as +z (a flat base"),
            "{g}"
        );
        // The same foot on top is a flat top: negative axes are not guessed.
        for q in &mut p {
            q.z = -q.z;
        }
        assert_eq!(guess_up(&p, &t).up, Axis::Y);
    }

    #[test]
    fn clues_that_disagree_keep_y() {
        // Standing on the origin along z, with a flat base at its lowest x.
        let (mut p, mut t) = diamond(Vec3::Z, Vec3::ONE);
        let side =
            [(-0.5, 0.5), (0.5, 0.5), (0.5, 1.5), (-0.5, 1.5)].map(|(y, z)| Vec3::new(-1.0, y, z));
        add_square(&mut p, &mut t, side);
        let g = guess_up(&p, &t);
        assert_eq!(
            (g.up, g.ground, g.base),
            (Axis::Y, Some(Axis::Z), Some(Axis::X))
        );
        assert!(g.to_string().contains("the clues disagree"), "{g}");
        // Clues that agree with +y say so.
        let (mut p, mut t) = diamond(Vec3::Y, Vec3::ONE);
        let foot =
            [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)].map(|(x, z)| Vec3::new(x, 0.0, z));
        add_square(&mut p, &mut t, foot);
        let g = guess_up(&p, &t);
        assert_eq!(
            (g.up, g.ground, g.base),
            (Axis::Y, Some(Axis::Y), Some(Axis::Y))
        );
        assert_eq!(
            g.to_string(),
            "up axis taken as +y (it stands on the plane y = 0, centred over the origin; a flat base at its lowest y)"
        );
    }
}
