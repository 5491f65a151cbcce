//! `noslip simulate`: a scene's setup ([`setup`]), the run loop with its log and summary
//! ([`run`]) and the pictures ([`plot`]).

pub mod plot;
pub mod run;
pub mod setup;
