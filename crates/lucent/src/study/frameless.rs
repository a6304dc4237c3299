//! The frameless study: double buffering, frameless and adaptive frameless rendering under the
//! same sample rate, each compared at every display refresh with the ideal image of that
//! instant (Bishop et al. 1994; Dayal et al. 2005).
//!
//! **The clock is simulated.** Each mode gets `samples_per_second / refresh_hz` samples per
//! refresh, traced at the instants its schedule asks for (resolved to `1 / (refresh_hz ·
//! substeps)` seconds), and what it would display at each refresh is recorded. Every run starts
//! from the same complete, exact picture at `−warmup` and is measured from time 0 to
//! `duration`.
//!
//! **Measures**, per refresh at instant `t_k`:
//! - *RMSE* against the ideal image of `t_k` (every pixel traced at `t_k`, as the modes trace
//!   them), over the pixels and the three channels, each clamped to the displayable `[0, 1]`.
//! - *Stale fraction*: the share of pixels showing the scene as it was before their latest
//!   change — a pixel *changes* at refresh `i` when its ideal colour differs from the one at
//!   refresh `i − 1` by more than `threshold` in a channel; it is stale when its own sample on
//!   screen was taken before `t_{i−1}` of its latest change `i`.
//! - *Latency*: at a random instant `c` in every refresh interval the scene "changes" (it moves
//!   all the time); its first visible effect is the first refresh `t_j ≥ c` at which some pixel
//!   that changed after `c` shows a sample taken at or after `c`. Latency is `t_j − c`.
//!
//! Besides the three modes at the given rate, frameless and adaptive frameless are run at lower
//! rates (`rate_divisors`), to find the rate at which each matches double buffering's mean
//! RMSE at the full rate: Dayal et al. report adaptive frameless rendering needs about a tenth.

use crate::Rgb;
use crate::sampling::uniform;
use crate::schedule::frameless::{DisplayMode, Presenter, Sample, SampleRequest};
use rayon::prelude::*;

/// Traces pixels of a moving scene at an instant.
pub trait Tracer: Sync {
    /// The screen's size in pixels.
    fn size(&self) -> (u32, u32);
    /// The radiance of each of `pixels` (`y · width + x`) at instant `time`, into `out`.
    fn trace(&self, time: f64, pixels: &[u32], out: &mut [Rgb]);
}

/// The study's conditions.
#[derive(Clone, Debug, PartialEq)]
pub struct StudySettings {
    /// The sample budget of every mode, per second of simulated time.
    pub samples_per_second: f64,
    /// Display refreshes per second.
    pub refresh_hz: f64,
    /// Seconds measured.
    pub duration: f64,
    /// Seconds simulated before the measurement, from an exact picture; `None`: long enough
    /// for the slowest run to sample every pixel twice (at least 2 s), so that no run is
    /// measured while it still shows the first picture.
    pub warmup: Option<f64>,
    /// Instants per refresh interval that samples are resolved to.
    pub substeps: u32,
    /// The colour difference (per channel, in `[0, 1]`) at which a pixel counts as changed.
    pub threshold: f32,
    /// Lower rates (the full rate divided by these) for frameless and adaptive frameless.
    pub rate_divisors: Vec<f64>,
    /// Seed of the schedules' orders and of the latency instants.
    pub seed: u64,
    /// Keep the pictures of the refresh at this instant (the ideal one, and what each mode
    /// shows at the full rate).
    pub capture_at: Option<f64>,
}

impl Default for StudySettings {
    fn default() -> Self {
        Self {
            samples_per_second: 400_000.0,
            refresh_hz: 60.0,
            duration: 6.0,
            warmup: None,
            substeps: 8,
            threshold: 0.02,
            rate_divisors: vec![2.0, 4.0, 8.0, 16.0, 32.0],
            seed: 1,
            capture_at: None,
        }
    }
}

/// What one refresh of one run showed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RefreshRecord {
    /// The refresh's instant.
    pub time: f64,
    /// RMSE against the ideal image.
    pub rmse: f64,
    /// Share of stale pixels.
    pub stale_fraction: f64,
}

