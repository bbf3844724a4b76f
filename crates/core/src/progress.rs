//! A progress bar on stderr that appears only once a render has run for half a second, and
//! only for a person watching a terminal: quick renders and scripts see nothing.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long a render runs before the bar is worth showing.
const DELAY: Duration = Duration::from_millis(500);

/// The bar of a long run (rows rendered, students graded): not the stages of the handout a
/// student has reached, which are `whitted_check::check::progress::Stages`.
pub struct Bar {
    bar: ProgressBar,
    started: Instant,
    /// Whether the bar may ever be shown (a terminal, and not --quiet).
    wanted: bool,
    shown: AtomicBool,
}

impl Bar {
    /// A bar over `rows` rows; `quiet` or a non-terminal stderr keep it hidden for good.
    pub fn new(rows: u64, quiet: bool) -> Self {
        Bar::counting(rows, quiet, "rendering", "rows")
    }

    /// A bar over `total` things (`unit`) that `doing` goes through.
    pub fn counting(total: u64, quiet: bool, doing: &str, unit: &str) -> Self {
        let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::hidden());
        if let Ok(style) = ProgressStyle::with_template(&format!(
            "{{spinner}} {doing} [{{bar:40}}] {{pos}}/{{len}} {unit}, {{eta}} left"
        )) {
            bar.set_style(style.progress_chars("=> "));
        }
        Bar {
            bar,
            started: Instant::now(),
            wanted: !quiet && std::io::stderr().is_terminal(),
            shown: AtomicBool::new(false),
        }
    }

    /// Records `rows` more finished rows; safe from any thread.
    pub fn advance(&self, rows: u64) {
        self.bar.inc(rows);
        if self.wanted
            && self.started.elapsed() >= DELAY
            && !self.shown.swap(true, Ordering::Relaxed)
        {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
    }

    /// Removes the bar from the screen.
    pub fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Drop for Bar {
    /// Also on an error or an interruption: the bar never stays on screen.
    fn drop(&mut self) {
        self.bar.finish_and_clear();
    }
}

/// Erases the current terminal line on stderr (where a bar may be drawn), for a process that
/// exits without unwinding.
pub fn clear_line() {
    use std::io::Write;
    let mut err = std::io::stderr();
    if err.is_terminal() {
        let _ = err.write_all(b"\r\x1b[2K");
    }
}
