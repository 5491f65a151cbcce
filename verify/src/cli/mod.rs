//! The subcommands of `noslip`, one module each.

pub mod collide;
pub mod verify;

/// Exit codes shared by the subcommands (for `--help`).
pub const EXIT_CODES: &str = "\
Exit codes:
  0  success
  1  the output could not be written
  2  bad input or usage: the input file cannot be read, is not JSON, or a case is invalid
     (one line on stderr says which case, which field and what is wrong)";
