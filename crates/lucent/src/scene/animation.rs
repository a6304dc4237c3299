//! Scenes that move: the moving objects' rest state and motions, and the scene at an instant.
//!
//! The static part of a scene (its meshes, their accelerators, the merged mesh, the top level
//! over the objects that stand still, the images and the light tables) is built once and
//! shared behind `Arc`s; an instant adds only the moving objects' places and a small top level
//! over them, so [`Scene::at_time`] costs about as much as the handful of objects that move.
//! Queries walk both top levels (see `query.rs`); the tie rule names primitives by their
//! index in the scene's arrays, not by where they are stored, so it is the same for both.

use super::Scene;
use crate::camera::Camera;
use crate::motion::Motion;
use crate::shape::{Primitive, Sphere, Transform};
use glam::Affine3A;
use lucent_accel::{Aabb, AccelKind, AnyAccelerator};
use std::sync::Arc;

/// What moves, at rest, and how.
#[derive(Debug)]
pub(super) struct Animation {
    /// Index into the scene's spheres, the sphere at rest, its motion.
    pub spheres: Vec<(u32, Sphere, Motion)>,
    /// Index into the scene's instances, its placement (object to world), its motion.
    pub instances: Vec<(u32, Affine3A, Motion)>,
    /// The camera as built, and its motion.
    pub camera: Option<(Camera, Motion)>,
    /// The bounds of everything that stands still.
    pub static_bounds: Aabb,
    /// The accelerator the moving objects' top level is built as.
    pub kind: AccelKind,
}

/// The top level over the moving objects at one instant.
#[derive(Debug)]
pub(super) struct Moving {
    pub primitives: Vec<Primitive>,
    pub accel: AnyAccelerator,
}

/// Sphere `rest` under motion `m` at time `t`: its centre carried as a point, its radius
/// scaled by the motion's (uniform) scale.
pub(super) fn moved_sphere(rest: &Sphere, m: &Motion, t: f64) -> Sphere {
    let (at, scale) = m.at_with_scale(t);
    Sphere {
        center: at.transform_point3(rest.center),
        radius: rest.radius * scale.x,
    }
}

impl Scene {
    /// Whether anything in the scene moves (an object or the camera).
    pub fn is_animated(&self) -> bool {
        self.animation.is_some()
    }

    /// How many objects move.
    pub fn moving_objects(&self) -> usize {
        self.animation
            .as_ref()
            .map_or(0, |a| a.spheres.len() + a.instances.len())
    }

    /// Whether the camera moves.
    pub fn camera_moves(&self) -> bool {
        self.animation.as_ref().is_some_and(|a| a.camera.is_some())
    }

    /// The scene at instant `t` seconds: every moving object at `M(t) · placement`, the
    /// moving objects' top level rebuilt, the bounds updated, and a moving camera at its
    /// place (the camera the scene was built with, moved; a camera set on this scene since
    /// is kept only when the camera does not move). A static scene comes back as it is. The
    /// instant is absolute: `at_time` of a scene returned by `at_time` is the same as of the
    /// scene built. The scene comes back without a shutter: it is one instant.
    ///
    /// Cheap: the static parts are shared, not copied; the arrays of spheres and instances
    /// are copied only when one of them moves.
    pub fn at_time(&self, t: f64) -> Scene {
        let mut scene = self.clone();
        scene.shutter = None;
        scene.blur = None;
        scene.place(t);
        scene
    }

    /// Puts the moving parts of this scene at instant `t`.
    pub(super) fn place(&mut self, t: f64) {
        let Some(anim) = self.animation.clone() else {
            return;
        };
        if !anim.spheres.is_empty() {
            let spheres = Arc::make_mut(&mut self.spheres);
            for (i, rest, motion) in &anim.spheres {
                spheres[*i as usize].0 = moved_sphere(rest, motion, t);
            }
        }
        if !anim.instances.is_empty() {
            let instances = Arc::make_mut(&mut self.instances);
            for (k, placement, motion) in &anim.instances {
                // A transform that rounds to singular at this instant (scales far beyond
                // f32) keeps the instance where it was.
                if let Some(tr) = Transform::new(motion.at(t) * *placement) {
                    instances[*k as usize].0.transform = Some(tr);
                }
            }
        }
        if anim.spheres.len() + anim.instances.len() > 0 {
            let mut primitives = Vec::new();
            let mut boxes = Vec::new();
            for (i, _, _) in &anim.spheres {
                primitives.push(Primitive::Sphere(*i));
                boxes.push(self.spheres[*i as usize].0.bounds());
            }
            for (k, _, _) in &anim.instances {
                primitives.push(Primitive::Instance(*k));
                let inst = &self.instances[*k as usize].0;
                let local = self.meshes[inst.mesh as usize].bounds;
                boxes.push(inst.transform.map_or(local, |t| t.bounds_to_world(local)));
            }
            self.bounds = boxes.iter().fold(anim.static_bounds, |b, x| b.union(*x));
            self.moving = Some(Arc::new(Moving {
                accel: anim.kind.build(&boxes),
                primitives,
            }));
        }
        if let Some((camera, motion)) = &anim.camera {
            self.camera = camera.moved(motion.at(t));
        }
    }
}
