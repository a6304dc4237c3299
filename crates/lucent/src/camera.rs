//! The camera: a ray from the eye through every point of the image — a pinhole, or a thin
//! lens that focuses at one distance and blurs what is nearer or farther (depth of field) — or
//! an orthographic projection, whose parallel rays start across the image's rectangle.

use glam::Vec3;
use lucent_accel::{Frustum, Ray};
use thiserror::Error;

/// Why a camera cannot be built.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum CameraError {
    /// `look_at` equals `eye` (or they are too far apart for their difference to be finite).
    #[error(
        "the camera's eye and look_at are the same point, or too far apart to give a direction"
    )]
    NoViewDirection,
    /// `up` is zero or parallel to the view direction: the image's roll is undefined.
    #[error("the camera's up vector is zero or parallel to the view direction")]
    UpParallelToView,
    /// The field of view is not strictly between 0 and 180 degrees.
    #[error("the field of view must be between 0 and 180 degrees (exclusive), got {0}")]
    FieldOfView(f32),
    /// An orthographic view that is not a positive, finite height.
    #[error("an orthographic camera's view height must be positive and finite, got {0}")]
    ViewHeight(f32),
    /// A zero width or height.
    #[error("the image must be at least 1×1 pixels, got {0}×{1}")]
    Resolution(u32, u32),
    /// A non-finite input.
    #[error("the camera's eye, look_at and up must be finite")]
    NotFinite,
    /// A negative or non-finite aperture, or a focus distance that is not positive.
    #[error("the lens needs an aperture radius ≥ 0 and a positive focus distance, got {0} and {1}")]
    Lens(f32, f32),
}

/// A pinhole camera with its image resolution.
///
/// Image coordinates `(x, y)` run over `[0, width) × [0, height)` in pixels: `x` to the right,
/// `y` downwards, so row 0 is the top of the image; pixel `(i, j)` covers `[i, i+1) × [j, j+1)`
/// and its centre is `(i + 0.5, j + 0.5)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    eye: Vec3,
    forward: Vec3,
    /// Unit right vector scaled to half the image width at unit distance.
    right: Vec3,
    /// Unit up vector scaled to half the image height at unit distance.
    up: Vec3,
    width: u32,
    height: u32,
    /// Radius of the thin lens's aperture; 0 for a pinhole.
    lens_radius: f32,
    /// Distance along the view direction of the plane in focus.
    focus_distance: f32,
    /// Orthographic: `right` and `up` are the half width and height of the view in scene
    /// units, and every ray runs along `forward` from the plane through the eye.
    orthographic: bool,
}

impl Camera {
    /// A camera at `eye` looking at `look_at`, with `up` giving the image's upright direction
    /// and `fov_degrees` its vertical field of view; the aspect ratio is `width / height`.
    pub fn new(
        eye: Vec3,
        look_at: Vec3,
        up: Vec3,
        fov_degrees: f32,
        width: u32,
        height: u32,
    ) -> Result<Self, CameraError> {
        if !(eye.is_finite() && look_at.is_finite() && up.is_finite()) {
            return Err(CameraError::NotFinite);
        }
        if !(fov_degrees > 0.0 && fov_degrees < 180.0) {
            return Err(CameraError::FieldOfView(fov_degrees));
        }
        if width == 0 || height == 0 {
            return Err(CameraError::Resolution(width, height));
        }
        let forward = (look_at - eye)
            .try_normalize()
            .ok_or(CameraError::NoViewDirection)?;
        let right = forward
            .cross(up)
            .try_normalize()
            .ok_or(CameraError::UpParallelToView)?;
        let true_up = right.cross(forward);
        let half_height = (fov_degrees.to_radians() / 2.0).tan();
        let half_width = half_height * width as f32 / height as f32;
        Ok(Self {
            eye,
            forward,
            right: right * half_width,
            up: true_up * half_height,
            width,
            height,
            lens_radius: 0.0,
            focus_distance: 1.0,
            orthographic: false,
        })
    }

    /// This camera made orthographic: parallel rays along the view direction, starting on the
    /// plane through the eye, over a view `height` scene units high (as wide as the image's
    /// aspect makes it). The lens is dropped.
    pub fn orthographic(mut self, height: f32) -> Result<Self, CameraError> {
        if !(height > 0.0 && height.is_finite()) {
            return Err(CameraError::ViewHeight(height));
        }
        let half = height / 2.0;
        self.right = self.right.normalize() * half * self.width as f32 / self.height as f32;
        self.up = self.up.normalize() * half;
        self.lens_radius = 0.0;
        self.orthographic = true;
        Ok(self)
    }

    /// Whether the rays are parallel (see [`Camera::orthographic`]).
    pub fn is_orthographic(&self) -> bool {
        self.orthographic
    }

