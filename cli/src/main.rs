//! `noslip`: collide two balls from JSON, verify and measure the kernels, run scenes. The
//! command lives in the `noslip` library ([`noslip::Cli`], [`noslip::run`]).

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    match noslip::Cli::try_parse() {
        Ok(cli) => noslip::run(cli),
        Err(e) => noslip::parse_stopped(e),
    }
}
