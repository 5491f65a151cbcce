//! `noslip`: collide two balls from JSON, verify and measure the kernels, run scenes. The
//! command lives in the `noslip` library ([`noslip::Cli`], [`noslip::run`]).

use clap::Parser;
use std::process::ExitCode;

/// Large arrays (the engine's records at many balls) on 2 MiB pages
/// (`noslip_sim::huge_pages`; measured in docs/benchmarks.md, "Huge pages").
#[global_allocator]
static ALLOC: noslip_sim::huge_pages::HugePages = noslip_sim::huge_pages::HugePages;

fn main() -> ExitCode {
    match noslip::Cli::try_parse() {
        Ok(cli) => noslip::run(cli),
        Err(e) => noslip::parse_stopped(e),
    }
}
