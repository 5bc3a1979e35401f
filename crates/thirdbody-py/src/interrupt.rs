//! Long computations run without the GIL on a thread of their own while the calling
//! thread keeps looking at the caller's signals (Ctrl-C) and hands progress events to
//! the caller's callback; each on a rayon pool of its own.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;

/// How often a running computation's caller looks at its signals (Ctrl-C) and hands
/// progress to its callback.
pub const POLL: Duration = Duration::from_millis(50);

/// Runs `work` on a rayon pool made for this call (`threads` threads; by default
/// as many as rayon's global pool would have, so results equal the CLI's). Never
/// rayon's global pool: a process forked after that pool started (a
/// `ProcessPoolExecutor`'s worker on Linux) inherits it without its threads, and its
/// first parallel loop would wait forever. A pool costs tens of microseconds.
pub fn in_own_pool<R: Send>(
    threads: Option<usize>,
    work: impl FnOnce() -> R + Send,
) -> PyResult<R> {
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        builder = builder.num_threads(n);
    }
    let pool = builder
        .build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start the solver's threads: {e}")))?;
    Ok(pool.install(work))
}

/// Runs `work` without the GIL on a thread of its own while this thread waits: every
/// [`POLL`] (and as soon as `work` sends events) it gives the events to `on_events`
/// and looks at the signals. Ctrl-C (`KeyboardInterrupt`) or an exception from
/// `on_events` sets the flag `work` is given, which it must look at often and stop
/// on; the exception is raised once `work` has returned.
pub fn interruptible<R: Send, E: Send>(
    py: Python<'_>,
    work: impl FnOnce(&AtomicBool, mpsc::Sender<E>) -> R + Send,
    mut on_events: impl FnMut(Python<'_>, Vec<E>) -> PyResult<()> + Send,
) -> PyResult<R> {
    let stop = AtomicBool::new(false);
    let (events, received) = mpsc::channel::<E>();
    let mut caller_error: Option<PyErr> = None;
    let (stop, caller_error_slot) = (&stop, &mut caller_error);
    let outcome = py.allow_threads(move || {
        std::thread::scope(|scope| {
            let worker = scope.spawn(move || work(stop, events));
            let mut pending = Vec::new();
            loop {
                let finished = match received.recv_timeout(POLL) {
                    Ok(e) => {
                        pending.push(e);
                        pending.extend(received.try_iter());
                        false
                    }
                    Err(RecvTimeoutError::Timeout) => false,
                    Err(RecvTimeoutError::Disconnected) => true,
                };
                if caller_error_slot.is_none() {
                    let batch = std::mem::take(&mut pending);
                    let checked = Python::with_gil(|py| -> PyResult<()> {
                        py.check_signals()?;
                        on_events(py, batch)
                    });
                    if let Err(e) = checked {
                        *caller_error_slot = Some(e);
                        stop.store(true, Ordering::Relaxed);
                    }
                }
                pending.clear();
                if finished {
                    break;
                }
            }
            worker.join()
        })
    });
    if let Some(e) = caller_error {
        return Err(e);
    }
    outcome.map_err(|_| PyRuntimeError::new_err("the solver panicked (a bug, please report it)"))
}