/// One mode at one sample rate.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// The display mode.
    pub mode: DisplayMode,
    /// Its sample budget per second.
    pub samples_per_second: f64,
    /// Every measured refresh.
    pub refreshes: Vec<RefreshRecord>,
    /// Latencies of the changes whose effect was seen, in seconds.
    pub latencies: Vec<f64>,
    /// Changes whose effect was never seen before the end.
    pub unseen: usize,
    /// Samples traced (warm-up included).
    pub samples: u64,
}

impl Run {
    /// Mean RMSE over the refreshes.
    pub fn mean_rmse(&self) -> f64 {
        mean(self.refreshes.iter().map(|r| r.rmse))
    }

    /// Mean stale fraction over the refreshes.
    pub fn mean_stale(&self) -> f64 {
        mean(self.refreshes.iter().map(|r| r.stale_fraction))
    }

    /// Mean latency, seconds.
    pub fn mean_latency(&self) -> f64 {
        mean(self.latencies.iter().copied())
    }

    /// The 95th percentile of latency, seconds (nearest rank).
    pub fn latency_p95(&self) -> f64 {
        let mut l = self.latencies.clone();
        if l.is_empty() {
            return f64::NAN;
        }
        l.sort_by(f64::total_cmp);
        l[((0.95 * l.len() as f64).ceil() as usize).clamp(1, l.len()) - 1]
    }
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    if n == 0 { f64::NAN } else { sum / n as f64 }
}

/// The study's results.
#[derive(Clone, Debug, PartialEq)]
pub struct StudyReport {
    /// The conditions.
    pub settings: StudySettings,
    /// Screen size.
    pub width: u32,
    /// Screen size.
    pub height: u32,
    /// Every run: the three modes at the full rate first, then the lower rates.
    pub runs: Vec<Run>,
    /// The pictures of [`StudySettings::capture_at`]: its instant, the ideal image, and what
    /// each mode showed at the full rate.
    pub capture: Option<Capture>,
}

/// The pictures of one refresh.
#[derive(Clone, Debug, PartialEq)]
pub struct Capture {
    /// The refresh's instant.
    pub time: f64,
    /// The ideal image.
    pub ideal: Vec<Rgb>,
    /// What each mode showed, at the full rate.
    pub shown: Vec<(DisplayMode, Vec<Rgb>)>,
}

impl StudyReport {
    /// The run of `mode` at the full rate.
    pub fn main_run(&self, mode: DisplayMode) -> Option<&Run> {
        self.runs
            .iter()
            .find(|r| r.mode == mode && r.samples_per_second == self.settings.samples_per_second)
    }

    /// The lowest sample rate at which `mode` matches double buffering's mean RMSE at the full
    /// rate, interpolated between the measured rates (log rate against log RMSE); `None` when
    /// it does not match it even at the full rate. When it still matches at the lowest rate
    /// measured, that rate is returned with `true` (a bound: the true rate is lower).
    pub fn matching_rate(&self, mode: DisplayMode) -> Option<(f64, bool)> {
        let target = self.main_run(DisplayMode::DoubleBuffer)?.mean_rmse();
        let mut runs: Vec<(f64, f64)> = self
            .runs
            .iter()
            .filter(|r| r.mode == mode)
            .map(|r| (r.samples_per_second, r.mean_rmse()))
            .collect();
        runs.sort_by(|a, b| b.0.total_cmp(&a.0)); // highest rate first
        let (first_rate, first_rmse) = *runs.first()?;
        if first_rmse > target {
            return None;
        }
        for pair in runs.windows(2) {
            let ((r_hi, e_hi), (r_lo, e_lo)) = (pair[0], pair[1]);
            if e_lo > target {
                // Between r_lo and r_hi: log-linear interpolation.
                let f = (target.ln() - e_hi.ln()) / (e_lo.ln() - e_hi.ln());
                return Some(((r_hi.ln() + f * (r_lo.ln() - r_hi.ln())).exp(), false));
            }
        }
        let (last_rate, _) = *runs.last()?;
        Some((last_rate.min(first_rate), true))
    }
}

/// A run in progress.
struct Live {
    presenter: Presenter,
    rate: f64,
    /// Samples owed: the fractional budget carried between refreshes.
    owed: f64,
    run: Run,
    /// Change instants not yet seen.
    pending: Vec<f64>,
}

