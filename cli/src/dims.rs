//! The `--dims` option of `verify` and `report`: which dimensions to run.

/// The dimensions to run, `--dims 2..6` or `--dims 2,3,5`: in increasing order, each once.
#[derive(Clone, Debug)]
pub struct Dims(pub Vec<usize>);

/// Parse `--dims`: a range `a..b` (or `a..=b`) or a list `a,b,c`, each a dimension with
/// generated kernels ([`collision_core::DIMS`]).
pub fn parse_dims(s: &str) -> Result<Dims, String> {
    let dims: Vec<usize> = if let Some((a, b)) = s.split_once("..") {
        let a: usize = a
            .trim()
            .parse()
            .map_err(|_| format!("bad range start in {s:?}"))?;
        let b: usize = b
            .trim_start_matches('=')
            .trim()
            .parse()
            .map_err(|_| format!("bad range end in {s:?}"))?;
        // Bounded before it is expanded: `--dims 0..1000000000000` is refused, not allocated.
        if !(collision_core::DIMS.contains(&a) && collision_core::DIMS.contains(&b)) {
            return Err(out_of_range(s));
        }
        if a > b {
            return Err(format!(
                "the range {s:?} runs backwards: write it from the lower dimension up ({b}..{a})"
            ));
        }
        (a..=b).collect()
    } else {
        s.split(',')
            .map(|x| x.trim().parse().map_err(|_| format!("bad dimension {x:?}")))
            .collect::<Result<_, _>>()?
    };
    if dims.is_empty() || dims.iter().any(|d| !collision_core::DIMS.contains(d)) {
        return Err(out_of_range(s));
    }
    let mut dims = dims;
    dims.sort_unstable();
    dims.dedup();
    Ok(Dims(dims))
}

fn out_of_range(s: &str) -> String {
    format!("dimensions must be in 2..6 (the generated kernels), got {s:?}")
}

#[cfg(test)]
mod tests {
    use super::parse_dims;

    #[test]
    fn ranges_and_lists_in_increasing_order_each_once() {
        assert_eq!(parse_dims("2..6").unwrap().0, vec![2, 3, 4, 5, 6]);
        assert_eq!(parse_dims("3..=4").unwrap().0, vec![3, 4]);
        assert_eq!(parse_dims("5, 2,5").unwrap().0, vec![2, 5]);
    }

    #[test]
    fn a_backward_range_is_refused_as_such() {
        for bad in ["6..2", "3..=2"] {
            let e = parse_dims(bad).unwrap_err();
            assert!(e.contains("runs backwards"), "{bad}: {e}");
        }
    }

    #[test]
    fn out_of_range_and_huge_ranges_are_refused_not_expanded() {
        for bad in [
            "1..3",
            "2..7",
            "0..18446744073709551615",
            "7",
            "",
            "2,x",
            "6..2",
        ] {
            assert!(parse_dims(bad).is_err(), "{bad:?}");
        }
    }
}
