//! `noslip`: collide two balls from JSON, verify and measure the kernels, run scenes.
//!
//! One module per subcommand under `cli/`; a new subcommand is a variant of [`Command`],
//! its `Args`, and a line in `main`.
//!
//! `Cli`, `Command` and `cli` are `pub(crate)` for the fuzz target `cli_args`
//! (fuzz/fuzz_targets/cli_args.rs), which compiles this file as a module of its own crate.

pub(crate) mod cli;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "noslip",
    version,
    about = "No-slip collisions of two rigid balls in R^n",
    long_about = "No-slip collisions of two rigid balls in R^n.\n\n\
        At contact, the state of two balls (angular velocities U_i in so(n), centre \
        velocities u_i) jumps to its reflection, in the kinetic-energy metric, across the \
        no-slip subspace {V_1(Q) = V_2(Q)}: the map is linear, an involution, and conserves \
        energy, linear momentum and each body's angular momentum about the contact point. \
        The kernels for n = 2..6 are generated code, run in f64 or in exact rationals.",
    after_long_help = cli::exit::help(cli::exit::ALL)
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    Collide(cli::collide::Args),
    /// Prove the generated kernels exact: identities, decomposition, inertia; writes reports.
    Verify(cli::verify::Args),
    /// Error against run time of every kernel variant, in typical and extreme regimes.
    Report(cli::report::Args),
    /// Run a scene: event-driven no-slip billiard / rough-ball gas; summary, log, plots.
    Simulate(cli::simulate::Args),
    /// Print the kernels specialised to a scene, with op counts (or check them exactly).
    Gen(cli::gen::Args),
}

fn main() -> ExitCode {
    match Cli::parse().command {
        Command::Collide(args) => cli::collide::run(&args),
        Command::Verify(args) => cli::exit::finish(cli::verify::run_cmd(&args)),
        Command::Report(args) => cli::exit::finish(cli::report::run_cmd(&args)),
        Command::Simulate(args) => cli::simulate::run_cmd(&args),
        Command::Gen(args) => cli::exit::finish(cli::gen::run(&args)),
    }
}
