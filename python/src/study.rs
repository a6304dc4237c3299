//! The frameless study (`lucent study frameless`) from Python: its table as rows of dicts, one
//! per run, and every refresh as the CLI's CSV has it.

use lucent::schedule::frameless::DisplayMode;
use lucent::study::frameless::{Run, StudyReport, StudySettings};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// One run (a display mode at a sample rate) as a row.
fn row<'py>(py: Python<'py>, run: &Run) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("mode", run.mode.name())?;
    d.set_item("samples_per_second", run.samples_per_second)?;
    d.set_item("mean_rmse", run.mean_rmse())?;
    d.set_item("mean_stale", run.mean_stale())?;
    d.set_item("mean_latency_ms", 1000.0 * run.mean_latency())?;
    d.set_item("latency_p95_ms", 1000.0 * run.latency_p95())?;
    d.set_item("unseen", run.unseen)?;
    d.set_item("samples", run.samples)?;
    d.set_item("refreshes", run.refreshes.len())?;
    Ok(d)
}

/// The report: `rows` (one per run: the three modes at the full rate first, then the lower
/// rates), `refreshes` (every measured refresh of every run), `matching` (the rate at which
/// frameless and adaptive frameless match double buffering's error), and the conditions.
pub fn report<'py>(
    py: Python<'py>,
    report: &StudyReport,
    rays: u64,
    interrupted: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("width", report.width)?;
    d.set_item("height", report.height)?;
    d.set_item("settings", settings(py, &report.settings)?)?;
    let rows = PyList::empty(py);
    let refreshes = PyList::empty(py);
    for run in &report.runs {
        rows.append(row(py, run)?)?;
        for r in &run.refreshes {
            let f = PyDict::new(py);
            f.set_item("mode", run.mode.name())?;
            f.set_item("samples_per_second", run.samples_per_second)?;
            f.set_item("time", r.time)?;
            f.set_item("rmse", r.rmse)?;
            f.set_item("stale_fraction", r.stale_fraction)?;
            refreshes.append(f)?;
        }
    }
    d.set_item("rows", rows)?;
    d.set_item("refreshes", refreshes)?;
    let matching = PyDict::new(py);
    for mode in [DisplayMode::Frameless, DisplayMode::Adaptive] {
        let m = match report.matching_rate(mode) {
            None => None,
            Some((rate, bound)) => {
                let m = PyDict::new(py);
                m.set_item("samples_per_second", rate)?;
                m.set_item("fewer_samples", report.settings.samples_per_second / rate)?;
                // The lowest rate tried still matched: the true rate is lower.
                m.set_item("bound", bound)?;
                Some(m)
            }
        };
        matching.set_item(mode.name(), m)?;
    }
    d.set_item("matching", matching)?;
    d.set_item("rays", rays)?;
    d.set_item("interrupted", interrupted)?;
    Ok(d)
}

fn settings<'py>(py: Python<'py>, s: &StudySettings) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("samples_per_second", s.samples_per_second)?;
    d.set_item("refresh", s.refresh_hz)?;
    // Stopped early: the span the refreshes cover.
    d.set_item("duration", s.duration)?;
    d.set_item("warmup", s.warmup)?;
    d.set_item("rate_divisors", s.rate_divisors.clone())?;
    d.set_item("seed", s.seed)?;
    Ok(d)
}