    /// This camera with a thin lens of aperture radius `radius` focused at `focus_distance`
    /// along the view direction (radius 0 keeps a pinhole).
    pub fn with_lens(mut self, radius: f32, focus_distance: f32) -> Result<Self, CameraError> {
        if !(radius >= 0.0
            && radius.is_finite()
            && focus_distance > 0.0
            && focus_distance.is_finite())
        {
            return Err(CameraError::Lens(radius, focus_distance));
        }
        self.lens_radius = radius;
        self.focus_distance = focus_distance;
        Ok(self)
    }

    /// The aperture radius (0: a pinhole) and the focus distance.
    pub fn lens(&self) -> (f32, f32) {
        (self.lens_radius, self.focus_distance)
    }

    /// The ray through image point `(x, y)` from the point of the lens chosen by `u` (uniform
    /// in the unit square, mapped to the aperture's disc): every such ray meets the pinhole
    /// ray at the plane in focus. A pinhole camera ignores `u`.
    pub fn ray_through_lens(&self, x: f32, y: f32, u: glam::Vec2) -> Ray {
        let pinhole = self.ray(x, y);
        if !self.has_lens() {
            return pinhole;
        }
        let along = pinhole.dir.dot(self.forward);
        let focus = self.eye + pinhole.dir * (self.focus_distance / along);
        let disc = crate::sampling::warp::square_to_concentric_disk(u) * self.lens_radius;
        let origin = self.eye + self.right.normalize() * disc.x + self.up.normalize() * disc.y;
        Ray::new(origin, (focus - origin).normalize())
    }

    /// Image width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Image height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The eye point.
    pub fn eye(&self) -> Vec3 {
        self.eye
    }

    /// The size of a pixel, at the image's centre, on a plane facing the camera at
    /// `distance`: the angle it subtends times the distance, or (orthographic) its width.
    pub fn pixel_size_at(&self, distance: f32) -> f32 {
        let size = 2.0 * self.up.length() / self.height as f32;
        if self.orthographic {
            size
        } else {
            size * distance
        }
    }

    /// The ray from the eye through image point `(x, y)` (see the type's docs), unit direction;
    /// for an orthographic camera, the ray along the view from that point of the view's
    /// rectangle.
    pub fn ray(&self, x: f32, y: f32) -> Ray {
        if self.orthographic {
            let ndc_x = 2.0 * x / self.width as f32 - 1.0;
            let ndc_y = 1.0 - 2.0 * y / self.height as f32;
            return Ray::new(
                self.eye + ndc_x * self.right + ndc_y * self.up,
                self.forward,
            );
        }
        Ray::new(self.eye, self.direction(x, y).normalize())
    }

    /// The direction through image point `(x, y)`, not normalised: linear in `(x, y)`, so the
    /// rays through a rectangle of the image lie in the cone of its corners' directions.
    fn direction(&self, x: f32, y: f32) -> Vec3 {
        let ndc_x = 2.0 * x / self.width as f32 - 1.0;
        let ndc_y = 1.0 - 2.0 * y / self.height as f32;
        self.forward + ndc_x * self.right + ndc_y * self.up
    }

    /// How far a surface point moves in the scene from one pixel to the next, along the
    /// image's x and y: the rays through the neighbouring pixels of the one that sees `p`, met
    /// with the plane through `p` perpendicular to `n` (pbrt-v4's `Approximate_dp_dxy`, exact
    /// for a camera ray through a pinhole; a thin lens counts as its pinhole). Texture lookups
    /// filter over this footprint. Zero vectors where the plane is seen edge-on or the point is
    /// behind the camera.
    pub fn footprint(&self, p: Vec3, n: Vec3) -> [Vec3; 2] {
        if self.orthographic {
            // The neighbouring rays are parallel, one pixel across: moved onto the plane.
            let steps = [
                self.right * (2.0 / self.width as f32),
                self.up * (-2.0 / self.height as f32),
            ];
            let denom = n.dot(self.forward);
            return steps.map(|step| {
                let moved = step - self.forward * (n.dot(step) / denom);
                if denom.abs() > 1e-6 && moved.is_finite() {
                    moved
                } else {
                    Vec3::ZERO
                }
            });
        }
        let to_p = p - self.eye;
        let depth = to_p.dot(self.forward);
        if depth.is_nan() || depth <= 0.0 {
            return [Vec3::ZERO; 2];
        }
        // The direction to p in the form of `direction` (forward component 1), and the steps
        // of one pixel along x and y.
        let d = to_p / depth;
        let steps = [
            self.right * (2.0 / self.width as f32),
            self.up * (-2.0 / self.height as f32),
        ];
        let plane = n.dot(to_p);
        steps.map(|step| {
            let dir = d + step;
            let denom = n.dot(dir);
            let t = plane / denom;
            let moved = self.eye + dir * t - p;
            if denom.abs() > 1e-6 * dir.length() && moved.is_finite() {
                moved
            } else {
                Vec3::ZERO
            }
        })
    }

