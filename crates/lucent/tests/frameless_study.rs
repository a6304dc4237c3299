//! The frameless study on an analytic moving picture: the claims of Bishop et al. (1994) and
//! Dayal et al. (2005) as the study measures them, on a scene whose every pixel is known.

use lucent::Rgb;
use lucent::schedule::frameless::DisplayMode;
use lucent::study::frameless::{StudySettings, Tracer, run_study};

/// A 64×48 screen: a still checkerboard of 8-pixel squares, and a white disc of radius 5
/// crossing it and back every 2 seconds, while the whole picture pans slowly (a moving camera).
struct MovingDisc;

impl Tracer for MovingDisc {
    fn size(&self) -> (u32, u32) {
        (64, 48)
    }

    fn trace(&self, time: f64, pixels: &[u32], out: &mut [Rgb]) {
        let phase = (time * std::f64::consts::PI).sin();
        let (cx, cy) = (32.0 + 24.0 * phase, 24.0);
        let pan = 2.0 * time; // pixels per second
        for (&p, o) in pixels.iter().zip(out) {
            let (x, y) = (f64::from(p % 64) + 0.5, f64::from(p / 64) + 0.5);
            *o = if (x - cx).powi(2) + (y - cy).powi(2) < 25.0 {
                Rgb::WHITE
            } else {
                let check = (((x + pan) / 8.0).floor() + (y / 8.0).floor()) as i64 % 2 == 0;
                Rgb::gray(if check { 0.6 } else { 0.2 })
            };
        }
    }
}

fn settings() -> StudySettings {
    StudySettings {
        // One double-buffered frame every 0.1 s.
        samples_per_second: 64.0 * 48.0 * 10.0,
        duration: 4.0,
        warmup: Some(1.0),
        rate_divisors: vec![2.0, 4.0, 8.0],
        ..StudySettings::default()
    }
}

#[test]
fn frameless_beats_double_buffering_and_adaptive_beats_frameless() {
    let report = run_study(&MovingDisc, &settings(), |_, _| true);
    let run = |m| report.main_run(m).unwrap();
    let (db, fl, ad) = (
        run(DisplayMode::DoubleBuffer),
        run(DisplayMode::Frameless),
        run(DisplayMode::Adaptive),
    );
    for r in [db, fl, ad] {
        eprintln!(
            "{:>13}: rmse {:.4}  stale {:.3}  latency {:.3} s (p95 {:.3}), {} unseen",
            r.mode.name(),
            r.mean_rmse(),
            r.mean_stale(),
            r.mean_latency(),
            r.latency_p95(),
            r.unseen
        );
        assert_eq!(r.refreshes.len(), 240);
        let expected = settings().samples_per_second * 5.0;
        assert!(
            (r.samples as f64 - expected).abs() <= 1.0,
            "{} samples",
            r.samples
        );
    }
    for r in &report.runs {
        eprintln!(
            "{:>13} at {:>8.0}/s: rmse {:.4}",
            r.mode.name(),
            r.samples_per_second,
            r.mean_rmse()
        );
    }
    let refresh = 1.0 / 60.0;
    let frame = 0.1;
    assert!(fl.mean_rmse() < db.mean_rmse());
    assert!(ad.mean_rmse() < fl.mean_rmse());
    // With a few hundred samples a refresh and a few dozen changing pixels, a change late in
    // a refresh interval is often first sampled in the next one: about a refresh on average
    // here (the study's scene, with thousands of samples a refresh, stays under one).
    assert!(
        fl.mean_latency() <= 1.5 * refresh,
        "frameless latency {}",
        fl.mean_latency()
    );
    assert!(
        db.mean_latency() >= frame,
        "double-buffer latency {}",
        db.mean_latency()
    );
    assert!(db.mean_stale() > fl.mean_stale());
    let (rate, bound) = report.matching_rate(DisplayMode::Adaptive).unwrap();
    eprintln!("adaptive matches double buffering at {rate:.0} samples/s (bound: {bound})");
    assert!(rate < settings().samples_per_second);
}

#[test]
fn a_study_stopped_early_reports_the_refreshes_it_measured() {
    let s = settings();
    let warm = (s.warmup.unwrap() * s.refresh_hz).round() as usize;
    // Stop ten refreshes into the measured span.
    let report = run_study(&MovingDisc, &s, |done, _| done < warm + 10);
    assert_eq!(report.runs.len(), 3 + 2 * s.rate_divisors.len());
    for run in &report.runs {
        assert_eq!(
            run.refreshes.len(),
            10,
            "{} at {}",
            run.mode.name(),
            run.samples_per_second
        );
        assert!(run.mean_rmse().is_finite());
    }
    assert!((report.settings.duration - 10.0 / s.refresh_hz).abs() < 1e-12);
    // Stopped in the warm-up: nothing measured, and the report says so.
    let report = run_study(&MovingDisc, &s, |done, _| done < 3);
    assert!(report.runs.iter().all(|r| r.refreshes.is_empty()));
    assert_eq!(report.settings.duration, 0.0);
}
