//! # noslip-verify
//!
//! The exact verification of the generated kernels: proof-style checks run in exact rational
//! arithmetic ([`checks`], [`identities`], the Schwartz-Zippel degrees of [`degree`] over the
//! sample set of [`sample`]), the suite that runs them per dimension ([`suite`]), its report
//! and the golden comparison with a unified diff ([`report`], [`diff`]). It checks; it does not
//! measure speed or float error (that is `noslip-accuracy`) and writes no files (that is the
//! `noslip` command).

#![warn(missing_docs, unreachable_pub)]

pub mod checks;
pub mod degree;
pub mod diff;
pub mod identities;
pub mod report;
pub mod sample;
pub mod suite;
pub mod under_test;
