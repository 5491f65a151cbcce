//! `noslip collide [--exact] [FILE]`: JSON cases in, post-collision states out.

use noslip_verify::json::case::MAX_DIM;
use noslip_verify::json::number::MAX_EXACT_EXPONENT;
use noslip_verify::json::{collide_json, Mode};
use std::io::{Read, Write};
use std::path::PathBuf;
use std::process::ExitCode;

const ABOUT: &str = "Collide two balls in contact: JSON cases in, post-collision states out";

const LONG_ABOUT: &str = "\
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
  Unknown keys are errors. The bodies must approach or graze: (u_2 - u_1) . nu <= 0. At
  most one body may be immovable, and at most one movable body a point mass (lambda = 0).

Numbers:
  A JSON number, or a string holding a decimal (\"0.1\", \"1e-3\", \"-2.5E+3\") or a rational
  (\"3/5\", \"-7/2\"). The text is read as written: a JSON number 0.1 is also 1/10. NaN and
  infinities are rejected; \"inf\" is allowed for mass only.

Modes:
  (default)  f64. Each number is rounded once to the nearest f64 (a rational as the exact
             quotient, rounded). nu must be unit within | |nu|^2 - 1 | <= 2e-12, U skew
             within 1e-12 max|U| (its skew part is used); lambda and gamma2 may exceed
             their bound by 8 ulps (a shell written in decimal). Numbers beyond the f64
             range are errors. Output: JSON numbers in Rust's shortest round-trip form,
             integers with a trailing .0 (2.0, -0.0, 0.1, 1e-300, 1.5e+300); reading
             them back as f64 gives the computed values exactly.
  --exact    Exact rationals: no rounding anywhere. nu must be exactly unit (use rationals
             such as 3/5, 4/5) and U exactly skew; decimal exponents are limited to
             |e| <= {MAX_EXACT_EXPONENT}. Output: reduced rationals as strings (\"-3/5\", \"2\").

Output (one line per input):
  {{\"bodies\": [{{\"angular_velocity\": [[..], ..], \"velocity\": [..]}}, {{..}}]}}

Dimensions:
  2..=6      the generated kernels (the same generic code in f64 and in --exact)
  7..={MAX_DIM}     the general-n reference (the reflection built from its definition: an
             impulse basis, a Gram matrix and a linear solve); slower, and it needs
             lambda > 0 for each movable body

{}",
        super::EXIT_CODES
    )
}

#[derive(clap::Args)]
#[command(about = ABOUT, long_about = LONG_ABOUT, after_long_help = after_long_help())]
pub struct Args {
    /// Compute in exact rational arithmetic (default: f64)
    #[arg(long)]
    pub exact: bool,

    /// The input file (a case or an array of cases); stdin when absent or "-"
    pub file: Option<PathBuf>,
}

fn read_input(file: Option<&PathBuf>) -> Result<String, String> {
    match file {
        Some(path) if path.as_os_str() != "-" => std::fs::read_to_string(path)
            .map_err(|e| format!("cannot read {}: {e}", path.display())),
        _ => {
            let mut text = String::new();
            std::io::stdin()
                .read_to_string(&mut text)
                .map_err(|e| format!("cannot read stdin: {e}"))?;
            Ok(text)
        }
    }
}

fn fail(code: u8, message: &str) -> ExitCode {
    // A message is one line; a path with a line break must not break that.
    eprintln!("error: {}", message.replace(['\n', '\r'], " "));
    ExitCode::from(code)
}

pub fn run(args: &Args) -> ExitCode {
    let input = match read_input(args.file.as_ref()) {
        Ok(text) => text,
        Err(m) => return fail(2, &m),
    };
    let mode = if args.exact { Mode::Exact } else { Mode::Float };
    let output = match collide_json(&input, mode) {
        Ok(out) => out,
        Err(e) => return fail(2, &e.to_string()),
    };
    let mut stdout = std::io::stdout().lock();
    match writeln!(stdout, "{output}").and_then(|()| stdout.flush()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(1, &format!("cannot write the output: {e}")),
    }
}
