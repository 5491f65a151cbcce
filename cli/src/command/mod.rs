//! The subcommands of `noslip`, one module each: its `Args` (clap) and its `run`, which
//! returns the outcome that [`crate::exit::finish`] turns into the exit code.

pub mod collide;
pub mod gen;
pub mod lyapunov;
pub mod orbits;
pub mod report;
pub mod simulate;
pub mod verify;