/// Runs the study on `tracer`'s scene; `progress(done, total)` is called after every refresh
/// and returns whether to go on. Stopped early, the report holds the refreshes measured so
/// far (every run the same ones), and its `settings.duration` is the span they cover.
pub fn run_study(
    tracer: &dyn Tracer,
    settings: &StudySettings,
    mut progress: impl FnMut(usize, usize) -> bool,
) -> StudyReport {
    let (width, height) = tracer.size();
    let n = (width as usize) * (height as usize);
    let all: Vec<u32> = (0..n as u32).collect();
    let ideal_at = |t: f64| {
        let mut image = vec![Rgb::BLACK; n];
        tracer.trace(t, &all, &mut image);
        image
    };
    let full = settings.samples_per_second;
    let mut rates: Vec<(DisplayMode, f64)> = DisplayMode::ALL.iter().map(|&m| (m, full)).collect();
    for &d in &settings.rate_divisors {
        if d > 1.0 {
            rates.push((DisplayMode::Frameless, full / d));
            rates.push((DisplayMode::Adaptive, full / d));
        }
    }
    let dt = 1.0 / settings.refresh_hz;
    let step = dt / f64::from(settings.substeps.max(1));
    let pixels = n as f64;
    let slowest = rates.iter().map(|r| r.1).fold(f64::INFINITY, f64::min);
    let warmup = settings
        .warmup
        .unwrap_or_else(|| (2.0 * pixels / slowest).max(2.0));
    let start = -warmup;
    let primer = ideal_at(start);
    let mut live: Vec<Live> = rates
        .iter()
        .map(|&(mode, rate)| {
            let mut presenter = Presenter::new(mode, width, height, settings.seed);
            presenter.prime(&primer, start);
            Live {
                presenter,
                rate,
                owed: 0.0,
                run: Run {
                    mode,
                    samples_per_second: rate,
                    refreshes: Vec::new(),
                    latencies: Vec::new(),
                    unseen: 0,
                    samples: 0,
                },
                pending: Vec::new(),
            }
        })
        .collect();

    let warm = (warmup * settings.refresh_hz).round() as usize;
    let measured = (settings.duration * settings.refresh_hz).round() as usize;
    let total = warm + measured;
    // Change tracking over the ideal images (from the first measured refresh on).
    let mut previous_ideal: Option<Vec<Rgb>> = None;
    let mut last_change = vec![f64::NEG_INFINITY; n]; // t_i of the latest change
    let mut before_change = vec![f64::NEG_INFINITY; n]; // t_{i-1} of it
    let mut capture = None;
    let mut done = 0;
    for k in 1..=total {
        let (t_prev, t_now) = (start + (k - 1) as f64 * dt, start + k as f64 * dt);
        for l in &mut live {
            advance(l, tracer, t_prev, t_now, step);
        }
        let measuring = k > warm;
        if k == warm || (k == 1 && warm == 0) {
            previous_ideal = Some(ideal_at(if warm == 0 { start } else { t_now }));
        }
        if measuring {
            let ideal = ideal_at(t_now);
            if let Some(prev) = &previous_ideal {
                for p in 0..n {
                    if changed(ideal[p], prev[p], settings.threshold) {
                        last_change[p] = t_now;
                        before_change[p] = t_prev;
                    }
                }
            }
            let c = t_prev + dt * f64::from(uniform(settings.seed, k as u64, 0, 7));
            for l in &mut live {
                l.pending.push(c);
                measure(l, &ideal, &last_change, &before_change, t_now);
            }
            if settings
                .capture_at
                .is_some_and(|at| at > t_prev && at <= t_now)
            {
                let shown = live
                    .iter_mut()
                    .filter(|l| l.rate == full)
                    .map(|l| (l.run.mode, l.presenter.present(t_now).to_vec()))
                    .collect();
                capture = Some(Capture {
                    time: t_now,
                    ideal: ideal.clone(),
                    shown,
                });
            }
            previous_ideal = Some(ideal);
        }
        done = k;
        if !progress(k, total) {
            break;
        }
    }
    let runs = live
        .into_iter()
        .map(|mut l| {
            l.run.unseen = l.pending.len();
            l.run
        })
        .collect();
    StudyReport {
        settings: StudySettings {
            warmup: Some(warmup),
            duration: done.saturating_sub(warm) as f64 / settings.refresh_hz,
            ..settings.clone()
        },
        width,
        height,
        runs,
        capture,
    }
}