    /// True for a pinhole: every ray starts at the eye.
    pub fn is_pinhole(&self) -> bool {
        self.lens_radius == 0.0 && !self.orthographic
    }

    /// True for a thin lens: rays start across its aperture, drawn by a lens sample.
    pub fn has_lens(&self) -> bool {
        self.lens_radius > 0.0
    }

    /// The beam of the pinhole's rays through the image rectangle `[x0, x1] × [y0, y1]` (pixel
    /// coordinates, which may reach outside the image): `None` for a thin lens or an
    /// orthographic camera, whose rays do not share an origin, or for a rectangle too thin to
    /// span a cone.
    pub fn frustum(&self, (x0, y0): (f32, f32), (x1, y1): (f32, f32)) -> Option<Frustum> {
        if !self.is_pinhole() {
            return None;
        }
        let corners = [(x0, y0), (x1, y0), (x1, y1), (x0, y1)].map(|(x, y)| self.direction(x, y));
        Frustum::new(self.eye, corners)
    }
}

/// What a viewer needs to build a camera of its own, and the camera under a motion.
impl Camera {
    /// The unit view direction.
    pub fn forward(&self) -> Vec3 {
        self.forward
    }

    /// The image's unit up direction (perpendicular to the view direction).
    pub fn up_dir(&self) -> Vec3 {
        self.up.normalize()
    }

    /// The vertical field of view, in degrees.
    pub fn fov_degrees(&self) -> f32 {
        2.0 * self.up.length().atan().to_degrees()
    }

