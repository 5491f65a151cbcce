//! The subcommands of `noslip`, one module each.

pub mod collide;
pub mod gen;
pub mod report;
pub mod simulate;
pub mod verify;

/// Exit codes shared by the subcommands (for `--help`).
pub const EXIT_CODES: &str = "\
Exit codes:
  0  success
  1  the output could not be written
  2  bad input or usage: the input file cannot be read, is not JSON, or a case is invalid
     (one line on stderr says which case, which field and what is wrong)";

/// The dimensions to run, `--dims 2..6` or `--dims 2,3,5`.
#[derive(Clone, Debug)]
pub struct Dims(pub Vec<usize>);

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
        (a..=b).collect()
    } else {
        s.split(',')
            .map(|x| x.trim().parse().map_err(|_| format!("bad dimension {x:?}")))
            .collect::<Result<_, _>>()?
    };
    if dims.is_empty() || dims.iter().any(|d| !(2..=6).contains(d)) {
        return Err(format!(
            "dimensions must be in 2..6 (the generated kernels), got {s:?}"
        ));
    }
    Ok(Dims(dims))
}
/// Print one line on stderr and return `code`.
pub fn fail(code: u8, message: &str) -> std::process::ExitCode {
    eprintln!("error: {}", message.replace(['\n', '\r'], " "));
    std::process::ExitCode::from(code)
}

/// Evaluate `$body` with const generics `N` (= `$dim`, 2..=6) and `S = N(N-1)/2` in scope.
macro_rules! with_dim {
    ($dim:expr, $f:ident ( $($arg:expr),* )) => {
        match $dim {
            2 => $f::<2, 1>($($arg),*),
            3 => $f::<3, 3>($($arg),*),
            4 => $f::<4, 6>($($arg),*),
            5 => $f::<5, 10>($($arg),*),
            6 => $f::<6, 15>($($arg),*),
            d => unreachable!("scene validation keeps dim in 2..=6, got {d}"),
        }
    };
}
pub(crate) use with_dim;
