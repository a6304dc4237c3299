//! TEMPORARY: `lucent::schedule::frameless::Snapshots` waits in the library for scene motion
//! (`Scene::at_time`); until it is enabled there, every instant shows the one still scene.
//! Same signatures, deleted when the library's is public.

use lucent::scene::Scene;
use std::sync::Arc;

/// The scene at an instant: here always the same.
pub struct Snapshots(Arc<Scene>);

impl Snapshots {
    /// Snapshots of `scene` every `step` seconds.
    pub fn new(scene: Arc<Scene>, _step: f64) -> Self {
        Self(scene)
    }

    /// The instant that samples at `t` are traced at (every instant is the same here).
    pub fn instant(&self, _t: f64) -> f64 {
        0.0
    }

    /// The scene at `t`.
    pub fn at(&self, _t: f64) -> Arc<Scene> {
        Arc::clone(&self.0)
    }
}