    /// Image width and height in pixels.
    pub fn resolution(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// This camera carried by the world-space transform `m` (a motion at one instant): the eye
    /// as a point, the view frame by the linear part, each frame vector kept at its length
    /// (so a scale in `m` changes neither the field of view nor the aspect). The lens and
    /// the resolution stay.
    pub fn moved(&self, m: glam::Affine3A) -> Camera {
        let carry = |v: Vec3| {
            let w = m.transform_vector3(v);
            w.try_normalize().map_or(v, |u| u * v.length())
        };
        let eye = m.transform_point3(self.eye);
        let eye = if eye.is_finite() { eye } else { self.eye };
        if m.matrix3 == glam::Mat3A::IDENTITY {
            // A pure translation keeps the frame bit for bit.
            return Camera { eye, ..*self };
        }
        Camera {
            eye,
            forward: carry(self.forward),
            right: carry(self.right),
            up: carry(self.up),
            ..*self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_footprint_is_the_distance_between_neighbouring_pixels_rays() {
        // 90° across 100 pixels: at distance 10 straight ahead a pixel is 0.2 wide.
        let c = Camera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 90.0, 100, 100).unwrap();
        let p = Vec3::new(0.0, 0.0, -10.0);
        let [dx, dy] = c.footprint(p, Vec3::Z);
        assert!((dx - Vec3::new(0.2, 0.0, 0.0)).length() < 1e-4, "{dx}");
        assert!((dy - Vec3::new(0.0, -0.2, 0.0)).length() < 1e-4, "{dy}");
        // The same ray hitting the pixel's neighbour's point: the footprint is that step.
        let hit = c.ray(50.5, 50.5);
        let q = hit.at(10.0 / hit.dir.dot(-Vec3::Z));
        let next = c.ray(51.5, 50.5);
        let q1 = next.at(10.0 / next.dir.dot(-Vec3::Z));
        let [dx, _] = c.footprint(q, Vec3::Z);
        assert!((q + dx - q1).length() < 1e-3, "{} vs {}", q + dx, q1);
        // A floor seen at a glancing angle stretches the footprint along the view.
        let floor = Vec3::new(0.0, -1.0, -10.0);
        let [_, dy] = c.footprint(floor, Vec3::Y);
        assert!(dy.length() > 1.0, "{dy}");
        assert_eq!(
            c.footprint(Vec3::new(0.0, 0.0, 5.0), Vec3::Z),
            [Vec3::ZERO; 2]
        );
    }

    fn camera(width: u32, height: u32) -> Camera {
        Camera::new(
            Vec3::new(0.0, 0.0, 5.0),
            Vec3::ZERO,
            Vec3::Y,
            90.0,
            width,
            height,
        )
        .unwrap()
    }

    #[test]
    fn the_image_centre_looks_at_the_target() {
        let ray = camera(4, 2).ray(2.0, 1.0);
        assert_eq!(ray.origin, Vec3::new(0.0, 0.0, 5.0));
        assert!((ray.dir - -Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn row_zero_is_the_top_and_the_edges_span_the_fov() {
        let c = camera(2, 2);
        // Top edge at the vertical centre line: 45° up for a 90° field of view.
        let top = c.ray(1.0, 0.0).dir;
        assert!((top - Vec3::new(0.0, 1.0, -1.0).normalize()).length() < 1e-6);
        let right = c.ray(2.0, 1.0).dir;
        assert!((right - Vec3::new(1.0, 0.0, -1.0).normalize()).length() < 1e-6);
    }

    #[test]
    fn wide_images_widen_the_horizontal_extent() {
        let c = camera(4, 2);
        let right = c.ray(4.0, 1.0).dir;
        assert!((right - Vec3::new(2.0, 0.0, -1.0).normalize()).length() < 1e-6);
    }

    #[test]
    fn orthographic_rays_are_parallel_across_the_view() {
        // A view 4 units high on a 2:1 image: 8 wide.
        let c = camera(4, 2).orthographic(4.0).unwrap();
        assert!(
            c.is_orthographic() && !c.is_pinhole() && c.frustum((0.0, 0.0), (1.0, 1.0)).is_none()
        );
        let centre = c.ray(2.0, 1.0);
        assert_eq!(centre.origin, Vec3::new(0.0, 0.0, 5.0));
        let corner = c.ray(0.0, 0.0);
        assert!(
            (corner.origin - Vec3::new(-4.0, 2.0, 5.0)).length() < 1e-6,
            "{}",
            corner.origin
        );
        assert_eq!(corner.dir, centre.dir);
        assert!((centre.dir - -Vec3::Z).length() < 1e-6);
        // A pixel is 2 units at any distance; on a floor seen at 45° it stretches by √2.
        assert!((c.pixel_size_at(1.0) - 2.0).abs() < 1e-6);
        assert!((c.pixel_size_at(100.0) - 2.0).abs() < 1e-6);
        let [dx, dy] = c.footprint(Vec3::ZERO, Vec3::new(0.0, 1.0, 1.0).normalize());
        assert!((dx - Vec3::new(2.0, 0.0, 0.0)).length() < 1e-5, "{dx}");
        assert!((dy.length() - 2.0 * 2f32.sqrt()).abs() < 1e-4, "{dy}");
        assert_eq!(
            camera(4, 2).orthographic(0.0),
            Err(CameraError::ViewHeight(0.0))
        );
    }

    #[test]
    fn degenerate_cameras_are_refused() {
        let e = Vec3::ZERO;
        assert_eq!(
            Camera::new(e, e, Vec3::Y, 60.0, 1, 1),
            Err(CameraError::NoViewDirection)
        );
        assert_eq!(
            Camera::new(e, Vec3::Y, Vec3::Y, 60.0, 1, 1),
            Err(CameraError::UpParallelToView)
        );
        assert_eq!(
            Camera::new(e, Vec3::Z, Vec3::Y, 180.0, 1, 1),
            Err(CameraError::FieldOfView(180.0))
        );
        assert_eq!(
            Camera::new(e, Vec3::Z, Vec3::Y, 60.0, 0, 1),
            Err(CameraError::Resolution(0, 1))
        );
    }

    #[test]
    fn getters_give_back_the_construction() {
        let c = Camera::new(
            Vec3::new(1.0, 2.0, 3.0),
            Vec3::new(1.0, 2.0, 0.0),
            Vec3::Y,
            50.0,
            32,
            16,
        )
        .unwrap();
        assert_eq!(c.eye(), Vec3::new(1.0, 2.0, 3.0));
        assert!((c.forward() - -Vec3::Z).length() < 1e-6);
        assert!((c.up_dir() - Vec3::Y).length() < 1e-6);
        assert!((c.fov_degrees() - 50.0).abs() < 1e-4);
        assert_eq!(c.resolution(), (32, 16));
    }

    #[test]
    fn a_moved_camera_turns_its_pinhole_rays() {
        // A quarter turn about +y, scaled by 2: the eye at +z goes to +2x, the view along −z
        // turns to −x, and the field of view stays.
        let c = camera(4, 2);
        let m = glam::Affine3A::from_scale_rotation_translation(
            Vec3::splat(2.0),
            glam::Quat::from_rotation_y(std::f32::consts::FRAC_PI_2),
            Vec3::ZERO,
        );
        let moved = c.moved(m);
        let ray = moved.ray(2.0, 1.0);
        assert!((ray.origin - Vec3::new(10.0, 0.0, 0.0)).length() < 1e-5);
        assert!((ray.dir - -Vec3::X).length() < 1e-6);
        let corner = moved.ray(4.0, 0.0).dir;
        let expected = m.transform_vector3(c.ray(4.0, 0.0).dir).normalize();
        assert!((corner - expected).length() < 1e-6);
        assert_eq!(moved.lens(), c.lens());
        assert_eq!(c.moved(glam::Affine3A::IDENTITY), c);
    }
}
