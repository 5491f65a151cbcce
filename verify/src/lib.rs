//! The `noslip` command's library: the JSON side of `collide` ([`json`]) and the exact
//! verification of the generated kernels ([`checks`], [`report`]), and error against run
//! time ([`accuracy`]).

pub mod json;

pub mod accuracy;

pub mod checks;
pub mod degree;
pub mod diff;
pub mod identities;
pub mod kernel;
pub mod publish;
pub mod report;
pub mod run;
pub mod sample;
pub mod simulate;
