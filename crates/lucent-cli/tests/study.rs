//! `lucent study frameless` on the built-in moving scene: the claims of the frameless papers
//! as the issue states them, at a quarter of the default resolution (the sample rate scaled with
//! it, so a double-buffered frame still takes 192 ms).

mod common;

#[cfg(unix)]
use common::signal_after;
use common::{assert_success, lucent};

/// The summary row of `mode`: mean RMSE, stale %, mean and p95 latency in ms.
fn row(stdout: &str, mode: &str) -> [f64; 4] {
    let line = stdout
        .lines()
        .find(|l| l.split_whitespace().next() == Some(mode))
        .unwrap_or_else(|| panic!("no row for {mode} in\n{stdout}"));
    let v: Vec<f64> = line
        .split_whitespace()
        .skip(1)
        .take(4)
        .map(|s| s.trim_end_matches('%').parse().unwrap())
        .collect();
    [v[0], v[1], v[2], v[3]]
}

#[test]
fn frameless_and_adaptive_frameless_beat_double_buffering_on_the_moving_scene() {
    let dir = tempfile::tempdir().unwrap();
    let (csv, svg, frames) = (
        dir.path().join("s.csv"),
        dir.path().join("s.svg"),
        dir.path().join("f"),
    );
    let out = lucent()
        .args(["study", "frameless", "--width", "160", "--height", "120"])
        .args([
            "--samples-per-second",
            "100000",
            "--duration",
            "2",
            "--rate-divisors",
            "2,4,8",
        ])
        .arg("--csv")
        .arg(&csv)
        .arg("--plot")
        .arg(&svg)
        .args(["--frames-at", "1"])
        .arg("--frames-dir")
        .arg(&frames)
        .output()
        .unwrap();
    assert_success(&out);
    let stdout = String::from_utf8_lossy(&out.stdout);
    eprintln!("{stdout}");
    let [db_rmse, db_stale, db_latency, _] = row(&stdout, "double-buffer");
    let [fl_rmse, fl_stale, fl_latency, _] = row(&stdout, "frameless");
    let [ad_rmse, _, ad_latency, _] = row(&stdout, "adaptive");
    let (refresh_ms, frame_ms) = (1000.0 / 60.0, 192.0);
    assert!(
        fl_rmse < db_rmse,
        "frameless {fl_rmse} vs double buffering {db_rmse}"
    );
    assert!(
        ad_rmse < fl_rmse,
        "adaptive {ad_rmse} vs frameless {fl_rmse}"
    );
    assert!(fl_latency <= refresh_ms && ad_latency <= refresh_ms);
    assert!(
        db_latency >= frame_ms,
        "double buffering's latency {db_latency} ms"
    );
    assert!(fl_stale < db_stale);
    // "adaptive matches double buffering's error at R samples/s: X× fewer samples"
    let ratio: f64 = stdout
        .lines()
        .find(|l| l.starts_with("adaptive matches") || l.starts_with("adaptive still beats"))
        .and_then(|l| {
            l.rsplit(": ")
                .next()?
                .split('×')
                .next()?
                .trim_start_matches("at least ")
                .parse()
                .ok()
        })
        .unwrap_or_else(|| panic!("no matching rate in\n{stdout}"));
    assert!(
        ratio >= 5.0,
        "adaptive frameless needs {ratio}× fewer samples (target 5×)"
    );

    let table = std::fs::read_to_string(&csv).unwrap();
    let mut lines = table.lines();
    assert_eq!(
        lines.next(),
        Some("mode,samples_per_second,time_s,rmse,stale_fraction")
    );
    let rows: Vec<&str> = lines.collect();
    // 3 modes at the full rate and 2 at each of 3 lower rates, 120 refreshes each.
    assert_eq!(rows.len(), 9 * 120);
    for mode in ["double-buffer", "frameless", "adaptive"] {
        assert!(
            rows.iter()
                .any(|r| r.starts_with(&format!("{mode},100000,")))
        );
    }
    let plot = std::fs::read_to_string(&svg).unwrap();
    assert!(plot.starts_with("<svg") && plot.matches("<polyline").count() >= 6);
    for name in ["ideal", "double-buffer", "frameless", "adaptive"] {
        assert!(frames.join(format!("{name}.png")).exists());
    }
}

#[test]
fn the_study_refuses_a_stochastic_integrator() {
    let out = lucent()
        .args([
            "study",
            "frameless",
            "--integrator",
            "path",
            "--duration",
            "1",
        ])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("deterministic integrator"), "{err}");
}

/// Ctrl-C (SIGINT) stops the study after the refresh under way: it writes the table, the CSV
/// and the plot of what was measured, and exits 130.
#[cfg(unix)]
#[test]
fn ctrl_c_writes_what_the_study_measured() {
    use std::time::Duration;
    let dir = tempfile::tempdir().unwrap();
    let (csv, svg) = (dir.path().join("s.csv"), dir.path().join("s.svg"));
    // A minute of simulated time at a small size: far longer than the test waits.
    let (output, _) = signal_after(
        lucent()
            .args(["study", "frameless", "--width", "48", "--height", "36"])
            .args(["--samples-per-second", "20000", "--warmup", "0.05"])
            .args(["--duration", "60", "--rate-divisors", "2", "--threads", "1"])
            .arg("--csv")
            .arg(&csv)
            .arg("--plot")
            .arg(&svg),
        Duration::from_millis(2500),
        "INT",
    );
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("interrupted: "), "{stderr}");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("double-buffer"), "the table: {stdout}");
    let rows = std::fs::read_to_string(&csv).unwrap().lines().count() - 1;
    // Five runs (three modes, two at half rate), the same refreshes each, fewer than a minute's.
    assert!(rows > 0 && rows % 5 == 0 && rows < 5 * 3600, "{rows} rows");
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
}
