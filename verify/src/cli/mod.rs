//! The subcommands of `noslip`, one module each.

pub mod collide;
pub mod exit;
pub mod gen;
pub mod out;
pub mod progress;
pub mod report;
pub mod simulate;
pub mod verify;

use exit::{Exit, Failure};
use noslip_verify::publish::PublishError;

/// The `Exit codes:` section of `collide --help` (rendered from [`exit::Exit`]).
pub const EXIT_CODES: exit::Codes =
    exit::Codes(&[Exit::Success, Exit::OutputFailed, Exit::BadInput]);

/// A publishing error as a failure: a directory that is not noslip's is bad usage of --out.
pub fn publish_failure(e: &PublishError) -> Failure {
    match e {
        PublishError::NotOurs(_) => Failure::bad_input(format!("--out: {e}")),
        PublishError::Io { .. } => Failure::output(format!("cannot write the output: {e}")),
    }
}

/// The dimensions to run, `--dims 2..6` or `--dims 2,3,5`: in increasing order, each once.
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
    let mut dims = dims;
    dims.sort_unstable();
    dims.dedup();
    Ok(Dims(dims))
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
