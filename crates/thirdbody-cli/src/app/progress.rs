//! A spinner on stderr fed by the solver's observer ([`thirdbody::Progress`]). It
//! stays hidden for the first second, so quick solves print nothing, and it is
//! never drawn when stderr is not a terminal.

use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use thirdbody::Progress;

/// Delay before the spinner appears.
const SHOW_AFTER: Duration = Duration::from_secs(1);

/// The spinner of one solve.
pub struct Spinner {
    bar: ProgressBar,
    window: usize,
    stop: Option<mpsc::Sender<()>>,
    timer: Option<JoinHandle<()>>,
}

impl Spinner {
    /// A spinner that shows itself after [`SHOW_AFTER`] if `enabled`.
    pub fn new(enabled: bool) -> Self {
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template("{spinner} {elapsed:>4} {msg}") {
            bar.set_style(style);
        }
        bar.set_message("setting up kernels");
        let (stop, timer) = if enabled {
            let (tx, rx) = mpsc::channel::<()>();
            let shown = bar.clone();
            let timer = std::thread::spawn(move || {
                // Disconnected (finished) before the delay: stay hidden.
                if let Err(mpsc::RecvTimeoutError::Timeout) = rx.recv_timeout(SHOW_AFTER) {
                    shown.set_draw_target(ProgressDrawTarget::stderr());
                    shown.enable_steady_tick(Duration::from_millis(120));
                }
            });
            (Some(tx), Some(timer))
        } else {
            (None, None)
        };
        Spinner {
            bar,
            window: 0,
            stop,
            timer,
        }
    }

    /// Shows what the solver reports.
    pub fn observe(&mut self, progress: Progress) {
        match progress {
            Progress::Window { attempt, grid } => {
                self.window = attempt;
                let [wx, wy] = grid.half_widths();
                self.bar.set_message(format!(
                    "window {attempt}: {} x {} cells, half widths {wx:.3e} x {wy:.3e}",
                    grid.nx, grid.ny
                ));
            }
            Progress::Iteration {
                iteration,
                residual,
            } => self.bar.set_message(format!(
                "window {}, iteration {iteration}, residual {residual:.2e}",
                self.window
            )),
        }
    }

    /// Removes the spinner.
    pub fn finish(mut self) {
        self.stop.take();
        if let Some(t) = self.timer.take() {
            let _ = t.join();
        }
        self.bar.finish_and_clear();
    }
}
