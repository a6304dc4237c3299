//! The shutter: a render that sees its moving objects over an interval of time, as a camera
//! whose shutter stays open does (motion blur; Cook, Porter & Carpenter's distribution of rays
//! in time).
//!
//! Each camera sample draws an instant in the interval and is traced, with every ray it
//! spawns, in the scene at that instant. A thread renders in a copy of the scene
//! ([`Scene::instants`]) whose moving objects and camera [`Scene::put_at`] moves for each
//! sample. The copy's top level over the moving objects is built once, over the boxes they
//! sweep while the shutter is open, so putting the scene at an instant only moves the objects
//! that move: it costs as much as they do, not as the scene. What stands still is shared,
//! untouched, and a scene where nothing moves renders with a shutter exactly as without.

use super::Scene;
use super::animation::{Moving, moved_sphere};
use crate::motion::Motion;
use crate::shape::{Primitive, Sphere, Transform};
use glam::{Affine3A, Vec3};
use lucent_accel::Aabb;
use std::sync::Arc;
use thiserror::Error;

/// The interval of time the shutter is open, in seconds (the scene's motions' time).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shutter {
    open: f64,
    close: f64,
}

/// Why an interval is no shutter.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum ShutterError {
    /// A time that is NaN or infinite.
    #[error("the shutter's times must be finite (got {0} and {1})")]
    NotFinite(f64, f64),
    /// The shutter closes before it opens.
    #[error("the shutter closes ({1}) before it opens ({0})")]
    Backwards(f64, f64),
}

impl Shutter {
    /// Open from `open` to `close` seconds; `open == close` is one instant.
    pub fn new(open: f64, close: f64) -> Result<Self, ShutterError> {
        if !(open.is_finite() && close.is_finite()) {
            return Err(ShutterError::NotFinite(open, close));
        }
        if close < open {
            return Err(ShutterError::Backwards(open, close));
        }
        Ok(Self { open, close })
    }

    /// When it opens.
    pub fn open(&self) -> f64 {
        self.open
    }

    /// When it closes.
    pub fn close(&self) -> f64 {
        self.close
    }

    /// The instant a fraction `u` in `[0, 1)` of the way through.
    pub fn at(&self, u: f32) -> f64 {
        self.open + (self.close - self.open) * f64::from(u)
    }
}

/// What a scene with a shutter renders from: the moving objects' top level over what they
/// sweep, and the scene's bounds over the interval.
#[derive(Debug)]
pub(super) struct Blur {
    /// `None` when only the camera moves.
    pub moving: Option<Arc<Moving>>,
    pub bounds: Aabb,
}

/// Instants at which a moving object's box is taken across the shutter.
const SWEEP_STEPS: usize = 64;

/// The box that points `at(t)` stay in while `t` runs over the shutter: their boxes at
/// [`SWEEP_STEPS`] + 1 instants, widened by the farthest any point went between two of them
/// (a point that moves smoothly stays within that of the instants on either side).
fn swept<const N: usize>(shutter: Shutter, at: impl Fn(f64) -> Option<[Vec3; N]>) -> Aabb {
    let mut bounds = Aabb::EMPTY;
    let mut step = 0.0f32;
    let mut last: Option<[Vec3; N]> = None;
    for i in 0..=SWEEP_STEPS {
        let u = i as f32 / SWEEP_STEPS as f32;
        let Some(points) = at(shutter.at(u)) else {
            continue;
        };
        if let Some(prev) = last {
            for (a, b) in prev.iter().zip(&points) {
                step = step.max(a.distance(*b));
            }
        }
        bounds = points.iter().fold(bounds, |b, p| b.grow(*p));
        last = Some(points);
    }
    if bounds.is_empty() || !step.is_finite() {
        return bounds;
    }
    Aabb::new(
        bounds.min - Vec3::splat(step),
        bounds.max + Vec3::splat(step),
    )
}

/// The corners of `b`.
fn corners(b: Aabb) -> [Vec3; 8] {
    std::array::from_fn(|i| {
        Vec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        )
    })
}

