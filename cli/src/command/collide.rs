//! `noslip collide [--exact] [FILE]`: JSON cases in, post-collision states out.

use crate::exit::{Exit, Failure};
use crate::json::case::MAX_DIM;
use crate::json::number::{MAX_DIGITS, MAX_EXACT_EXPONENT};
use crate::json::{collide_json, Mode};
use std::io::{Read, Write};
use std::path::PathBuf;

const ABOUT: &str = "Collide two balls in contact: JSON cases in, post-collision states out";

pub(crate) const LONG_ABOUT: &str = "\
Collide two balls in contact. Reads a case (or a JSON array of cases) from FILE or stdin \
and prints the post-collision states as JSON on one line, in the same order: an array \
gives an array, a single case a single object. On the first invalid case nothing is \
printed; one line on stderr names the case (0-based), the field and what is wrong.";

/// The help after the options: schema, numbers, modes, output, dimensions, exit codes.
fn after_long_help() -> String {
    format!(
        "\
Input (one case; body 1 of the formulas is bodies[0], body 2 is bodies[1]):
  {{\"dim\": 3,
   \"normal\": [\"0\", \"3/5\", \"4/5\"],
   \"bodies\": [
     {{\"mass\": \"2\", \"radius\": \"1\", \"lambda\": \"1/5\",
      \"angular_velocity\": [[\"0\",\"1\",\"-2\"], [\"-1\",\"0\",\"3\"], [\"2\",\"-3\",\"0\"]],
      \"velocity\": [\"1\",\"0\",\"1/2\"]}},
     {{\"mass\": \"inf\", \"radius\": \"3/2\", \"gamma2\": \"2/5\",
      \"angular_velocity\": [[\"0\",\"0\",\"0\"], [\"0\",\"0\",\"0\"], [\"0\",\"0\",\"0\"]],
      \"velocity\": [\"0\",\"0\",\"0\"]}}]}}

  dim               an integer n, 2 <= n <= {MAX_DIM}
  normal            the unit vector nu from the centre of bodies[0] to that of bodies[1]
  bodies            exactly two bodies, each with the keys
    mass            a positive number, or \"inf\": an immovable body (returned unchanged)
    radius          R, a positive number
    lambda          (1/(n m)) int |b|^2 dmu(b), in [0, R^2/n] (0: a point mass)
    gamma2          2 lambda / R^2, in [0, 2/n] (in 3D I/(m R^2): 2/5 for a solid ball)
    distribution    \"uniform\" (lambda = R^2/(n+2)) or \"shell\" (lambda = R^2/n)
                    (at most one of lambda, gamma2, distribution; none means uniform)
    angular_velocity
                    U, the n x n skew matrix, row by row (the body point x moves with
                    U (x - a) + u, a the centre); in 2D also a number c (U = c J,
                    J = [[0,-1],[1,0]]); in 3D also a 3-vector omega (U x = omega x x).
                    The output uses the same form, per body.
    velocity        u, the centre velocity: n numbers
  contact           optional, the contact law (docs/derivation.md §15): \"no-slip\" (the
                    default), \"smooth\" (specular), or {{\"e\": .., \"beta\": ..}}, the
                    rough-ball law: the normal slip of the contact point becomes -e times
                    itself (e in [0, 1]) and its tangential slip -beta times itself (beta in
                    [-1, 1]); (1, 1) is no-slip, (1, -1) smooth. Or {{\"e\": .., \"mu\": ..,
                    \"beta0\": ..}}, the Walton law (§15.1): beta = min(beta0, beta_C), beta_C
                    the beta of sliding at |J_t| = mu |J_n| (mu >= 0, beta0 in [-1, 1]).
                    dim 2..=6 only.
  Unknown keys and keys given twice are errors. The bodies must approach or graze:
  (u_2 - u_1) . nu <= 0. At most one body may be immovable, and at most one movable body a
  point mass (lambda = 0).

Numbers:
  A JSON number, or a string holding a decimal (\"0.1\", \"1e-3\", \"-2.5E+3\") or a rational
  (\"3/5\", \"-7/2\"). The text is read as written: a JSON number 0.1 is also 1/10. NaN and
  infinities are rejected; \"inf\" is allowed for mass only. A number has at most
  {MAX_DIGITS} digits (a decimal's mantissa, or a rational's numerator and denominator
  together): at that size a 6D case takes about 2 ms of CPU in --exact.

Modes:
  (default)  f64. Each number is rounded once to the nearest f64 (a rational as the exact
             quotient, rounded); numbers beyond the f64 range are errors. Below the
             normal range (|x| < 2.2e-308) a number keeps fewer digits: a mass, radius,
             lambda or gamma2 there is an error; a velocity or angular velocity entry
             there is taken while its rounding (at most 2^-1075, times R for a spin
             entry) is within eps/2 of the contact's speed scale max(|u_i|, R_i |U_i|),
             an error naming it otherwise.
             The rounding allowance: a quantity that misses its bound by rounding, by at
             most 8 eps (eps = 2^-52) of its scale, is accepted and clamped to the bound:
               lambda in [0, R^2/n]   scale R^2/n   set to the bound
               gamma2 in [0, 2/n]     scale 2/n     set to the bound (also 2 lambda/R^2)
               |nu|^2 = 1             scale |nu|^2  nu renormalised; (8 + 2n) eps, the
                                      rounding of d/|d| in n dimensions
               U skew                 scale max|U|  its skew part (U - U^T)/2 used
               (u_2 - u_1) . nu <= 0  scale sum_k |nu_k| (|u_1k| + |u_2k|)
                                      grazing: the normal part of u_2 - u_1 removed,
                                      momentum kept
             Beyond the allowance these are errors.
             The kernel computes with an unbounded exponent: no intermediate quantity
             overflows or underflows, so any magnitudes (1e-300 .. 1e300 in any field)
             give the f64 kernel's accuracy. A case whose answer does not fit f64 (a
             component beyond 1.8e308, or a body's answer whose components below the
             normal range, 2.2e-308, would cost more than 8 eps of its energy norm
             sqrt(gamma2 R^2 |U|^2 + |u|^2)) is an error naming the component and the
             input that drives it; --exact computes it.
             Output: JSON numbers in Rust's shortest round-trip form, integers with a
             trailing .0 (2.0, -0.0, 0.1, 1e-300, 1.5e+300); reading them back as f64
             gives the computed values exactly.
  --exact    Exact rationals: no rounding and no allowance anywhere. nu must be exactly
             unit (use rationals such as 3/5, 4/5) and U exactly skew; decimal exponents
             are limited to |e| <= {MAX_EXACT_EXPONENT}. Output: reduced rationals as strings
             (\"-3/5\", \"2\").

Output (one line per input):
  {{\"bodies\": [{{\"angular_velocity\": [[..], ..], \"velocity\": [..]}}, {{..}}]}}

Dimensions:
  2..=6      the generated kernels (the same generic code in f64 and in --exact)
  7..={MAX_DIM}     the general-n reference (the reflection built from its definition: an
             impulse basis, a Gram matrix and a linear solve); slower, and it needs
             lambda > 0 for each movable body. In --exact its cost grows fast with n
             and with the size of the numbers: at n = 16, 4 s with 17-digit rationals,
             34 s with 50 digits, 75 s with exponents near 1000

{}",
        crate::exit::COLLIDE_CODES
    )
}

/// The arguments of `noslip collide`.
#[derive(clap::Args)]
#[command(about = ABOUT, long_about = LONG_ABOUT, after_long_help = after_long_help())]
pub struct Args {
    /// Compute in exact rational arithmetic (default: f64)
    #[arg(long)]
    pub exact: bool,

    /// The input file (a case or an array of cases); stdin when absent or "-"
    pub file: Option<PathBuf>,
}

/// The largest input `collide` reads (a case or an array of cases), 16 MiB: about 45,000
/// cases of `examples/case.json`'s size. Parsing holds about 32 times the input (JSON values
/// with arbitrary-precision numbers: 520 MB for 16 MB of `[0,0,...]`, 207 MB for 6.9 MiB of
/// cases), so a run stays near 0.5 GB; a larger input is refused before it is read whole.
/// More cases: several files, or the Python package's `collide_batch`.
pub const MAX_INPUT_BYTES: u64 = 16 << 20;

fn read_input(file: Option<&PathBuf>) -> Result<String, String> {
    match file {
        Some(path) if path.as_os_str() != "-" => {
            let what = path.display().to_string();
            let f = std::fs::File::open(path).map_err(|e| format!("cannot read {what}: {e}"))?;
            read_limited(f, &what)
        }
        _ => read_limited(std::io::stdin().lock(), "stdin"),
    }
}

/// All of `input` as text, refused beyond [`MAX_INPUT_BYTES`] (it reads one byte more to
/// know).
fn read_limited(input: impl Read, what: &str) -> Result<String, String> {
    let mut bytes = Vec::new();
    input
        .take(MAX_INPUT_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot read {what}: {e}"))?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(format!(
            "{what}: larger than {} MiB, the limit of an input (split the cases into several \
             files)",
            MAX_INPUT_BYTES >> 20
        ));
    }
    String::from_utf8(bytes)
        .map_err(|_| format!("cannot read {what}: stream did not contain valid UTF-8"))
}

/// Write the answer and a newline to stdout, all of it, or say why not (a closed stdout, a
/// broken pipe, a full disk).
fn write_answer(answer: &str) -> std::io::Result<()> {
    if let Some(why) = crate::out::unusable_stdout() {
        return Err(std::io::Error::new(
            std::io::ErrorKind::BrokenPipe,
            format!("stdout is {why}"),
        ));
    }
    let mut stdout = std::io::stdout().lock();
    stdout.write_all(answer.as_bytes())?;
    stdout.write_all(b"\n")?;
    stdout.flush()
}

/// Read the case, collide, print the answer.
pub fn run(args: &Args) -> Result<Exit, Failure> {
    let input = read_input(args.file.as_ref()).map_err(Failure::bad_input)?;
    let mode = if args.exact { Mode::Exact } else { Mode::Float };
    let answer = collide_json(&input, mode).map_err(|e| Failure::bad_input(e.to_string()))?;
    write_answer(&answer).map_err(|e| Failure::output(format!("cannot write the output: {e}")))?;
    Ok(Exit::Success)
}
