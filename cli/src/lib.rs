//! # noslip
//!
//! The `noslip` command: collide two balls from a JSON case, prove the generated kernels
//! exact, measure their error against run time, run scenes, and print the kernels
//! specialised to a scene. It is thin: it parses arguments, reads the JSON case format
//! ([`json`], the `noslip-case` crate), calls the library crates (`collision-core`, `noslip-verify`,
//! `noslip-accuracy`, `noslip-sim`, `noslip-codegen`), and publishes their outputs atomically
//! ([`publish`]) with one table of exit codes ([`exit`]). It holds no physics, no checks and
//! no measurements of its own.
//!
//! One module per subcommand under [`command`]; a new subcommand is a variant of [`Command`],
//! its `Args` and `run`, and a line in [`run`].

#![warn(missing_docs, unreachable_pub)]

pub mod command;
pub mod dims;
pub mod exit;
/// The JSON case format (the `noslip-case` crate, shared with the Python package).
pub use noslip_case as json;
pub mod out;
pub mod progress;
pub mod publish;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// The command line: `noslip <subcommand> [args]`.
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
    after_long_help = exit::help(exit::ALL)
)]
pub struct Cli {
    /// The subcommand and its arguments.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Subcommand)]
pub enum Command {
    // A variant's doc comment is its `about` and would also replace the long help the
    // command's own module writes; `long_about` here puts that back.
    /// Collide two balls in contact: JSON cases in, post-collision states out.
    #[command(long_about = command::collide::LONG_ABOUT)]
    Collide(command::collide::Args),
    /// Prove the generated kernels exact: identities, decomposition, inertia; writes reports.
    #[command(long_about = command::verify::LONG_ABOUT)]
    Verify(command::verify::Args),
    /// Error against run time of every kernel variant, in typical and extreme regimes.
    #[command(long_about = command::report::LONG_ABOUT)]
    Report(command::report::Args),
    /// Run a scene: event-driven no-slip billiard / rough-ball gas; summary, log, plots.
    #[command(long_about = command::simulate::LONG_ABOUT)]
    Simulate(command::simulate::Args),
    /// Print the kernels specialised to a scene, with op counts (or check them exactly).
    #[command(long_about = command::gen::LONG_ABOUT)]
    Gen(command::gen::Args),
    /// Lyapunov exponents of a scene: tangent space with QR, or two trajectories.
    #[command(long_about = command::lyapunov::LONG_ABOUT)]
    Lyapunov(command::lyapunov::Args),
    /// Periodic orbits of a one-ball table's boundary map, with their linear stability.
    #[command(long_about = command::orbits::LONG_ABOUT)]
    Orbits(command::orbits::Args),
}

/// Run the parsed command line; the exit code of its outcome ([`exit::finish`]).
pub fn run(cli: Cli) -> ExitCode {
    exit::finish(match cli.command {
        Command::Collide(args) => command::collide::run(&args),
        Command::Verify(args) => command::verify::run(&args),
        Command::Report(args) => command::report::run(&args),
        Command::Simulate(args) => command::simulate::run(&args),
        Command::Gen(args) => command::gen::run(&args),
        Command::Lyapunov(args) => command::lyapunov::run(&args),
        Command::Orbits(args) => command::orbits::run(&args),
    })
}

/// End a command line the parser stopped at: a usage error is clap's (its message on stderr,
/// exit 2); help and version texts are printed through [`out::print`], so a stdout that
/// fails (`--help > /dev/full`, `>&-`) is one error line and exit 1, not a silent 0.
pub fn parse_stopped(e: clap::Error) -> ExitCode {
    if e.use_stderr() {
        e.exit();
    }
    let text = if std::io::IsTerminal::is_terminal(&std::io::stdout()) {
        e.render().ansi().to_string()
    } else {
        e.render().to_string()
    };
    match out::print(&text) {
        Ok(()) => ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(1)),
        Err(f) => exit::finish(Err(f)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory;

    /// Each subcommand's `--help` shows the long description its module writes, and its exit
    /// codes.
    #[test]
    fn each_subcommand_long_help_is_its_own() {
        let mut cli = Cli::command();
        for (name, long) in [
            ("collide", command::collide::LONG_ABOUT),
            ("verify", command::verify::LONG_ABOUT),
            ("report", command::report::LONG_ABOUT),
            ("simulate", command::simulate::LONG_ABOUT),
            ("gen", command::gen::LONG_ABOUT),
            ("lyapunov", command::lyapunov::LONG_ABOUT),
            ("orbits", command::orbits::LONG_ABOUT),
        ] {
            let help = cli
                .find_subcommand_mut(name)
                .expect("a subcommand")
                .render_long_help()
                .to_string();
            let first = long.lines().next().expect("a first line").trim();
            assert!(
                help.contains(first),
                "{name} --help lacks {first:?}:\n{help}"
            );
            assert!(
                help.contains("Exit codes:"),
                "{name} --help lacks its exit codes"
            );
        }
    }
}
