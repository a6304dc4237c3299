//! The scene at an instant, shared between threads: one snapshot per step of time.
//!
//! [`Scene::at_time`] rebuilds only what moves (transforms, the top level), but even that is
//! too much per sample; samples within one `step` of each other share a snapshot, so an
//! instant is resolved to `step` (a millisecond in the viewer, an eighth of a refresh in the
//! study).

use crate::scene::Scene;
use std::collections::VecDeque;
use std::sync::{Arc, Mutex};

/// How many snapshots are kept: the threads' instants are close together.
const KEPT: usize = 16;

/// Snapshots of an animated scene, made on demand.
#[derive(Debug)]
pub struct Snapshots {
    base: Arc<Scene>,
    step: f64,
    cache: Mutex<VecDeque<(i64, Arc<Scene>)>>,
}

impl Snapshots {
    /// Snapshots of `scene` every `step` seconds (`step` > 0).
    pub fn new(scene: Arc<Scene>, step: f64) -> Self {
        Self {
            base: scene,
            step: if step > 0.0 { step } else { 1e-3 },
            cache: Mutex::new(VecDeque::new()),
        }
    }

    /// The instant that samples at `t` are traced at: `t` rounded down to a step.
    pub fn instant(&self, t: f64) -> f64 {
        (t / self.step).floor() * self.step
    }

    /// The scene at `t` (at [`Snapshots::instant`] of it); the scene itself when nothing moves.
    pub fn at(&self, t: f64) -> Arc<Scene> {
        if !self.base.is_animated() {
            return self.base.clone();
        }
        let key = (t / self.step).floor() as i64;
        if let Some((_, s)) = self.lock().iter().find(|(k, _)| *k == key) {
            return s.clone();
        }
        // Built outside the lock: another thread may build the same one meanwhile, harmlessly.
        let scene = Arc::new(self.base.at_time(key as f64 * self.step));
        let mut cache = self.lock();
        if cache.len() == KEPT {
            cache.pop_front();
        }
        cache.push_back((key, scene.clone()));
        scene
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, VecDeque<(i64, Arc<Scene>)>> {
        // A panic elsewhere cannot leave the cache inconsistent: take it as it is.
        self.cache.lock().unwrap_or_else(|e| e.into_inner())
    }
}
