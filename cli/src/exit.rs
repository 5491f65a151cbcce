//! The exit codes of `noslip`, defined once: each subcommand's `--help` lists the ones it can
//! return ([`help`]), and every subcommand ends through [`finish`].

use crate::publish::PublishError;
use std::io::Write;
use std::process::ExitCode;

/// How a run of `noslip` ends. The code is what the shell sees; the meaning is what `--help`
/// says. Two outcomes share code 1: a check that failed and an output that could not be
/// written both mean "do not trust this run's result".
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exit {
    /// 0: the run finished and every check it made passed.
    Success,
    /// 1: the run finished and wrote its results, but a check failed.
    CheckFailed,
    /// 1: an output (a file, a directory, stdout) could not be written.
    OutputFailed,
    /// 2: bad input or usage; nothing was computed.
    BadInput,
}

impl Exit {
    /// The process exit code.
    pub const fn code(self) -> u8 {
        match self {
            Exit::Success => 0,
            Exit::CheckFailed | Exit::OutputFailed => 1,
            Exit::BadInput => 2,
        }
    }

    /// One line for `--help`.
    pub const fn meaning(self) -> &'static str {
        match self {
            Exit::Success => "success",
            Exit::CheckFailed => "a check failed (the results are written; stdout names it)",
            Exit::OutputFailed => {
                "an output (file, directory or stdout) could not be written (one line on stderr)"
            }
            Exit::BadInput => {
                "bad input or usage: an unreadable or invalid file, a bad option (one line on \
                 stderr names the file, field or option and what is wrong)"
            }
        }
    }
}

/// The `Exit codes:` section of a subcommand's help, one line per outcome in `codes`.
pub fn help(codes: &[Exit]) -> String {
    let mut text = String::from("Exit codes:");
    for exit in codes {
        text.push_str(&format!("\n  {}  {}", exit.code(), exit.meaning()));
    }
    text
}

/// Every outcome, for the top-level help.
pub const ALL: &[Exit] = &[
    Exit::Success,
    Exit::CheckFailed,
    Exit::OutputFailed,
    Exit::BadInput,
];

/// A list of outcomes that renders as [`help`] (for help texts built with `format!`).
#[derive(Clone, Copy, Debug)]
pub struct Codes(pub &'static [Exit]);

impl std::fmt::Display for Codes {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&help(self.0))
    }
}

/// A run that stopped early: the outcome and the one line that says why.
#[derive(Debug)]
pub struct Failure {
    /// The outcome.
    pub exit: Exit,
    /// Why, in one line.
    pub message: String,
}

impl Failure {
    /// A failure with outcome `exit`.
    pub fn new(exit: Exit, message: impl Into<String>) -> Failure {
        Failure {
            exit,
            message: message.into(),
        }
    }

    /// Bad input or usage ([`Exit::BadInput`], code 2).
    pub fn bad_input(message: impl Into<String>) -> Failure {
        Failure::new(Exit::BadInput, message)
    }

    /// An output that could not be written ([`Exit::OutputFailed`], code 1).
    pub fn output(message: impl Into<String>) -> Failure {
        Failure::new(Exit::OutputFailed, message)
    }
}

/// A publishing error as a failure: a directory that is not noslip's is bad usage of --out.
pub fn publish_failure(e: &PublishError) -> Failure {
    match e {
        PublishError::NotOurs(_) | PublishError::NoName(_) => {
            Failure::bad_input(format!("--out: {e}"))
        }
        PublishError::Io { .. } => Failure::output(format!("cannot write the output: {e}")),
    }
}

/// The `Exit codes:` section of `collide --help`.
pub const COLLIDE_CODES: Codes = Codes(&[Exit::Success, Exit::OutputFailed, Exit::BadInput]);

/// End a subcommand: its outcome's code, and for a failure one line `error: ...` on stderr
/// (line breaks in the message, say from a path, are flattened; a failing stderr is ignored,
/// there is nowhere left to report it).
pub fn finish(result: Result<Exit, Failure>) -> ExitCode {
    let exit = match result {
        Ok(exit) => exit,
        Err(f) => {
            let line = f.message.replace(['\n', '\r'], " ");
            let _ = writeln!(std::io::stderr(), "error: {line}");
            f.exit
        }
    };
    ExitCode::from(exit.code())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn help_lists_the_given_outcomes_with_their_codes() {
        let text = help(&[Exit::Success, Exit::BadInput]);
        assert_eq!(
            text.lines().map(|l| &l[..5]).collect::<Vec<_>>(),
            ["Exit ", "  0  ", "  2  "]
        );
    }
}
