//! Printing to stdout without panicking (`println!` panics when stdout fails).
//!
//! The rule, for every subcommand: a reader that went away (a broken pipe, `noslip gen |
//! head`) ends all further output quietly and the run ends with the exit code its results
//! give; any other failure (a full disk, `> /dev/full`, a stdout closed at start, `>&-`) is
//! [`Exit::OutputFailed`] with one line on stderr. Subcommands write their files before they
//! print, so a failing stdout never loses them.

use super::exit::{Exit, Failure};
use std::io::{self, ErrorKind, Write};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::OnceLock;

/// Set once a write met a broken pipe: nothing more is printed.
static READER_GONE: AtomicBool = AtomicBool::new(false);

/// Why stdout cannot take output at all (`closed`, `open for reading only`), if it cannot: closed when the program started, or
/// open for reading only. Both would lose every line silently: the Rust runtime puts
/// `/dev/null`, opened read-write, in place of a closed standard descriptor, and the standard
/// library treats a write's `EBADF` (a read-only descriptor) as success. A `> /dev/null` of
/// the shell opens it write-only, so a read-write `/dev/null` is taken for `>&-` (also
/// `1<>/dev/null`, which nobody writes on purpose). Linux only (it reads `/proc/self`);
/// elsewhere `None`. Computed once.
pub fn unusable_stdout() -> Option<&'static str> {
    static WHY: OnceLock<Option<&'static str>> = OnceLock::new();
    *WHY.get_or_init(|| {
        if !cfg!(target_os = "linux") {
            return None;
        }
        let flags = std::fs::read_to_string("/proc/self/fdinfo/1")
            .ok()
            .and_then(|info| {
                let flags = info.lines().find_map(|l| l.strip_prefix("flags:"))?;
                u32::from_str_radix(flags.trim(), 8).ok()
            })?;
        let null = std::fs::read_link("/proc/self/fd/1").is_ok_and(|p| p == Path::new("/dev/null"));
        match flags & 0o3 {
            0o2 if null => Some("closed"),
            0o0 => Some("open for reading only"),
            _ => None,
        }
    })
}

/// Write `text` to stdout and flush it.
pub fn print(text: &str) -> Result<(), Failure> {
    if READER_GONE.load(Ordering::Relaxed) {
        return Ok(());
    }
    if let Some(why) = unusable_stdout() {
        return Err(Failure::new(
            Exit::OutputFailed,
            format!("cannot write to stdout: it is {why}"),
        ));
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
