//! Progress bars on standard error (indicatif) for the long commands: sweeps and reports.
//! Drawn only when standard error is a terminal and `--quiet` is not given, so that pipes,
//! files and the tests see nothing of them.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// A progress bar, or nothing.
pub struct Progress {
    bar: Option<ProgressBar>,
}

impl Progress {
    /// A bar of `len` steps labelled `what`; hidden with `quiet` or when standard error is
    /// not a terminal.
    pub fn new(quiet: bool, len: u64, what: &str) -> Progress {
        if quiet || !std::io::stderr().is_terminal() {
            return Progress { bar: None };
        }
        let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
        if let Ok(style) =
            ProgressStyle::with_template("{msg:>18} [{bar:40}] {pos}/{len} {elapsed_precise}")
        {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(what.to_string());
        Progress { bar: Some(bar) }
    }

    /// One step done (boundary refinements may go past the length: the bar then stays full).
    pub fn tick(&self) {
        if let Some(b) = &self.bar
            && b.position() + 1 < b.length().unwrap_or(u64::MAX)
        {
            b.inc(1);
        }
    }

    /// Sets the message (the stage of a report).
    pub fn stage(&self, what: &str) {
        if let Some(b) = &self.bar {
            b.set_message(what.to_string());
            b.inc(1);
        }
    }

    /// Removes the bar from the terminal.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}
