//! Printing to stdout without panicking (`println!` panics when stdout fails).
//!
//! The rule, for every subcommand: a reader that went away (a broken pipe, `noslip gen |
//! head`) ends all further output quietly and the run ends with the exit code its results
//! give; any other failure (a full disk, `> /dev/full`) is [`Exit::OutputFailed`] with one
//! line on stderr. Subcommands write their files before they print, so a failing stdout
//! never loses them.

use super::exit::{Exit, Failure};
use std::io::{self, ErrorKind, Write};
use std::sync::atomic::{AtomicBool, Ordering};

/// Set once a write met a broken pipe: nothing more is printed.
static READER_GONE: AtomicBool = AtomicBool::new(false);

/// Write `text` to stdout and flush it.
pub fn print(text: &str) -> Result<(), Failure> {
    if READER_GONE.load(Ordering::Relaxed) {
        return Ok(());
    }
    let mut stdout = io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == ErrorKind::BrokenPipe => {
            READER_GONE.store(true, Ordering::Relaxed);
            Ok(())
        }
        Err(e) => Err(Failure::new(
            Exit::OutputFailed,
            format!("cannot write to stdout: {e}"),
        )),
    }
}

/// `println!` through [`print()`]: evaluates to `Result<(), Failure>`.
macro_rules! outln {
    ($($arg:tt)*) => {
        $crate::out::print(&format!("{}\n", format_args!($($arg)*)))
    };
}
pub(crate) use outln;
