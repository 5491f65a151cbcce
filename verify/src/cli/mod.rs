//! The subcommands of `noslip`, one module each.

pub mod collide;
pub mod gen;
pub mod simulate;
pub mod verify;

/// Exit codes shared by the subcommands (for `--help`).
pub const EXIT_CODES: &str = "\
Exit codes:
  0  success
  1  the output could not be written
  2  bad input or usage: the input file cannot be read, is not JSON, or a case is invalid
     (one line on stderr says which case, which field and what is wrong)";

/// Print one line on stderr and return `code`.
pub fn fail(code: u8, message: &str) -> std::process::ExitCode {
    eprintln!("error: {}", message.replace(['\n', '\r'], " "));
    std::process::ExitCode::from(code)
}

/// Evaluate `$body` with const generics `N` (= `$dim`, 2..=6) and `S = N(N-1)/2` in scope.
macro_rules! with_dim {
    ($dim:expr, $f:ident ( $($arg:expr),* )) => {
        match $dim {
            2 => $f::<2, 1>($($arg),*),
            3 => $f::<3, 3>($($arg),*),
            4 => $f::<4, 6>($($arg),*),
            5 => $f::<5, 10>($($arg),*),
            6 => $f::<6, 15>($($arg),*),
            d => unreachable!("scene validation keeps dim in 2..=6, got {d}"),
        }
    };
}
pub(crate) use with_dim;
