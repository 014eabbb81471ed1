//! Progress bars for long work (sweeps, the benchmark): drawn on a terminal only, with the
//! elapsed time and an ETA; durations as a clock (`1h02m03s`) for their messages.
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;

/// A progress bar over `total` items called `unit` (drawn only on a terminal, and only when
/// `show`), with elapsed time and ETA, starting at `done`.
pub(crate) fn progress_bar(total: u64, done: u64, show: bool, unit: &str) -> ProgressBar {
    let pb = ProgressBar::with_draw_target(
        Some(total),
        if show && std::io::stderr().is_terminal() {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        },
    );
    pb.set_style(
        ProgressStyle::with_template(&format!(
            "{{bar:30}} {{pos}}/{{len}} {unit}  {{elapsed_precise}} elapsed, ETA {{eta_precise}}  {{msg}}"
        ))
        .expect("valid template"),
    );
    pb.set_position(done);
    pb.reset_eta();
    pb
}

/// Seconds as `1h02m03s`, `2m03s` or `3s`.
pub(crate) fn clock(s: f64) -> String {
    let s = s.max(0.0).round() as u64;
    match (s / 3600, s / 60 % 60, s % 60) {
        (0, 0, sec) => format!("{sec}s"),
        (0, m, sec) => format!("{m}m{sec:02}s"),
        (h, m, sec) => format!("{h}h{m:02}m{sec:02}s"),
    }
}