/// What sphere `rest` under `motion` sweeps: its box's corners carried.
fn sphere_sweep(shutter: Shutter, rest: &Sphere, motion: &Motion) -> Aabb {
    swept(shutter, |t| {
        Some(corners(moved_sphere(rest, motion, t).bounds()))
    })
}

/// What an instance of a mesh with box `local`, placed by `placement`, sweeps under `motion`.
fn instance_sweep(shutter: Shutter, local: Aabb, placement: Affine3A, motion: &Motion) -> Aabb {
    if local.is_empty() {
        return local;
    }
    swept(shutter, |t| {
        let m = motion.at(t) * placement;
        Some(corners(local).map(|c| m.transform_point3(c)))
    })
}

impl Scene {
    /// This scene seen through `shutter`: a render draws each camera sample's instant in it.
    /// Replaces a shutter set before. A scene where nothing moves is unchanged by it (and
    /// renders the same bit for bit); [`Scene::at_time`] takes the shutter away again.
    pub fn with_shutter(mut self, shutter: Shutter) -> Scene {
        self.shutter = Some(shutter);
        let Some(anim) = self.animation.clone() else {
            return self;
        };
        let mut primitives = Vec::new();
        let mut boxes = Vec::new();
        for (i, rest, motion) in &anim.spheres {
            primitives.push(Primitive::Sphere(*i));
            boxes.push(sphere_sweep(shutter, rest, motion));
        }
        for (k, placement, motion) in &anim.instances {
            primitives.push(Primitive::Instance(*k));
            let local = self.meshes[self.instances[*k as usize].0.mesh as usize].bounds;
            boxes.push(instance_sweep(shutter, local, *placement, motion));
        }
        let bounds = boxes.iter().fold(anim.static_bounds, |b, x| b.union(*x));
        let moving = (!primitives.is_empty()).then(|| {
            Arc::new(Moving {
                accel: anim.kind.build(&boxes),
                primitives,
            })
        });
        self.blur = Some(Arc::new(Blur { moving, bounds }));
        self
    }

    /// The shutter a render sees this scene through, if any (also when nothing moves).
    pub fn shutter(&self) -> Option<Shutter> {
        self.shutter
    }

    /// Whether a render draws an instant for each sample: a shutter, and something moves.
    pub fn blurs(&self) -> bool {
        self.blur.is_some()
    }

    /// A copy of this scene for one thread of a render with a shutter, to [`Scene::put_at`]
    /// each sample's instant; `None` when nothing blurs. What stands still is shared with
    /// this scene; the arrays of spheres and instances are the copy's own when one of them
    /// moves.
    pub fn instants(&self) -> Option<Scene> {
        let blur = self.blur.as_ref()?;
        let mut copy = self.clone();
        copy.moving = blur.moving.clone();
        copy.bounds = blur.bounds;
        if let Some(anim) = &self.animation {
            if !anim.spheres.is_empty() {
                Arc::make_mut(&mut copy.spheres);
            }
            if !anim.instances.is_empty() {
                Arc::make_mut(&mut copy.instances);
            }
        }
        copy.put_at(self.shutter.map_or(0.0, |s| s.open));
        Some(copy)
    }

    /// Puts the moving objects and a moving camera of a copy from [`Scene::instants`] at
    /// instant `t` (within the shutter): cheap, the top level over them is not rebuilt.
    pub fn put_at(&mut self, t: f64) {
        let Scene {
            animation,
            spheres,
            instances,
            camera,
            ..
        } = self;
        let Some(anim) = animation else {
            return;
        };
        if !anim.spheres.is_empty() {
            let spheres = Arc::make_mut(spheres);
            for (i, rest, motion) in &anim.spheres {
                spheres[*i as usize].0 = moved_sphere(rest, motion, t);
            }
        }
        if !anim.instances.is_empty() {
            let instances = Arc::make_mut(instances);
            for (k, placement, motion) in &anim.instances {
                if let Some(tr) = Transform::new(motion.at(t) * *placement) {
                    instances[*k as usize].0.transform = Some(tr);
                }
            }
        }
        if let Some((rest, motion)) = &anim.camera {
            *camera = rest.moved(motion.at(t));
        }
    }
}
