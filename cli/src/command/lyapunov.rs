//! `noslip lyapunov FILE`: Lyapunov exponents of a scene's dynamics.

use crate::exit::{self, Exit, Failure};
use crate::out::outln;
use crate::publish::Staging;
use collision_core::Generated;
use noslip_dynamics::lyapunov::{
    choice, qr, two_trajectory, Dim, LyapunovError, Options, Spectrum,
};
use noslip_dynamics::Law;
use noslip_scene::Scene;
use noslip_sim::setup::setup;
use std::io::Write;
use std::path::{Path, PathBuf};

pub(crate) const LONG_ABOUT: &str = "\
Lyapunov exponents of a scene (TOML, see docs/scenes.md): a one-ball billiard or a gas, in
the phase space of the balls' centres, velocities and spins (orientations never feed back
and are left out; see docs/dynamics.md).

--method qr (default): the --k largest exponents from tangent vectors carried by the exact
flight and contact tangent maps along the engine's trajectory, re-orthonormalised
(Gram-Schmidt) every --every contacts (default: every contact for one ball, balls/4 for a
gas, shortened to a block's contacts; a longer --every is refused, as it would leave blocks
without an estimate). k vectors of the phase-space dimension d = balls x (2n + S) take 8 k d bytes, and each
re-orthonormalisation about k^2 d multiply-adds. Default --k: the whole spectrum (k = d) if
it fits 64 MiB of vectors and 2e9 multiply-adds of Gram-Schmidt over the
run (a few seconds), else the largest k that fits both, said on stderr. A --k whose vectors
pass 1 GiB is refused. --method two-trajectory: the largest exponent from a
second run kept 1e-9 away (Benettin), an independent check with no tangent map.

