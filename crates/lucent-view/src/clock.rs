//! The viewer's clock: seconds since the start, standing still while paused, so that a
//! paused scene's motion and the age of its pixels stop too.

use std::time::{Duration, Instant};

/// A pausable clock.
#[derive(Clone, Copy, Debug)]
pub struct Clock {
    started: Instant,
    /// When the current pause began.
    paused_at: Option<Instant>,
    /// Time spent in earlier pauses.
    paused_for: Duration,
}

impl Clock {
    /// A running clock at 0.
    pub fn start() -> Self {
        Self {
            started: Instant::now(),
            paused_at: None,
            paused_for: Duration::ZERO,
        }
    }

    /// Seconds of running time.
    pub fn now(&self) -> f64 {
        self.at(Instant::now())
    }

    fn at(&self, instant: Instant) -> f64 {
        let end = self.paused_at.unwrap_or(instant);
        end.saturating_duration_since(self.started)
            .saturating_sub(self.paused_for)
            .as_secs_f64()
    }

    /// True while paused.
    pub fn paused(&self) -> bool {
        self.paused_at.is_some()
    }

    /// Stops the clock, or starts it again.
    pub fn toggle(&mut self) {
        match self.paused_at.take() {
            Some(at) => self.paused_for += at.elapsed(),
            None => self.paused_at = Some(Instant::now()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_paused_clock_stands_still_and_resumes_where_it_stopped() {
        let mut c = Clock::start();
        c.toggle();
        let t = c.now();
        std::thread::sleep(Duration::from_millis(20));
        assert_eq!(c.now(), t);
        c.toggle();
        assert!(c.now() >= t && c.now() < t + 0.015, "{} vs {t}", c.now());
    }
}
