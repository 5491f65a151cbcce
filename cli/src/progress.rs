//! Progress of a long run on stderr: a bar on a terminal; elsewhere (a log file, CI, a pipe),
//! where the bar does not draw, a plain line now and then, so a two-minute run is never
//! silent. Failing stderr writes are ignored: progress is not a result.

use indicatif::{ProgressBar, ProgressStyle};
use std::io::{self, IsTerminal, Write};

/// Progress of a long run on stderr: a bar on a terminal, a line now and then elsewhere.
pub struct ProgressDisplay {
    /// `Some` on a terminal.
    bar: Option<ProgressBar>,
}

impl ProgressDisplay {
    /// `len` steps; `unit` names them in the bar (`checks`, `regimes`).
    pub fn new(len: u64, unit: &str) -> ProgressDisplay {
        let bar = io::stderr().is_terminal().then(|| {
            let bar = ProgressBar::new(len);
            let template = format!("{{bar:30}} {{pos}}/{{len}} {unit}  {{msg}}");
            bar.set_style(ProgressStyle::with_template(&template).expect("a valid template"));
            bar
        });
        ProgressDisplay { bar }
    }

    /// What is running now (the bar's message; nothing off a terminal).
    pub fn set_message(&self, text: String) {
        if let Some(bar) = &self.bar {
            bar.set_message(text);
        }
    }

    /// One step done; off a terminal, `line` (if any) is printed for it.
    pub fn inc(&self, line: Option<String>) {
        match (&self.bar, line) {
            (Some(bar), _) => bar.inc(1),
            (None, Some(line)) => eprint_line(&line),
            (None, None) => {}
        }
    }

    /// A line that must be seen (a failure), on a terminal or not.
    pub fn println(&self, line: String) {
        match &self.bar {
            Some(bar) => bar.println(line),
            None => eprint_line(&line),
        }
    }

    /// Clear the bar (nothing to do off a terminal).
    pub fn finish(self) {
        if let Some(bar) = self.bar {
            bar.finish_and_clear();
        }
    }
}

fn eprint_line(line: &str) {
    let _ = writeln!(io::stderr().lock(), "{line}");
}
