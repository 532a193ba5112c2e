//! Limits on one fuzz input, so that a reader that hangs or asks for unbounded memory fails the
//! test naming the input instead of hanging CI or being killed by the kernel.
//!
//! Each input runs on a worker thread of a [`BoundedRunner`]; the driver waits for it at most
//! [`Limits::time`]. Memory is counted by [`CountingAlloc`], which a binary that runs bounded
//! inputs installs as its global allocator: what the worker's thread holds is counted while an
//! input runs. Past [`Limits::memory`] the input fails when it returns; past
//! [`ABORT_FACTOR`] times that, the process stops at once, first writing the input to its file
//! and naming it (memory that large would take the machine down before the input returned).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::{Cell, RefCell};
use std::io::Write;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::sync::mpsc::{channel, Receiver, RecvTimeoutError, Sender};
use std::time::Duration;

/// What one input may take.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    pub time: Duration,
    /// Bytes held at once by the thread the input runs on.
    pub memory: usize,
}

/// Over this many times [`Limits::memory`], the process is stopped with the input named.
pub const ABORT_FACTOR: usize = 8;

/// How one input ended.
#[derive(Debug, PartialEq)]
pub enum Outcome {
    /// The reader returned: accepted (`Ok`) or refused with its message.
    Returned(Result<(), String>),
    /// Panicked, with its message (an integer overflow's among them: every crate of ours is
    /// built with overflow checks, in release too).
    Panicked(String),
    /// Still running when the time limit passed (the worker is left behind; the runner is spent).
    TimedOut,
    /// Returned, but held more memory than the limit at its peak (bytes).
    OverMemory(usize),
}

thread_local! {
    /// Whether this thread's allocations are counted (while a bounded input runs on it).
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    /// Bytes allocated minus freed by this thread since the input started.
    static HELD: Cell<isize> = const { Cell::new(0) };
    static PEAK: Cell<isize> = const { Cell::new(0) };
    static ABORT_AT: Cell<isize> = const { Cell::new(isize::MAX) };
    /// The running input and the file it is written to if it breaks a limit.
    static INPUT: RefCell<(PathBuf, Vec<u8>)> = const { RefCell::new((PathBuf::new(), Vec::new())) };
}

/// The system allocator, counting the bytes a bounded input's thread holds.
pub struct CountingAlloc;

impl CountingAlloc {
    fn count(size: usize, grow: bool) {
        // `try_with`: a thread being torn down has no locals left.
        let _ = COUNTING.try_with(|counting| {
            if !counting.get() {
                return;
            }
            let held = HELD.get() + if grow { size as isize } else { -(size as isize) };
            HELD.set(held);
            if held > PEAK.get() {
                PEAK.set(held);
            }
            if held > ABORT_AT.get() {
                // Stop counting first: naming the input allocates.
                counting.set(false);
                abort_naming_the_input(held as usize);
            }
        });
    }
}

fn abort_naming_the_input(held: usize) -> ! {
    let message = INPUT.with_borrow(|(file, input)| {
        let written = std::fs::write(file, input).map_or_else(|e| format!(" (not written: {e})"), |_| String::new());
        format!("fuzz: an input asked for {} MiB at once; it is in {}{written}\n", held >> 20, file.display())
    });
    let _ = std::io::stderr().write_all(message.as_bytes());
    std::process::abort()
}

// SAFETY: every call is passed on to `System` unchanged; the counting around it touches only
// this thread's `const` thread-locals, which do not allocate, and never unwinds.
unsafe impl GlobalAlloc for CountingAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        Self::count(layout.size(), true);
        System.alloc(layout)
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        Self::count(layout.size(), true);
        System.alloc_zeroed(layout)
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        Self::count(layout.size(), false);
        System.dealloc(ptr, layout)
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        Self::count(new_size.abs_diff(old), new_size > old);
        System.realloc(ptr, layout, new_size)
    }
}

type Reader = dyn Fn(&[u8]) -> Result<(), String> + Send;

/// What the worker sends back for an input: the reader's result (`Err` with the panic's
/// message if it panicked), and the most bytes its thread held.
type Finished = (Result<Result<(), String>, String>, isize);

/// A panic's message, as `panic!` and the overflow checks give it.
fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".into())
}

/// Runs inputs one at a time on a worker thread, each under [`Limits`].
pub struct BoundedRunner {
    limits: Limits,
    inputs: Sender<(PathBuf, Vec<u8>)>,
    outcomes: Receiver<Finished>,
}

impl BoundedRunner {
    /// A worker that feeds each input to `reader`. Memory is counted only in a binary whose
    /// global allocator is [`CountingAlloc`].
    pub fn new(limits: Limits, reader: Box<Reader>) -> Self {
        let (inputs, worker_inputs) = channel::<(PathBuf, Vec<u8>)>();
        let (worker_outcomes, outcomes) = channel();
        let abort_at = limits.memory.saturating_mul(ABORT_FACTOR).min(isize::MAX as usize) as isize;
        std::thread::Builder::new()
            .name("fuzz-input".into())
            .spawn(move || {
                ABORT_AT.set(abort_at);
                for (file, input) in worker_inputs {
                    INPUT.set((file, input));
                    HELD.set(0);
                    PEAK.set(0);
                    COUNTING.set(true);
                    let result = INPUT.with_borrow(|(_, input)| catch_unwind(AssertUnwindSafe(|| reader(input))));
                    COUNTING.set(false);
                    let result = result.map_err(|payload| panic_message(payload.as_ref()));
                    if worker_outcomes.send((result, PEAK.get())).is_err() {
                        return;
                    }
                }
            })
            .expect("a fuzz worker thread");
        Self { limits, inputs, outcomes }
    }

    /// Runs `input`, to be written to `file` and named if it breaks a limit (the caller writes
    /// it for an outcome it judges a failure). Returns how it ended and the most memory it held.
    pub fn run(&self, input: &[u8], file: PathBuf) -> (Outcome, usize) {
        if self.inputs.send((file, input.to_vec())).is_err() {
            return (Outcome::Panicked("the worker is gone".into()), 0);
        }
        match self.outcomes.recv_timeout(self.limits.time) {
            Ok((result, peak)) => {
                let peak = peak.max(0) as usize;
                let outcome = match result {
                    Ok(_) if peak > self.limits.memory => Outcome::OverMemory(peak),
                    Ok(result) => Outcome::Returned(result),
                    Err(message) => Outcome::Panicked(message),
                };
                (outcome, peak)
            }
            Err(RecvTimeoutError::Disconnected) => (Outcome::Panicked("the worker is gone".into()), 0),
            Err(RecvTimeoutError::Timeout) => (Outcome::TimedOut, 0),
        }
    }
}
