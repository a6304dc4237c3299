//! Reads run on a thread of their own, under a deadline, with a global allocator that counts
//! what each such thread holds.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::path::Path;
use std::sync::mpsc::RecvTimeoutError;
use std::time::Duration;

/// Most bytes one read may hold at once before the test fails.
pub const CAP: usize = 512 << 20;
/// Above this, a single request or the live total is refused and the process aborts: a broken
/// parser must not take the machine's memory with it before the test can report.
pub const HARD_CAP: usize = 2 << 30;
/// Longest one read may take (the samples take milliseconds).
pub const DEADLINE: Duration = Duration::from_secs(10);

/// `System`, counting the bytes each watched thread holds and refusing what passes [`HARD_CAP`].
struct Counting;

thread_local! {
    /// Whether this thread's allocations are counted (the threads that run one read).
    static WATCHED: Cell<bool> = const { Cell::new(false) };
    /// Bytes allocated minus bytes freed on this thread since it began watching.
    static LIVE: Cell<isize> = const { Cell::new(0) };
    /// The largest `LIVE` seen.
    static PEAK: Cell<isize> = const { Cell::new(0) };
    /// The largest single request.
    static LARGEST: Cell<usize> = const { Cell::new(0) };
}

impl Counting {
    /// Counts `grow` more bytes, of a request of `size`; false when they must be refused.
    fn admit(grow: usize, size: usize) -> bool {
        if !WATCHED.with(Cell::get) {
            return true;
        }
        LARGEST.with(|l| l.set(l.get().max(size)));
        let live = LIVE.with(Cell::get).saturating_add(grow as isize);
        PEAK.with(|p| p.set(p.get().max(live)));
        if size > HARD_CAP || live > HARD_CAP as isize {
            return false;
        }
        LIVE.with(|l| l.set(live));
        true
    }

    fn release(size: usize) {
        if WATCHED.with(Cell::get) {
            LIVE.with(|l| l.set(l.get() - size as isize));
        }
    }
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !Self::admit(layout.size(), layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: forwarded unchanged; `layout` is the caller's, valid by the trait's contract.
        let p = unsafe { System.alloc(layout) };
        if p.is_null() {
            Self::release(layout.size());
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !Self::admit(layout.size(), layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: as in `alloc`.
        let p = unsafe { System.alloc_zeroed(layout) };
        if p.is_null() {
            Self::release(layout.size());
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: `ptr` came from `System` with `layout`, by the trait's contract.
        unsafe { System.dealloc(ptr, layout) };
        Self::release(layout.size());
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        if !Self::admit(new_size.saturating_sub(old), new_size) {
            return std::ptr::null_mut();
        }
        // SAFETY: `ptr` came from `System` with `layout`; `new_size` is the caller's.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if p.is_null() {
            Self::release(new_size.saturating_sub(old));
        } else {
            Self::release(old.saturating_sub(new_size));
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// What one read did to memory: the most bytes held at once, and the largest single request.
struct Memory {
    peak: usize,
    largest: usize,
}

/// Runs `read` on a thread of its own, watched by the allocator, and waits at most
/// [`DEADLINE`]. `Err` on a panic or a breach of [`CAP`]; on a hang, the process exits.
pub fn run_watched(
    format: &str,
    input: &Path,
    read: impl FnOnce() + Send + 'static,
) -> Result<(), String> {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::Builder::new()
        .name(format!("read {format}"))
        // The main thread's size: what the command line reads scenes with.
        .stack_size(8 << 20)
        .spawn(move || {
            WATCHED.with(|w| w.set(true));
            let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(read));
            let memory = Memory {
                peak: PEAK.with(Cell::get).max(0) as usize,
                largest: LARGEST.with(Cell::get),
            };
            WATCHED.with(|w| w.set(false));
            let outcome = outcome.map_err(|p| {
                p.downcast_ref::<String>()
                    .cloned()
                    .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                    .unwrap_or_else(|| "a panic without a message".into())
            });
            let _ = tx.send((outcome, memory));
        })
        .map_err(|e| format!("cannot start a thread: {e}"))?;
    let (outcome, memory) = match rx.recv_timeout(DEADLINE) {
        Ok(done) => done,
        Err(RecvTimeoutError::Disconnected) => {
            return Err("the read's thread ended without an answer".into());
        }
        Err(RecvTimeoutError::Timeout) => {
            // Not through the test harness's capture, which an exit would lose.
            use std::io::Write;
            let _ = writeln!(
                std::io::stderr(),
                "fuzz_mutations: reading a mutated {format} file took more than {DEADLINE:?}; the input is {}",
                input.display()
            );
            std::process::exit(1);
        }
    };
    outcome.map_err(|m| format!("the read panicked: {m}"))?;
    if memory.peak > CAP || memory.largest > CAP {
        return Err(format!(
            "the read held {} MiB at once and asked for {} MiB in one request; the cap is {} MiB",
            memory.peak >> 20,
            memory.largest >> 20,
            CAP >> 20
        ));
    }
    Ok(())
}
