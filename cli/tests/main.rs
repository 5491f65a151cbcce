//! The command's integration tests, one module a file, compiled as one test binary (one
//! link instead of one per file): `cargo test -p noslip --test cli MODULE::` runs one
//! file's tests.

mod support;

mod c_recipe;
mod cli_collide;
mod cli_collide_rough;
mod cli_counts;
mod cli_driven;
mod cli_gen;
mod cli_granular;
mod cli_html;
mod cli_lyapunov;
mod cli_orbits;
mod cli_outputs;
mod cli_pair_laws;
mod cli_parquet;
mod cli_simulate;
mod cli_tables;
mod collide_below_range;
mod collide_range;
mod faults;
