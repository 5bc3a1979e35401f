//! Progress on stderr: a spinner fed by the solver's observer
//! ([`thirdbody::Progress`]), and bars for the stress phase
//! ([`thirdbody::stress::StressProgress`], one step per depth plane, with the time
//! left) and for `reproduce` (one step per figure). Each stays hidden for the first
//! second, so quick work prints nothing, and none is drawn when stderr is not a
//! terminal.

use std::sync::mpsc;
use std::thread::JoinHandle;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use thirdbody::stress::StressProgress;
use thirdbody::Progress;

/// Delay before the spinner appears.
const SHOW_AFTER: Duration = Duration::from_secs(1);

/// A hidden bar that shows itself after [`SHOW_AFTER`] unless finished first.
struct Delayed {
    bar: ProgressBar,
    stop: Option<mpsc::Sender<()>>,
    timer: Option<JoinHandle<()>>,
}

impl Delayed {
    /// A bar of `length` steps (`None`: a spinner) drawn with `template`, shown after
    /// [`SHOW_AFTER`] if `enabled`.
    fn new(enabled: bool, length: Option<u64>, template: &str) -> Self {
        let bar = ProgressBar::with_draw_target(length, ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template(template) {
            bar.set_style(style.progress_chars("=> "));
        }
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
        Delayed { bar, stop, timer }
    }

    /// Removes the bar.
    fn finish(mut self) {
        self.stop.take();
        if let Some(t) = self.timer.take() {
            let _ = t.join();
        }
        self.bar.finish_and_clear();
    }
}

/// The spinner of one solve.
pub struct Spinner {
    shown: Delayed,
    window: usize,
}

impl Spinner {
    /// A spinner that shows itself after [`SHOW_AFTER`] if `enabled`.
    pub fn new(enabled: bool) -> Self {
        let shown = Delayed::new(enabled, None, "{spinner} {elapsed:>4} {msg}");
        shown.bar.set_message("setting up kernels");
        Spinner { shown, window: 0 }
    }

    /// Shows what the solver reports.
    pub fn observe(&mut self, progress: Progress) {
        match progress {
            Progress::Window { attempt, grid } => {
                self.window = attempt;
                let [wx, wy] = grid.half_widths();
                self.shown.bar.set_message(if grid.is_line() {
                    format!("window {attempt}: {} cells, half width {wx:.3e}", grid.nx())
                } else {
                    format!(
                        "window {attempt}: {} x {} cells, half widths {wx:.3e} x {wy:.3e}",
                        grid.nx(),
                        grid.ny()
                    )
                });
            }
            Progress::Iteration {
                iteration,
                residual,
            } => self.shown.bar.set_message(format!(
                "window {}, iteration {iteration}, residual {residual:.2e}",
                self.window
            )),
        }
    }

    /// Removes the spinner.
    pub fn finish(self) {
        self.shown.finish();
    }
}

/// The bar of a stress computation: depth planes done of all, the section being
/// computed and the time left.
pub struct StressBar {
    shown: Delayed,
}

impl StressBar {
    /// A bar that shows itself after [`SHOW_AFTER`] if `enabled`.
    pub fn new(enabled: bool) -> Self {
        let shown = Delayed::new(
            enabled,
            Some(0),
            "{spinner} {elapsed:>4} stresses, {msg} [{bar:24}] {pos}/{len} depth planes, \
             about {eta} left",
        );
        StressBar { shown }
    }

    /// Shows what the stress computation reports (called from any thread).
    pub fn observe(&self, progress: StressProgress<'_>) {
        let bar = &self.shown.bar;
        match progress {
            StressProgress::Start { planes } => bar.set_length(planes as u64),
            StressProgress::Section { name, .. } => bar.set_message(name.to_string()),
            StressProgress::PlaneDone => bar.inc(1),
        }
    }

    /// Removes the bar.
    pub fn finish(self) {
        self.shown.finish();
    }
}

/// The bar of `thirdbody reproduce`: figures done of all, the one being computed.
pub struct FigureBar {
    shown: Delayed,
}

impl FigureBar {
    /// A bar of `figures` steps that shows itself after [`SHOW_AFTER`] if `enabled`.
    pub fn new(enabled: bool, figures: usize) -> Self {
        let shown = Delayed::new(
            enabled,
            Some(figures as u64),
            "{spinner} {elapsed:>4} {msg} [{bar:24}] {pos}/{len} figures, about {eta} left",
        );
        FigureBar { shown }
    }

    /// Figure `name` is being computed.
    pub fn start(&self, name: &str) {
        self.shown.bar.set_message(name.to_string());
    }

    /// A figure is done; `line` is printed above the bar.
    pub fn done(&self, line: &str) {
        self.shown.bar.suspend(|| eprintln!("{line}"));
        self.shown.bar.inc(1);
    }

    /// Removes the bar.
    pub fn finish(self) {
        self.shown.finish();
    }
}
