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

/// The fewest instants at which a moving object's box is taken across the shutter.
const SWEEP_STEPS: usize = 64;
/// Steps per shortest part of a motion (a key's span, a swing, a turn).
const STEPS_PER_PART: f64 = 8.0;
/// The most steps: a motion faster than this shows is a blur of its whole path anyway.
const MOST_STEPS: usize = 1 << 14;

/// How many steps [`swept`] takes for `motion` over `shutter`: at least [`SWEEP_STEPS`], and
/// enough that each key's span, swing and turn spans several, so that between two steps every
/// point moves on a short, smooth stretch of its path.
fn steps_for(shutter: Shutter, motion: &Motion) -> usize {
    let keys = motion.keys().windows(2).map(|k| k[1].time - k[0].time);
    let periods = motion.oscillate().map(|o| o.period).into_iter();
    let shortest = keys
        .chain(periods)
        .chain(motion.orbit().map(|o| o.period))
        .fold(f64::INFINITY, f64::min);
    let length = shutter.close - shutter.open;
    let wanted = (STEPS_PER_PART * length / shortest).ceil();
    if wanted.is_finite() {
        (wanted as usize).clamp(SWEEP_STEPS, MOST_STEPS)
    } else {
        SWEEP_STEPS
    }
}

/// The box that points `at(t)` stay in while `t` runs over the shutter: their boxes at
/// `steps + 1` instants, widened by the farthest any point went between two of them (a point
/// that moves smoothly stays within that of the instants on either side).
fn swept<const N: usize>(
    shutter: Shutter,
    steps: usize,
    at: impl Fn(f64) -> Option<[Vec3; N]>,
) -> Aabb {
    let mut bounds = Aabb::EMPTY;
    let mut step = 0.0f32;
    let mut last: Option<[Vec3; N]> = None;
    for i in 0..=steps {
        let u = i as f32 / steps as f32;
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
fn sphere_sweep(shutter: Shutter, steps: usize, rest: &Sphere, motion: &Motion) -> Aabb {
    swept(shutter, steps, |t| {
        Some(corners(moved_sphere(rest, motion, t).bounds()))
    })
}

/// What an instance of a mesh with box `local`, placed by `placement`, sweeps under `motion`.
fn instance_sweep(
    shutter: Shutter,
    steps: usize,
    (local, placement): (Aabb, Affine3A),
    motion: &Motion,
) -> Aabb {
    if local.is_empty() {
        return local;
    }
    swept(shutter, steps, |t| {
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
            boxes.push(sphere_sweep(
                shutter,
                steps_for(shutter, motion),
                rest,
                motion,
            ));
        }
        for (k, placement, motion) in &anim.instances {
            primitives.push(Primitive::Instance(*k));
            let local = self.meshes[self.instances[*k as usize].0.mesh as usize].bounds;
            let steps = steps_for(shutter, motion);
            boxes.push(instance_sweep(shutter, steps, (local, *placement), motion));
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
                if let Some(tr) = Transform::moved(motion.at(t) * *placement) {
                    instances[*k as usize].0.transform = Some(tr);
                }
            }
        }
        if let Some((rest, motion)) = &anim.camera {
            *camera = rest.moved(motion.at(t));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::{Key, Orbit, Oscillate, Repeat};
    use proptest::prelude::*;
    use std::sync::atomic::{AtomicBool, Ordering};

    /// A motion with every part: two keys (moved, turned up to 170°, scaled), a swing and
    /// an orbit, each as fast as a shutter of a second can show.
    fn motion(v: [f32; 9], loops: bool) -> Motion {
        let keys = vec![
            Key::new(0.0),
            Key::new(0.7)
                .with_translate(Vec3::new(v[0], v[1], v[2]) * 4.0)
                .with_rotate_degrees(Vec3::new(v[3], v[4], v[5]) * 170.0)
                .with_scale(Vec3::splat(1.0 + v[6].abs())),
        ];
        let repeat = if loops { Repeat::Loop } else { Repeat::Bounce };
        let oscillate = Oscillate {
            offset: Vec3::new(v[7], 0.0, 1.0),
            period: 0.3,
            phase: 0.0,
        };
        let orbit = Orbit {
            center: Vec3::new(1.0, 0.0, v[8]),
            axis: Vec3::new(v[8], 1.0, 0.3),
            period: 0.9,
            phase: 0.5,
        };
        Motion::new(keys, repeat, Some(oscillate), Some(orbit)).unwrap()
    }

    proptest! {
        /// The boxes at the steps alone miss the object (checked to happen, so that the test
        /// can fail): the padding holds it.
        #[test]
        fn what_a_sweep_bounds_holds_the_object_at_every_instant(
            v in prop::array::uniform9(-1.0f32..1.0),
            loops: bool,
            open in -2.0f64..2.0,
            length in 0.0f64..1.5,
            u in prop::collection::vec(0.0f32..1.0, 64),
        ) {
            let m = motion(v, loops);
            let shutter = Shutter::new(open, open + length).unwrap();
            let steps = steps_for(shutter, &m);
            let local = Aabb::new(Vec3::new(-1.0, -0.5, -0.2), Vec3::new(1.0, 0.5, 0.2));
            let placement = Affine3A::from_translation(Vec3::new(0.0, 2.0, 0.0));
            let rest = Sphere { center: Vec3::new(0.5, 0.0, 0.0), radius: 0.4 };
            let (inst_box, sphere_box) = (
                instance_sweep(shutter, steps, (local, placement), &m),
                sphere_sweep(shutter, steps, &rest, &m),
            );
            let world_at = |t: f64| Transform::new(m.at(t) * placement).unwrap().bounds_to_world(local);
            let unpadded = (0..=steps)
                .map(|i| world_at(shutter.at(i as f32 / steps as f32)))
                .fold(Aabb::EMPTY, Aabb::union);
            let mut escaped = false;
            for u in u {
                let t = shutter.at(u);
                let world = world_at(t);
                prop_assert!(inst_box.grow(world.min).grow(world.max) == inst_box, "at {t}");
                escaped |= unpadded.grow(world.min).grow(world.max) != unpadded;
                let s = moved_sphere(&rest, &m, t).bounds();
                prop_assert!(sphere_box.grow(s.min).grow(s.max) == sphere_box, "at {t}");
            }
            ESCAPED.fetch_or(escaped, Ordering::Relaxed);
        }
    }

    static ESCAPED: AtomicBool = AtomicBool::new(false);

    #[test]
    fn the_steps_alone_miss_the_object() {
        // Run after (or with) the property above; it sets the flag when an unpadded box missed.
        what_a_sweep_bounds_holds_the_object_at_every_instant();
        assert!(
            ESCAPED.load(Ordering::Relaxed),
            "the padding was never needed"
        );
    }

    #[test]
    fn a_shutter_is_finite_and_forwards() {
        assert!(Shutter::new(0.0, 0.0).is_ok());
        assert_eq!(
            Shutter::new(1.0, 0.5),
            Err(ShutterError::Backwards(1.0, 0.5))
        );
        assert!(Shutter::new(f64::NAN, 1.0).is_err());
        assert_eq!(Shutter::new(2.0, 4.0).unwrap().at(0.25), 2.5);
    }
}
