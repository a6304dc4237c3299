//! The worker threads and what they share with the display thread.
//!
//! Each worker loops: lock the screen briefly to `plan` a batch of samples for the instants
//! ahead, trace them unlocked (each at the scene and camera of its own instant), lock again
//! to `accept` them. The display thread only ever takes the same short locks, so neither
//! waits for the other's work: a frame is never waited for.

use crate::clock::Clock;
use crate::pose::Pose;
use lucent::camera::Camera;
use lucent::integrator::{Integrator, RayStats};
use lucent::scene::Scene;
use lucent::schedule::frameless::{
    DisplayMode, Presenter, Sample, SampleRequest, Snapshots, trace_sample,
};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::Instant;

/// Samples planned and traced at once: enough that the two locks per batch cost nothing,
/// few enough that a batch takes a small part of a frame.
pub const BATCH: usize = 256;

/// The screen: the mode's presenter at the current render resolution.
pub struct Screen {
    /// The mode's state.
    pub presenter: Presenter,
    /// Render resolution.
    pub width: u32,
    /// Render resolution.
    pub height: u32,
    /// Counts new presenters: samples planned for an older one are dropped.
    pub generation: u64,
}

/// What the user controls.
pub struct Control {
    /// Running or paused time.
    pub clock: Clock,
    /// The user's camera, once they have moved it; until then the scene's.
    pub pose: Option<Pose>,
    /// Set to end the workers.
    pub quit: bool,
}

/// The state the display thread and the workers share.
pub struct Shared {
    /// The screen.
    pub screen: Mutex<Screen>,
    /// Clock, camera, quit.
    pub control: Mutex<Control>,
    /// Wakes paused workers.
    pub wake: Condvar,
    /// Samples traced since the start.
    pub samples: AtomicU64,
    /// Set when a worker has panicked, so the display can stop.
    pub failed: AtomicBool,
    snapshots: Snapshots,
    /// The scene's own camera, followed until the user moves theirs.
    scene_pose: Pose,
    integrator: Integrator,
    seed: u64,
}

impl Shared {
    /// The state of a viewer of `scene` from `pose`, starting on an empty screen.
    pub fn new(
        scene: Arc<Scene>,
        scene_pose: Pose,
        integrator: Integrator,
        (mode, width, height): (DisplayMode, u32, u32),
        seed: u64,
    ) -> Self {
        Self {
            screen: Mutex::new(Screen {
                presenter: Presenter::new(mode, width, height, seed),
                width,
                height,
                generation: 0,
            }),
            control: Mutex::new(Control {
                clock: Clock::start(),
                pose: None,
                quit: false,
            }),
            wake: Condvar::new(),
            samples: AtomicU64::new(0),
            failed: AtomicBool::new(false),
            // One snapshot per millisecond: finer than any refresh rate, coarse enough that
            // a batch's samples share a few.
            snapshots: Snapshots::new(scene, 1e-3),
            scene_pose,
            integrator,
            seed,
        }
    }

    /// The screen, locked.
    pub fn screen(&self) -> MutexGuard<'_, Screen> {
        self.screen.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The controls, locked.
    pub fn control(&self) -> MutexGuard<'_, Control> {
        self.control.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Starts over with a new presenter of `mode` at `width × height`.
    pub fn reset(&self, mode: DisplayMode, width: u32, height: u32) {
        let mut s = self.screen();
        let generation = s.generation + 1;
        *s = Screen {
            presenter: Presenter::new(mode, width, height, self.seed ^ generation),
            width,
            height,
            generation,
        };
    }

    /// The pose the camera has now: the user's, or the scene's at the clock's instant (so
    /// that taking over a moving camera starts where it is).
    pub fn pose(&self) -> Pose {
        let (user, now) = {
            let c = self.control();
            (c.pose, c.clock.now())
        };
        user.unwrap_or_else(|| self.scene_pose_in(&self.snapshots.at(now)))
    }

