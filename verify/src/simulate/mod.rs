//! `noslip simulate`: a scene's setup ([`setup`]) after the range checks of the scene in f64
//! ([`range`]), with random placement on a cell grid ([`place`]); the run loop with its log
//! and summary ([`run`]), the events log file ([`log`]), the traced paths ([`trace`]) and the
//! pictures ([`plot`]).

pub mod log;
pub mod place;
pub mod plot;
pub mod range;
pub mod run;
pub mod setup;
pub mod trace;
