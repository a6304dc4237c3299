//! The display thread: the window, its events, and a redraw at the refresh rate that shows
//! whatever the presenter has (it never waits for the workers).

use crate::display::{blit, render_size};
use crate::input::Input;
use crate::pose::Pose;
use crate::readout::{self, Rate};
use crate::workers::{self, Shared};
use crate::{DisplayMode, Options, Summary, ViewError};
use lucent::Rgb;
use lucent::integrator::Integrator;
use lucent::scene::Scene;
use lucent::schedule::frameless::Presenter;
use std::num::NonZeroU32;
use std::rc::Rc;
use std::sync::Arc;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::WindowEvent;
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::window::{Window, WindowId};

type Surface = softbuffer::Surface<Rc<Window>, Rc<Window>>;

/// Runs the viewer to its end; see [`crate::run`].
pub fn run(
    scene: Scene,
    pose: Pose,
    integrator: Integrator,
    options: &Options,
) -> Result<Summary, ViewError> {
    let event_loop = EventLoop::new().map_err(|e| ViewError::Window(e.to_string()))?;
    let threads = match options.threads {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        n => n,
    };
    let (w, h) = options.size;
    let (rw, rh) = render_size(w, h, options.scale);
    let shared = Arc::new(Shared::new(
        Arc::new(scene),
        pose,
        integrator,
        (options.mode, rw, rh),
        options.seed,
    ));
    let workers = workers::spawn(&shared, threads);
    let mut app = App::new(Arc::clone(&shared), options.clone());
    let result = event_loop.run_app(&mut app);
    // However the loop ended, the workers end with it.
    workers::stop(&shared, workers);
    result.map_err(|e| ViewError::Window(e.to_string()))?;
    if let Some(e) = app.error.take() {
        return Err(e);
    }
    let screen = shared.screen();
    Ok(Summary {
        mode: screen.presenter.mode(),
        resolution: (screen.width, screen.height),
        threads,
        samples: shared.samples.load(Ordering::Relaxed),
        seconds: shared.control().clock.now(),
    })
}

/// The window and what the display thread keeps between events.
struct App {
    shared: Arc<Shared>,
    options: Options,
    window: Option<(Rc<Window>, Surface)>,
    /// A copy of the presented image, so that tone mapping does not hold the lock.
    image: Vec<Rgb>,
    input: Input,
    period: Duration,
    next_frame: Instant,
    next_title: Instant,
    rate: Rate,
    started: Instant,
    error: Option<ViewError>,
}

impl App {
    fn new(shared: Arc<Shared>, options: Options) -> Self {
        let now = Instant::now();
        Self {
            shared,
            period: Duration::from_secs_f64(1.0 / options.refresh.max(1.0)),
            options,
            window: None,
            image: Vec::new(),
            input: Input::default(),
            next_frame: now,
            next_title: now,
            rate: Rate::new(0),
            started: now,
            error: None,
        }
    }

    fn open(&mut self, event_loop: &ActiveEventLoop) -> Result<(), String> {
        let (w, h) = self.options.size;
        let attributes = Window::default_attributes()
            .with_title(format!("lucent view — {}", self.options.name))
            .with_inner_size(PhysicalSize::new(w, h));
        let window = Rc::new(
            event_loop
                .create_window(attributes)
                .map_err(|e| e.to_string())?,
        );
        let context = softbuffer::Context::new(Rc::clone(&window)).map_err(|e| e.to_string())?;
        let surface = Surface::new(&context, Rc::clone(&window)).map_err(|e| e.to_string())?;
        self.window = Some((window, surface));
        Ok(())
    }

    fn mode(&self) -> DisplayMode {
        self.shared.screen().presenter.mode()
    }

    /// Shows the presenter's picture at the clock's now.
    fn draw(&mut self) -> Result<(), String> {
        let Some((window, surface)) = &mut self.window else {
            return Ok(());
        };
        let size = window.inner_size();
        let (Some(w), Some(h)) = (NonZeroU32::new(size.width), NonZeroU32::new(size.height)) else {
            return Ok(());
        };
        let (rw, rh) = render_size(size.width, size.height, self.options.scale);
        let (now, paused) = {
            let c = self.shared.control();
            (c.clock.now(), c.clock.paused())
        };
        let (mode, age, image_size) = {
            let mut s = self.shared.screen();
            if (s.width, s.height) != (rw, rh) {
                // A new size is a new screen; the workers' batches for the old one are dropped.
                let mode = s.presenter.mode();
                drop(s);
                self.shared.reset(mode, rw, rh);
                s = self.shared.screen();
            }
            let info = (
                s.presenter.mode(),
                now - s.presenter.oldest_shown(),
                (s.width, s.height),
            );
            if let Presenter::Adaptive(_) = s.presenter {
                // Its reconstruction filters every pixel: done on a copy, outside the lock the
                // workers take to plan and accept.
                let mut copy = s.presenter.clone();
                drop(s);
                self.image.clear();
                self.image.extend_from_slice(copy.present(now));
            } else {
                let shown = s.presenter.present(now);
                self.image.clear();
                self.image.extend_from_slice(shown);
            }
            info
        };
        surface.resize(w, h).map_err(|e| e.to_string())?;
        let mut buffer = surface.buffer_mut().map_err(|e| e.to_string())?;
        blit(
            &self.image,
            image_size,
            &mut buffer,
            (size.width, size.height),
        );
        buffer.present().map_err(|e| e.to_string())?;
        if Instant::now() >= self.next_title {
            self.next_title = Instant::now() + readout::EVERY;
            let rate = self
                .rate
                .update(self.shared.samples.load(Ordering::Relaxed));
            let rate = if paused { 0.0 } else { rate };
            window.set_title(&readout::title(&self.options.name, mode, rate, age, paused));
        }
        Ok(())
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: ViewError) {
        self.error.get_or_insert(e);
        event_loop.exit();
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.window.is_none()
            && let Err(e) = self.open(event_loop)
        {
            self.fail(event_loop, ViewError::Window(e));
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::RedrawRequested => {
                if let Err(e) = self.draw() {
                    self.fail(event_loop, ViewError::Window(e));
                }
            }
            event => {
                let mode = self.mode();
                if self.input.event(&event, &self.shared, mode).quit {
                    event_loop.exit();
                }
            }
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if self.shared.failed.load(Ordering::SeqCst) {
            return self.fail(event_loop, ViewError::Worker);
        }
        let now = Instant::now();
        if self
            .options
            .exit_after
            .is_some_and(|s| now.duration_since(self.started).as_secs_f64() >= s)
        {
            return event_loop.exit();
        }
        if now >= self.next_frame {
            self.input.hold(&self.shared);
            if let Some((window, _)) = &self.window {
                window.request_redraw();
            }
            // A late frame is not made up for: the next one is a period from now.
            self.next_frame = (self.next_frame + self.period).max(now);
        }
        event_loop.set_control_flow(ControlFlow::WaitUntil(self.next_frame));
    }
}