--events N contacts are run; the first of --blocks + 1 equal parts is a warm-up, the other
--blocks give the standard error (the spread of the blocks' estimates over sqrt(blocks)).
Exponents are given per unit time and per contact. Each contact follows its own kind from
the scene (contact = \"smooth\" or \"no-slip\" per wall, container, polygon, obstacle and
for ball pairs), in the trajectory and in the tangent map; --contact smooth (or no-slip)
overrides every contact's kind: smooth is the classical billiard, the Hamiltonian control.

Prints the spectrum with errors, its sum and the number of exponents below 1% of the largest,
and writes to --out (default out/lyapunov/SCENE), published as one set: spectrum.json (the
summary) and running.csv (the running estimate: contacts, time, exponents).";

/// The arguments of `noslip lyapunov`.
#[derive(clap::Args)]
#[command(long_about = LONG_ABOUT, after_long_help = exit::help(CODES))]
pub struct Args {
    /// The scene file.
    pub file: PathBuf,
    /// Contacts to run (warm-up included).
    #[arg(long, default_value_t = 100_000)]
    events: u64,
    /// The number of exponents, largest first (qr; default all).
    #[arg(long)]
    k: Option<usize>,
    /// `qr` or `two-trajectory`.
    #[arg(long, default_value = "qr")]
    method: String,
    /// Seed of the initial tangent vectors or perturbation.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Measured blocks for the standard error (after a warm-up block), at most 10000.
    #[arg(long, default_value_t = 10)]
    blocks: usize,
    /// Contacts between re-orthonormalisations (default: the method's).
    #[arg(long)]
    every: Option<u64>,
    /// Override every contact's law: `no-slip` or `smooth` (default: each contact's kind
    /// from the scene).
    #[arg(long)]
    contact: Option<String>,
    /// The output directory (default out/lyapunov/SCENE).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// What `lyapunov` can return.
pub const CODES: &[Exit] = &[Exit::Success, Exit::OutputFailed, Exit::BadInput];

/// The contact law named by `--contact`.
pub fn parse_law(s: &str) -> Result<Law, Failure> {
    match s {
        "no-slip" => Ok(Law::NoSlip),
        "smooth" => Ok(Law::Smooth),
        _ => Err(Failure::bad_input(format!(
            "--contact: must be no-slip or smooth, got {s:?}"
        ))),
    }
}

/// The run's options from the arguments (and whether the method is `two-trajectory`); a bad
/// option exits 2 naming it.
pub fn options(args: &Args) -> Result<(Options, bool), Failure> {
    let two = match args.method.as_str() {
        "qr" => false,
        "two-trajectory" => true,
        m => {
            return Err(Failure::bad_input(format!(
                "--method: must be qr or two-trajectory, got {m:?}"
            )))
        }
    };
    if args.every == Some(0) {
        return Err(Failure::bad_input("--every: must be at least 1"));
    }
    if two && args.k.is_some_and(|k| k != 1) {
        return Err(Failure::bad_input(
            "--k: two-trajectory gives the largest exponent only (--k 1)",
        ));
    }
    Ok((
        Options {
            events: args.events,
            k: args.k,
            blocks: args.blocks,
            seed: args.seed,
            law: args.contact.as_deref().map(parse_law).transpose()?,
            every: args.every,
        },
        two,
    ))
}

fn spectrum<const N: usize, const S: usize>(
    scene: &Scene,
    options: &Options,
    two: bool,
) -> Result<Spectrum, Failure>
where
    Generated: Dim<N, S>,
{
    let setup =
        setup::<N, S>(scene).map_err(|e| Failure::bad_input(format!("{}: {e}", scene.origin)))?;
    let result = if two {
        two_trajectory(setup, options)
    } else {
        // What the default --k chose (or what a large --k costs), before the run.
        if let Some(note) = choice(&setup, options).ok().and_then(|c| c.note()) {
            let _ = writeln!(std::io::stderr(), "note: {note}");
        }
        qr(setup, options)
    };
    result.map_err(|e| match e {
        LyapunovError::Setup(_) => Failure::bad_input(format!("{}: {e}", scene.origin)),
        LyapunovError::K { .. }
        | LyapunovError::Memory { .. }
        | LyapunovError::Blocks { .. }
        | LyapunovError::Events { .. }
        | LyapunovError::Every { .. }
        | LyapunovError::Overflow { .. } => Failure::bad_input(e.to_string()),
        _ => Failure::bad_input(format!("{}: {e}", scene.origin)),
    })
}

/// The running estimate as CSV: `contacts,time,lambda_1,..`.
pub fn running_csv(s: &Spectrum) -> String {
    let k = s.per_time.len();
    let mut text = String::from("contacts,time");
    for i in 1..=k {
        text.push_str(&format!(",lambda_{i}"));
    }
    text.push('\n');
    for r in &s.running {
        text.push_str(&format!("{},{:e}", r.contacts, r.time));
        for x in &r.exponents {
            text.push_str(&format!(",{x:e}"));
        }
        text.push('\n');
    }
    text
}

/// Read the scene, run the method, publish and print.
pub fn run(args: &Args) -> Result<Exit, Failure> {
    let (options, two) = options(args)?;
    let scene = Scene::from_file(&args.file).map_err(|e| Failure::bad_input(e.to_string()))?;
    if scene.thermostat.is_some() {
        return Err(Failure::bad_input(format!(
            "{}: thermostat: a driven gas's random kicks have no tangent map here: lyapunov \
             takes undriven scenes",
            scene.origin
        )));
    }
    let s = collision_core::with_dim!(
        scene.dim,
        |N, S| spectrum::<N, S>(&scene, &options, two),
        unreachable!("scene validation keeps dim in {:?}", collision_core::DIMS)
    )?;
    let out = args.out.clone().unwrap_or_else(|| {
        let stem = Path::new(&scene.origin)
            .file_stem()
            .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
        PathBuf::from("out/lyapunov").join(stem)
    });
    let mut set = Staging::new(&out).map_err(|e| exit::publish_failure(&e))?;
    let mut summary = serde_json::to_value(&s).expect("spectrum serialises");
    summary
        .as_object_mut()
        .expect("an object")
        .remove("running");
    let json = serde_json::to_string_pretty(&summary).expect("serialises") + "\n";
    set.write("spectrum.json", json.as_bytes())
        .map_err(|e| exit::publish_failure(&e))?;
    set.write("running.csv", running_csv(&s).as_bytes())
        .map_err(|e| exit::publish_failure(&e))?;
    set.commit().map_err(|e| exit::publish_failure(&e))?;
    outln!(
        "{}: {} exponent{} by {} ({} contacts), phase-space dimension {}; {} contacts \
         (warm-up {}), measured time {:.6}, renormalised every {} contact{}",
        scene.origin,
        s.per_time.len(),
        if s.per_time.len() == 1 { "" } else { "s" },
        s.method,
        args.contact
            .as_deref()
            .map_or("the scene's kinds of".to_string(), |c| format!("all {c}")),
        s.dimension,
        s.contacts,
        s.warmup,
        s.time,
        s.every,
        if s.every == 1 { "" } else { "s" }
    )?;
    outln!("  i   per unit time              per contact")?;
    for (i, (t, c)) in s.per_time.iter().zip(&s.per_contact).enumerate() {
        outln!(
            "{:>3}   {:+.6e} ± {:.1e}   {:+.6e} ± {:.1e}",
            i + 1,
            t.value,
            t.error,
            c.value,
            c.error
        )?;
    }
    if s.per_time.len() == s.dimension {
        let top = s.per_time[0].value.abs();
        let zeros = s
            .per_time
            .iter()
            .filter(|e| e.value.abs() < 0.01 * top)
            .count();
        outln!(
            "sum {:+.3e} ± {:.1e} (0 by volume preservation); {} below 1% of the largest",
            s.sum.value,
            s.sum.error,
            zeros
        )?;
    }
    outln!("wrote {}", out.display())?;
    Ok(Exit::Success)
}

#[cfg(test)]
mod tests {
    use super::LONG_ABOUT;
    use noslip_dynamics::lyapunov::cost::{DEFAULT_TANGENT_BYTES, DEFAULT_WORK, MAX_TANGENT_BYTES};

    /// The help states the budgets the code applies.
    #[test]
    fn the_help_states_the_budgets() {
        let about = LONG_ABOUT.replace('\n', " ");
        assert!(about.contains(&format!("fits {} MiB", DEFAULT_TANGENT_BYTES >> 20)));
        assert!(about.contains(&format!("and {DEFAULT_WORK:.0e} multiply-adds")));
        assert!(about.contains(&format!("pass {} GiB is refused", MAX_TANGENT_BYTES >> 30)));
    }
}
