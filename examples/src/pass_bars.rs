//! A progress bar per pass of a render, on the terminal's standard error (hidden where it
//! is not a terminal), for the example programs' long renders.

use std::sync::Mutex;

use beam_trace::Progress;
use indicatif::{MultiProgress, ProgressBar, ProgressStyle};

/// Shows each pass of a render as a bar while it runs, and clears it when the pass ends.
pub struct PassBars {
    bar: Mutex<Option<ProgressBar>>,
    quiet: bool,
    /// Where the bars go, below other bars (an animation's frames); `None`: on their own.
    multi: Option<MultiProgress>,
}

impl PassBars {
    /// Bars on their own line; none at all where `quiet`.
    pub fn new(quiet: bool) -> Self {
        Self {
            bar: Mutex::new(None),
            quiet,
            multi: None,
        }
    }

    /// Bars added to `multi`, below the bars it holds.
    pub fn below(multi: MultiProgress, quiet: bool) -> Self {
        Self {
            multi: Some(multi),
            ..Self::new(quiet)
        }
    }
}

impl Progress for PassBars {
    fn begin(&self, pass: &str, total: u64) {
        if self.quiet {
            return;
        }
        let b = ProgressBar::new(total);
        b.set_style(
            ProgressStyle::with_template("{prefix:>13} [{bar:40}] {pos}/{len} {elapsed}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        b.set_prefix(pass.to_string());
        let b = match &self.multi {
            Some(m) => m.add(b),
            None => b,
        };
        *self.bar.lock().expect("progress lock") = Some(b);
    }

    fn advance(&self, n: u64) {
        if let Some(b) = self.bar.lock().expect("progress lock").as_ref() {
            b.inc(n);
        }
    }

    fn end(&self) {
        if let Some(b) = self.bar.lock().expect("progress lock").take() {
            b.finish_and_clear();
        }
    }
}
