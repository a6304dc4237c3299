//! Long work (a render, the frameless study) run on its own thread with the GIL released,
//! while the calling thread wakes every [`POLL`] to report progress and to let Python's
//! signal handlers run: Ctrl-C stops the work, which returns what it has.

use pyo3::exceptions::{PyException, PyKeyboardInterrupt};
use pyo3::prelude::*;
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// How often the calling thread looks up from the work: for Ctrl-C and progress.
const POLL: Duration = Duration::from_millis(50);

/// What the work is given: a flag to stop at, and where to report (done, total).
pub struct Control<'a> {
    /// Set when the work should stop and return what it has.
    pub cancel: &'a AtomicBool,
    /// Reports (done, total) from any thread.
    pub report: &'a (dyn Fn(u64, u64) + Sync),
}

/// Runs `work` on its own thread; `progress(done, total)` is called about every 50 ms and
/// once at the end. Returns its result and whether Ctrl-C (KeyboardInterrupt) stopped it; an
/// error raised by `progress` stops the work and is raised here.
pub fn run_polled<T: Send>(
    py: Python<'_>,
    progress: Option<&Bound<'_, PyAny>>,
    work: impl FnOnce(Control<'_>) -> T + Send,
) -> PyResult<(T, bool)> {
    let (cancel, ended) = (AtomicBool::new(false), AtomicBool::new(false));
    // One lock for the pair, so a poll never sees a new `done` with an old `total`.
    let counts = Mutex::new((0u64, 0u64));
    let report = |d: u64, t: u64| {
        if let Ok(mut c) = counts.lock() {
            *c = (d, t);
        }
    };
    let call = |f: &Bound<'_, PyAny>| {
        let (d, t) = counts.lock().map_or((0, 0), |c| *c);
        f.call1((d, t)).map(drop)
    };
    let mut stopped_by: Option<PyErr> = None;
    let result = std::thread::scope(|s| {
        let control = Control {
            cancel: &cancel,
            report: &report,
        };
        // The worker's end wakes the caller at once, not at the next poll.
        let caller = std::thread::current();
        let ended = &ended;
        let worker = s.spawn(move || {
            let result = work(control);
            ended.store(true, Ordering::Release);
            caller.unpark();
            result
        });
        loop {
            py.detach(|| std::thread::park_timeout(POLL));
            // (A worker that panicked never says it ended.)
            if ended.load(Ordering::Acquire) || worker.is_finished() {
                break;
            }
            if stopped_by.is_some() {
                continue;
            }
            let polled = py
                .check_signals()
                .and_then(|()| progress.map_or(Ok(()), call));
            if let Err(e) = polled {
                cancel.store(true, Ordering::Relaxed);
                stopped_by = Some(e);
            }
        }
        worker.join()
    });
    let Ok(result) = result else {
        return Err(PyException::new_err(
            "lucent: internal error (a thread panicked)",
        ));
    };
    let interrupted = match stopped_by {
        Some(e) if e.is_instance_of::<PyKeyboardInterrupt>(py) => true,
        Some(e) => return Err(e),
        None => false,
    };
    if let Some(f) = progress {
        call(f)?;
    }
    Ok((result, interrupted))
}
