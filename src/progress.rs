//! A spinner on the terminal for runs that take longer than a second:
//! which stage the run is in and how long it has taken. Nothing is drawn
//! when stderr is not a terminal (a pipe, a file, a test), nor for a run
//! that ends within the second. The environment variable
//! `HIDER_SPINNER_DELAY_MS` sets another delay (0 draws at once).

use std::io::{ErrorKind, IsTerminal, Write};
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long a run goes before the spinner appears, unless
/// `HIDER_SPINNER_DELAY_MS` says otherwise.
const DELAY: Duration = Duration::from_secs(1);

/// The delay: [`DELAY`] or the environment's.
fn delay() -> Duration {
    std::env::var("HIDER_SPINNER_DELAY_MS")
        .ok()
        .and_then(|ms| ms.trim().parse().ok())
        .map_or(DELAY, Duration::from_millis)
}

/// Draws `bar` on stderr from now on.
fn show(bar: &ProgressBar) {
    bar.set_draw_target(ProgressDrawTarget::stderr());
    bar.enable_steady_tick(Duration::from_millis(120));
}

/// The spinner of one run; cleared when dropped.
pub struct Progress {
    bar: Option<ProgressBar>,
}

impl Progress {
    /// Starts timing the run; the spinner appears after the delay if the
    /// run is still going and stderr is a terminal.
    pub fn start(first_stage: &str) -> Self {
        if !std::io::stderr().is_terminal() {
            return Self { bar: None };
        }
        let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template("{spinner} {elapsed} {msg}") {
            bar.set_style(style);
        }
        bar.set_message(first_stage.to_owned());
        let delay = delay();
        if delay.is_zero() {
            show(&bar);
            bar.tick();
        } else {
            let later = bar.clone();
            std::thread::spawn(move || {
                std::thread::sleep(delay);
                if !later.is_finished() {
                    show(&later);
                }
            });
        }
        Self { bar: Some(bar) }
    }

    /// Names the stage the run is in now.
    pub fn stage(&self, what: &str) {
        if let Some(bar) = &self.bar {
            bar.set_message(what.to_owned());
        }
    }

    /// Runs `print` with the spinner lifted, so printed lines stay whole.
    pub fn suspend<R>(&self, print: impl FnOnce() -> R) -> R {
        match &self.bar {
            Some(bar) => bar.suspend(print),
            None => print(),
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}

/// Writes `text` and a newline to stdout. A reader that has gone (a closed
/// pipe: `hider analyze FILE | head -1`) is not an error, the rest of the
/// output is simply not wanted; any other failure (a full disk) is.
pub fn print_line(text: &str) -> std::io::Result<()> {
    let mut out = std::io::stdout().lock();
    match writeln!(out, "{text}").and_then(|()| out.flush()) {
        Err(e) if e.kind() == ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}

/// Writes `text` and a newline to stderr, ignoring failure: a closed
/// stderr (`hider ... 2>&1 | head -1`) has nowhere to report to, and the
/// run's outputs matter more than its messages. `eprintln!` panics there.
pub fn eprint_line(text: &str) {
    let _ = writeln!(std::io::stderr().lock(), "{text}");
}