    /// The pose of the scene's own camera in `scene` (a snapshot): its eye and frame, looking
    /// at the point as far ahead as the file's look-at was.
    fn scene_pose_in(&self, scene: &Scene) -> Pose {
        let c = &scene.camera;
        let reach = (self.scene_pose.look_at - self.scene_pose.eye).length();
        Pose {
            eye: c.eye(),
            look_at: c.eye() + c.forward() * reach,
            up: c.up_dir(),
            fov_degrees: c.fov_degrees(),
            lens: c.lens(),
        }
    }
}

/// Starts `threads` workers.
pub fn spawn(shared: &Arc<Shared>, threads: usize) -> Vec<JoinHandle<()>> {
    (0..threads)
        .map(|i| {
            let shared = Arc::clone(shared);
            std::thread::Builder::new()
                .name(format!("lucent-view worker {i}"))
                .spawn(move || {
                    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                        work(&shared, i as u64)
                    }));
                    if result.is_err() {
                        shared.failed.store(true, Ordering::SeqCst);
                    }
                })
                .expect("a worker thread starts")
        })
        .collect()
}

/// Stops and joins the workers.
pub fn stop(shared: &Shared, workers: Vec<JoinHandle<()>>) {
    shared.control().quit = true;
    shared.wake.notify_all();
    for w in workers {
        let _ = w.join();
    }
}

/// One worker's loop, until quit.
fn work(shared: &Shared, worker: u64) {
    let mut requests: Vec<SampleRequest> = Vec::with_capacity(BATCH);
    let mut samples: Vec<Sample> = Vec::with_capacity(BATCH);
    let mut stats = RayStats::default();
    // How long the last batch took: the next one is planned over that much time ahead.
    let mut batch_time = 0.0;
    // A different stream of sample indices per worker; the seed keeps them apart.
    let seed = shared.seed ^ lucent::sampling::mix64(worker + 1);
    let mut index = 0u32;
    loop {
        let (now, user) = {
            let mut c = shared.control();
            while c.clock.paused() && !c.quit {
                c = shared.wake.wait(c).unwrap_or_else(|e| e.into_inner());
            }
            if c.quit {
                return;
            }
            (c.clock.now(), c.pose)
        };
        let started = Instant::now();
        let (generation, width, height) = {
            let mut s = shared.screen();
            requests.clear();
            s.presenter
                .plan(BATCH, now, now + batch_time, &mut requests);
            (s.generation, s.width, s.height)
        };
        if requests.is_empty() {
            // Double buffering has handed out its whole frame: the frame in flight finishes
            // on other threads first.
            std::thread::sleep(std::time::Duration::from_micros(200));
            continue;
        }
        let user_camera = user.and_then(|p| p.camera(width, height));
        // The snapshot and its camera, looked up again only when a request's instant moves to
        // another snapshot: a lookup per sample would share the snapshot's reference count
        // between the threads on every sample.
        let mut cached: Option<(f64, Arc<Scene>, Option<Camera>)> = None;
        samples.clear();
        for r in &requests {
            let instant = shared.snapshots.instant(r.time);
            if cached.as_ref().is_none_or(|(t, _, _)| *t != instant) {
                let scene = shared.snapshots.at(r.time);
                let camera = match user_camera {
                    Some(c) => Some(c),
                    None => shared.scene_pose_in(&scene).camera(width, height),
                };
                cached = Some((instant, scene, camera));
            }
            let Some((_, scene, Some(camera))) = &cached else {
                continue;
            };
            let color = trace_sample(
                scene,
                camera,
                &shared.integrator,
                r.pixel,
                index,
                seed,
                &mut stats,
            );
            samples.push(Sample {
                pixel: r.pixel,
                time: r.time,
                color,
            });
        }
        index = index.wrapping_add(1);
        {
            let mut s = shared.screen();
            if s.generation == generation {
                s.presenter.accept(&samples);
            }
        }
        shared
            .samples
            .fetch_add(samples.len() as u64, Ordering::Relaxed);
        batch_time = started.elapsed().as_secs_f64();
    }
}
