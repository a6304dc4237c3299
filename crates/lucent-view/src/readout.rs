//! The title bar's readout: the mode, samples per second, the age of the oldest pixel on
//! screen, and whether the viewer is paused.

use crate::DisplayMode;
use std::time::{Duration, Instant};

/// How often the readout changes: often enough to follow, seldom enough to read.
pub const EVERY: Duration = Duration::from_millis(250);

/// Samples per second over the last readout period.
pub struct Rate {
    at: Instant,
    samples: u64,
    per_second: f64,
}

impl Rate {
    /// A rate counting from `samples` now.
    pub fn new(samples: u64) -> Self {
        Self {
            at: Instant::now(),
            samples,
            per_second: 0.0,
        }
    }

    /// Takes the sample count at the end of a period; returns the rate over it.
    pub fn update(&mut self, samples: u64) -> f64 {
        let now = Instant::now();
        let dt = now.duration_since(self.at).as_secs_f64();
        if dt > 0.0 {
            self.per_second = samples.saturating_sub(self.samples) as f64 / dt;
        }
        self.at = now;
        self.samples = samples;
        self.per_second
    }
}

/// The title: `lucent view — frameless — 1.23 M samples/s — oldest 0.41 s [paused]`.
/// `age` is `now − oldest_shown`: infinite while some pixel has never been sampled.
pub fn title(name: &str, mode: DisplayMode, per_second: f64, age: f64, paused: bool) -> String {
    let age = if age.is_finite() {
        format!("oldest pixel {age:.2} s")
    } else {
        "filling the screen".to_string()
    };
    format!(
        "lucent view — {name} — {} — {} samples/s — {age}{}",
        mode.name(),
        si(per_second),
        if paused { " — paused" } else { "" }
    )
}

/// `1234567.0` as `1.23 M`.
fn si(v: f64) -> String {
    if v >= 1e6 {
        format!("{:.2} M", v / 1e6)
    } else if v >= 1e3 {
        format!("{:.1} k", v / 1e3)
    } else {
        format!("{v:.0}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn titles() {
        assert_eq!(
            title(
                "whitted.toml",
                DisplayMode::Frameless,
                1.234e6,
                0.414,
                false
            ),
            "lucent view — whitted.toml — frameless — 1.23 M samples/s — oldest pixel 0.41 s"
        );
        assert_eq!(
            title("x", DisplayMode::Frameless, 950.0, f64::INFINITY, true),
            "lucent view — x — frameless — 950 samples/s — filling the screen — paused"
        );
    }
}