/// Whether a pixel's colour changed from `b` to `a`: by more than `threshold` in a channel,
/// each clamped to `[0, 1]`.
fn changed(a: Rgb, b: Rgb, threshold: f32) -> bool {
    let d = |x: f32, y: f32| (x.clamp(0.0, 1.0) - y.clamp(0.0, 1.0)).abs() > threshold;
    d(a.r, b.r) || d(a.g, b.g) || d(a.b, b.b)
}

/// Spends one refresh interval's budget of `l`: plan, trace at the resolved instants, accept.
fn advance(l: &mut Live, tracer: &dyn Tracer, t0: f64, t1: f64, step: f64) {
    l.owed += l.rate * (t1 - t0);
    let budget = l.owed.floor() as usize;
    l.owed -= budget as f64;
    let mut done = 0;
    let mut requests: Vec<SampleRequest> = Vec::new();
    while done < budget {
        let from = t0 + (t1 - t0) * done as f64 / budget as f64;
        requests.clear();
        l.presenter.plan(budget - done, from, t1, &mut requests);
        if requests.is_empty() {
            break;
        }
        let samples = trace_requests(tracer, &requests, step);
        l.presenter.accept(&samples);
        done += requests.len();
    }
    l.run.samples += done as u64;
}

/// Traces requests grouped by their instant resolved down to `step`.
fn trace_requests(tracer: &dyn Tracer, requests: &[SampleRequest], step: f64) -> Vec<Sample> {
    let instant = |t: f64| (t / step).floor() * step;
    let mut order: Vec<usize> = (0..requests.len()).collect();
    order.sort_by(|&a, &b| instant(requests[a].time).total_cmp(&instant(requests[b].time)));
    let mut samples = vec![
        Sample {
            pixel: 0,
            time: 0.0,
            color: Rgb::BLACK
        };
        requests.len()
    ];
    let mut i = 0;
    while i < order.len() {
        let t = instant(requests[order[i]].time);
        let mut j = i;
        while j < order.len() && instant(requests[order[j]].time) == t {
            j += 1;
        }
        let pixels: Vec<u32> = order[i..j].iter().map(|&r| requests[r].pixel).collect();
        let mut colors = vec![Rgb::BLACK; pixels.len()];
        tracer.trace(t, &pixels, &mut colors);
        for (&r, color) in order[i..j].iter().zip(colors) {
            samples[r] = Sample {
                pixel: requests[r].pixel,
                time: t,
                color,
            };
        }
        i = j;
    }
    samples
}

/// Records refresh `t_now` of `l` against `ideal`.
fn measure(l: &mut Live, ideal: &[Rgb], last_change: &[f64], before_change: &[f64], t_now: f64) {
    let shown = l.presenter.present(t_now).to_vec();
    let times = l.presenter.shown_times();
    let clamp = |v: f32| f64::from(v.clamp(0.0, 1.0));
    let (sums, stale, visible) = shown
        .par_iter()
        .zip(ideal)
        .zip(times)
        .zip(last_change.par_iter().zip(before_change))
        .map(|(((s, i), &shown_at), (&changed_at, &began))| {
            let e = (clamp(s.r) - clamp(i.r)).powi(2)
                + (clamp(s.g) - clamp(i.g)).powi(2)
                + (clamp(s.b) - clamp(i.b)).powi(2);
            let stale = changed_at.is_finite() && shown_at < began;
            // The latest change instant this pixel's sample could show.
            let visible = if changed_at.is_finite() {
                shown_at.min(changed_at)
            } else {
                f64::NEG_INFINITY
            };
            (e, stale as usize, visible)
        })
        .reduce(
            || (0.0, 0, f64::NEG_INFINITY),
            |a, b| (a.0 + b.0, a.1 + b.1, a.2.max(b.2)),
        );
    let n = ideal.len().max(1) as f64;
    l.run.refreshes.push(RefreshRecord {
        time: t_now,
        rmse: (sums / (3.0 * n)).sqrt(),
        stale_fraction: stale as f64 / n,
    });
    l.pending.retain(|&c| {
        let seen = c <= visible;
        if seen {
            l.run.latencies.push(t_now - c);
        }
        !seen
    });
}
