//! The log10 axes: a range of whole decades around the data, and the labels at the decades
//! (times in ns, us or ms as people write them; errors as `1e-16`), none between them.

/// The decades `[floor(log10 lo), ceil(log10 hi)]`, at least one wide.
pub(super) fn decades(lo: f64, hi: f64) -> (f64, f64) {
    let (a, b) = (lo.log10().floor(), hi.log10().ceil());
    (a, b.max(a + 1.0))
}

/// A time in ns at a decade, as people write it.
pub(super) fn time_label(log_ns: f64) -> String {
    if (log_ns - log_ns.round()).abs() > 1e-9 {
        return String::new();
    }
    match log_ns.round() as i32 {
        k @ 0..=2 => format!("{} ns", 10i64.pow(k as u32)),
        k @ 3..=5 => format!("{} us", 10i64.pow(k as u32 - 3)),
        k @ 6..=8 => format!("{} ms", 10i64.pow(k as u32 - 6)),
        k => format!("1e{k} ns"),
    }
}

/// An error at a decade, as `1e-16`.
pub(super) fn error_label(log_err: f64) -> String {
    if (log_err - log_err.round()).abs() > 1e-9 {
        return String::new();
    }
    format!("1e{}", log_err.round() as i32)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_cover_whole_decades_with_readable_labels() {
        assert_eq!(decades(2.3e-16, 0.4), (-16.0, 0.0));
        assert_eq!(decades(5.0, 5.0), (0.0, 1.0));
        assert_eq!(time_label(0.0), "1 ns");
        assert_eq!(time_label(4.0), "10 us");
        assert_eq!(time_label(6.0), "1 ms");
        assert_eq!(time_label(0.5), "");
        assert_eq!(error_label(-16.0), "1e-16");
        assert_eq!(error_label(-15.5), "");
    }
}
