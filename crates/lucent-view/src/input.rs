//! Mouse and keys: what each does to the camera, the clock and the mode.
//!
//! Moves are made on the shared pose at once, so the very next batch of samples sees them;
//! held keys move the camera by their speed times the time since the last frame.

use crate::DisplayMode;
use crate::pose::Pose;
use crate::workers::Shared;
use std::collections::HashSet;
use std::time::Instant;
use winit::dpi::PhysicalPosition;
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::keyboard::{KeyCode, PhysicalKey};

/// Radians of orbit per pixel dragged.
const ORBIT_PER_PIXEL: f32 = 0.006;
/// Share of the distance dollied per pixel dragged.
const DOLLY_PER_PIXEL: f32 = 0.005;
/// Share of the distance dollied per wheel notch.
const DOLLY_PER_NOTCH: f32 = 0.1;
/// Flying speed, in distances (eye to look-at) per second.
const FLY_SPEED: f32 = 0.5;
/// Turning speed of the arrow keys, radians per second.
const TURN_SPEED: f32 = 0.8;

/// What an event asks of the viewer beyond the camera.
#[derive(Clone, Copy, Debug, Default)]
pub struct Outcome {
    /// Close the window.
    pub quit: bool,
}

/// The state of the mouse and the held keys.
#[derive(Debug, Default)]
pub struct Input {
    held: HashSet<KeyCode>,
    cursor: Option<PhysicalPosition<f64>>,
    left: bool,
    right: bool,
    last_hold: Option<Instant>,
}

impl Input {
    /// Handles one window event.
    pub fn event(&mut self, event: &WindowEvent, shared: &Shared, mode: DisplayMode) -> Outcome {
        match event {
            WindowEvent::KeyboardInput {
                event,
                is_synthetic,
                ..
            } => {
                let PhysicalKey::Code(code) = event.physical_key else {
                    return Outcome::default();
                };
                if event.state == ElementState::Released {
                    self.held.remove(&code);
                    return Outcome::default();
                }
                // A key already down when the window gets the focus arrives as a synthetic
                // press: it was not pressed for this window.
                if event.repeat || *is_synthetic {
                    return Outcome::default();
                }
                return self.press(code, shared, mode);
            }
            WindowEvent::Focused(false) => {
                self.held.clear();
                self.left = false;
                self.right = false;
            }
            WindowEvent::MouseInput { state, button, .. } => {
                let down = *state == ElementState::Pressed;
                match button {
                    MouseButton::Left => self.left = down,
                    MouseButton::Right => self.right = down,
                    _ => {}
                }
            }
            WindowEvent::CursorMoved { position, .. } => {
                if let Some(last) = self.cursor.replace(*position) {
                    let (dx, dy) = ((position.x - last.x) as f32, (position.y - last.y) as f32);
                    if self.left {
                        // Grab the world: dragging right turns it right, the eye left.
                        move_camera(shared, |p| {
                            p.orbit(-dx * ORBIT_PER_PIXEL, dy * ORBIT_PER_PIXEL)
                        });
                    } else if self.right {
                        move_camera(shared, |p| p.dolly(-dy * DOLLY_PER_PIXEL));
                    }
                }
            }
            WindowEvent::CursorLeft { .. } => self.cursor = None,
            WindowEvent::MouseWheel { delta, .. } => {
                let notches = match delta {
                    MouseScrollDelta::LineDelta(_, y) => *y,
                    // Touchpads scroll in pixels; a notch is about 40 of them.
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                move_camera(shared, |p| p.dolly(notches * DOLLY_PER_NOTCH));
            }
            _ => {}
        }
        Outcome::default()
    }

    fn press(&mut self, code: KeyCode, shared: &Shared, mode: DisplayMode) -> Outcome {
        match code {
            KeyCode::Escape => return Outcome { quit: true },
            KeyCode::Space => {
                shared.control().clock.toggle();
                shared.wake.notify_all();
            }
            KeyCode::KeyM => {
                let next = mode.next();
                let (w, h) = {
                    let s = shared.screen();
                    (s.width, s.height)
                };
                shared.reset(next, w, h);
            }
            KeyCode::KeyR => shared.control().pose = None,
            _ => {
                self.held.insert(code);
            }
        }
        Outcome::default()
    }

    /// Moves the camera by the keys held since the last call (once a frame).
    pub fn hold(&mut self, shared: &Shared) {
        let now = Instant::now();
        // At most a tenth of a second at once: a stalled frame does not throw the camera.
        let dt = self
            .last_hold
            .replace(now)
            .map_or(0.0, |t| now.duration_since(t).as_secs_f32().min(0.1));
        if self.held.is_empty() || dt == 0.0 {
            return;
        }
        let axis = |plus: KeyCode, minus: KeyCode| {
            f32::from(u8::from(self.held.contains(&plus)))
                - f32::from(u8::from(self.held.contains(&minus)))
        };
        let right = axis(KeyCode::KeyD, KeyCode::KeyA);
        let up = axis(KeyCode::KeyE, KeyCode::KeyQ);
        let forward = axis(KeyCode::KeyW, KeyCode::KeyS);
        let yaw = axis(KeyCode::ArrowLeft, KeyCode::ArrowRight);
        let pitch = axis(KeyCode::ArrowUp, KeyCode::ArrowDown);
        if [right, up, forward, yaw, pitch].iter().all(|&v| v == 0.0) {
            return;
        }
        let (fly, turn) = (FLY_SPEED * dt, TURN_SPEED * dt);
        move_camera(shared, |p| {
            p.fly(right * fly, up * fly, forward * fly);
            p.turn(yaw * turn, pitch * turn);
        });
    }
}

/// Applies `f` to the user's camera, which starts as the one on screen.
fn move_camera(shared: &Shared, f: impl FnOnce(&mut Pose)) {
    let mut pose = shared.pose();
    f(&mut pose);
    shared.control().pose = Some(pose);
}
