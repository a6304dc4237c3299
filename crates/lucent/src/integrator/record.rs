//! The ray tree of a pixel, as the lecture draws it: every camera, reflected and refracted ray,
//! what it hit, the shadow rays to each light, and what each contributes to the pixel.
//!
//! The Whitted integrator tells a [`Recorder`] what it does ([`NoRecord`] when rendering, which
//! compiles to nothing); [`RayTree`] keeps it. A node's *contribution* to the pixel is its
//! weight (the product of the `kr`/`kt` factors from the camera) times its local colour (ambient,
//! emission and the lights, or the background for a miss): the pixel's value is the sum of the
//! contributions of every node of its tree.

use crate::Rgb;
use crate::shape::SurfaceHit;
use lucent_accel::Ray;

/// What kind of ray a node is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RayKind {
    /// From the eye through the pixel.
    Camera,
    /// Mirror-reflected (`kr`, and `kt` under total internal reflection).
    Reflected,
    /// Refracted by Snell's law (`kt`).
    Refracted,
}

impl RayKind {
    /// The kind's name as `lucent explain` prints it.
    pub fn name(self) -> &'static str {
        match self {
            RayKind::Camera => "camera",
            RayKind::Reflected => "reflected",
            RayKind::Refracted => "refracted",
        }
    }
}

/// Why a ray was not traced, or a refraction became a reflection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cut {
    /// The ray's weight fell under `min_weight`.
    Weight(RayKind, Rgb),
    /// The depth limit `max_depth` was reached.
    Depth,
    /// The per-pixel budget of secondary rays ran out.
    Budget(RayKind),
    /// Total internal reflection: no refracted ray; its `kt` went to the reflected one.
    TotalInternalReflection,
}

/// Told what the integrator does, in order: `begin` a ray, its `hit`, its `light` terms and
/// `local` colour, its `cut`s, its children (nested `begin`…`end`), then its `end`.
pub trait Recorder {
    /// A ray of `kind` with `weight` starts.
    fn begin(&mut self, kind: RayKind, ray: &Ray, weight: Rgb);
    /// What it hit (`None`: nothing).
    fn hit(&mut self, hit: Option<&SurfaceHit>);
    /// Light `index`'s shadow term and what it adds to the local colour.
    fn light(&mut self, index: usize, shadow: Rgb, term: Rgb);
    /// The ray's local colour: ambient + emission + lights, or the background.
    fn local(&mut self, color: Rgb);
    /// A ray not traced, or total internal reflection.
    fn cut(&mut self, cut: Cut);
    /// The ray's radiance, children included.
    fn end(&mut self, radiance: Rgb);
}

/// Records nothing.
pub struct NoRecord;

impl Recorder for NoRecord {
    #[inline(always)]
    fn begin(&mut self, _: RayKind, _: &Ray, _: Rgb) {}
    #[inline(always)]
    fn hit(&mut self, _: Option<&SurfaceHit>) {}
    #[inline(always)]
    fn light(&mut self, _: usize, _: Rgb, _: Rgb) {}
    #[inline(always)]
    fn local(&mut self, _: Rgb) {}
    #[inline(always)]
    fn cut(&mut self, _: Cut) {}
    #[inline(always)]
    fn end(&mut self, _: Rgb) {}
}

/// What a ray hit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HitRecord {
    /// Distance along the (unit) ray.
    pub t: f32,
    /// The point.
    pub point: glam::Vec3,
    /// The scene object (its index in the scene file's order).
    pub object: u32,
    /// The material index.
    pub material: u32,
    /// True when the ray met the surface's front (entering a solid).
    pub entering: bool,
}

/// One shadow ray's outcome.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightRecord {
    /// The light's index in the scene.
    pub index: usize,
    /// `S_j`: 1 unblocked, 0 blocked, between for transmissive blockers.
    pub shadow: Rgb,
    /// What the light adds to the node's local colour.
    pub term: Rgb,
}

/// One ray of the tree.
#[derive(Clone, Debug, PartialEq)]
pub struct RayNode {
    /// Camera, reflected or refracted.
    pub kind: RayKind,
    /// Where it starts.
    pub origin: glam::Vec3,
    /// Its unit direction.
    pub dir: glam::Vec3,
    /// Product of the `kr`/`kt` factors from the camera.
    pub weight: Rgb,
    /// What it hit.
    pub hit: Option<HitRecord>,
    /// Shadow rays, one per light facing the point.
    pub lights: Vec<LightRecord>,
    /// Ambient + emission + lights, or the background.
    pub local: Rgb,
    /// Rays not traced, and total internal reflection.
    pub cuts: Vec<Cut>,
    /// Reflected and refracted rays.
    pub children: Vec<RayNode>,
    /// Its radiance, children included.
    pub radiance: Rgb,
}

impl RayNode {
    /// `weight × local`: what this ray alone adds to the pixel.
    pub fn contribution(&self) -> Rgb {
        self.weight * self.local
    }

    /// Every node, depth first (this one first).
    pub fn walk(&self) -> Vec<&RayNode> {
        let mut out = vec![self];
        for c in &self.children {
            out.extend(c.walk());
        }
        out
    }
}

/// Builds the tree of one camera ray.
#[derive(Default)]
pub struct RayTree {
    stack: Vec<RayNode>,
    /// The finished tree.
    pub root: Option<RayNode>,
}

impl Recorder for RayTree {
    fn begin(&mut self, kind: RayKind, ray: &Ray, weight: Rgb) {
        self.stack.push(RayNode {
            kind,
            origin: ray.origin,
            dir: ray.dir,
            weight,
            hit: None,
            lights: Vec::new(),
            local: Rgb::BLACK,
            cuts: Vec::new(),
            children: Vec::new(),
            radiance: Rgb::BLACK,
        });
    }

    fn hit(&mut self, hit: Option<&SurfaceHit>) {
        if let Some(node) = self.stack.last_mut() {
            node.hit = hit.map(|h| HitRecord {
                t: h.t * node.dir.length(),
                point: h.point,
                object: h.object,
                material: h.material,
                entering: h.normal.dot(node.dir) < 0.0,
            });
        }
    }

    fn light(&mut self, index: usize, shadow: Rgb, term: Rgb) {
        if let Some(node) = self.stack.last_mut() {
            node.lights.push(LightRecord {
                index,
                shadow,
                term,
            });
        }
    }

    fn local(&mut self, color: Rgb) {
        if let Some(node) = self.stack.last_mut() {
            node.local = color;
        }
    }

    fn cut(&mut self, cut: Cut) {
        if let Some(node) = self.stack.last_mut() {
            node.cuts.push(cut);
        }
    }

    fn end(&mut self, radiance: Rgb) {
        let Some(mut node) = self.stack.pop() else {
            return;
        };
        node.radiance = radiance;
        match self.stack.last_mut() {
            Some(parent) => parent.children.push(node),
            None => self.root = Some(node),
        }
    }
}
