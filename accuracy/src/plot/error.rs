//! A drawing's failure: plotters' error, kept as its message.

/// What a drawing returns: on failure, plotters' error as text.
pub(super) type Result<T> = std::result::Result<T, String>;

/// Plotters' error `e` as text.
pub(super) fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}
