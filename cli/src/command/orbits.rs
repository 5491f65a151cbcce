//! `noslip orbits FILE --period K`: periodic orbits of a one-ball table's boundary map.

use crate::command::lyapunov::parse_law;
use crate::exit::{self, Exit, Failure};
use crate::out::outln;
use crate::publish::Staging;
use collision_core::Exact;
use noslip_dynamics::orbits::search::{search, Search, SearchError};
use noslip_scene::{parse_exact, Scene};
use std::path::{Path, PathBuf};

pub(crate) const LONG_ABOUT: &str = "\
Periodic orbits of the K-th return map of the boundary map of a one-ball table (a scene with
one [[ball]]: walls of the box, fixed ball obstacles, periodic axes, and the table's walls,
containers, polygon tables, wedges and polygon obstacles). Each contact follows its
boundary's kind in the scene (contact = \"smooth\" or \"no-slip\"); --contact overrides
every contact's kind. The section is the state
just after a contact: the centre on a boundary, the velocity and the spin, [x, u, U] (2n + S
numbers).

Orbits are found by Newton's method on P^K(z) - z with the exact derivative (the flight and
contact tangent maps, projected onto the section), a least-norm step (the velocity scaling
and translations are neutral) and the energy fixed at the start's. Starts: each --from STATE
(2n + S numbers separated by commas: rationals such as 1/2 or decimals, moved along the
normal onto the nearest boundary), or --grid M (2D: M points on each boundary x M outgoing
angles x M spins, at unit speed), or by default the scene's ball after its first contact.

Each orbit is reported once (orbits found from several starts are merged): its contact
sequence (boundary indices: walls 2k and 2k+1 at x_k = 0 and L_k for each walled axis k in
order, then the obstacles, then the table's boundaries in the scene's order: walls, the
polygon's or wedge's walls, containers, each polygon obstacle's edges then vertices), its start, the eigenvalues of the linearised return map on the
section and the verdict: elliptic (all on the unit circle, some non-real), parabolic (all at
+-1) or hyperbolic (some off the unit circle), with tolerance 1e-6. For a rational --from on
a table whose contact times are rational (flat walls whose normals have rational length),
the return map at that start and the
characteristic polynomial of its linearisation are also computed in exact rationals.
Writes orbits.json to --out (default out/orbits/SCENE), published as one set.";

/// The arguments of `noslip orbits`.
#[derive(clap::Args)]
#[command(long_about = LONG_ABOUT, after_long_help = exit::help(CODES))]
pub struct Args {
    /// The scene file.
    pub file: PathBuf,
    /// The period K (contacts per orbit).
    #[arg(long)]
    period: usize,
    /// A start `[x, u, U]`, 2n + S numbers separated by commas (repeatable).
    #[arg(long, allow_negative_numbers = true)]
    from: Vec<String>,
    /// 2D: M^3 starts per boundary (positions x angles x spins).
    #[arg(long)]
    grid: Option<usize>,
    /// Override every contact's law: `no-slip` or `smooth` (default: each boundary's kind
    /// from the scene).
    #[arg(long)]
    contact: Option<String>,
    /// The output directory (default out/orbits/SCENE).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// What `orbits` can return.
pub const CODES: &[Exit] = &[Exit::Success, Exit::OutputFailed, Exit::BadInput];

fn parse_start(i: usize, text: &str) -> Result<Vec<Exact>, Failure> {
    text.split(',')
        .enumerate()
        .map(|(k, p)| {
            parse_exact(p)
                .map(|x| Exact::from_fraction(&x))
                .map_err(|e| Failure::bad_input(format!("--from[{i}][{k}]: {e}")))
        })
        .collect()
}

/// The search's error as the command's: its field is the option of the same name.
fn failure(e: SearchError) -> Failure {
    match e.field() {
        Some(field) => Failure::bad_input(format!("--{field}: {}", e.message())),
        None => Failure::bad_input(e.message()),
    }
}

fn show(v: &[f64]) -> String {
    v.iter()
        .map(|x| format!("{x:.12}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// Check the arguments, search, publish and print.
pub fn run(args: &Args) -> Result<Exit, Failure> {
    let law = args.contact.as_deref().map(parse_law).transpose()?;
    let from = args
        .from
        .iter()
        .enumerate()
        .map(|(i, text)| parse_start(i, text))
        .collect::<Result<Vec<_>, _>>()?;
    let ask = Search {
        period: args.period,
        from,
        grid: args.grid,
        law,
    };
    let scene = Scene::from_file(&args.file).map_err(|e| Failure::bad_input(e.to_string()))?;
    let report = collision_core::with_dim!(
        scene.dim,
        |N, S| search::<N, S>(&scene, &ask).map_err(failure),
        unreachable!("scene validation keeps dim in {:?}", collision_core::DIMS)
    )?;
    let out = args.out.clone().unwrap_or_else(|| {
        let stem = Path::new(&scene.origin)
            .file_stem()
            .map_or("scene".into(), |s| s.to_string_lossy().into_owned());
        PathBuf::from("out/orbits").join(stem)
    });
    let mut set = Staging::new(&out).map_err(|e| exit::publish_failure(&e))?;
    let json = serde_json::to_string_pretty(&report).expect("serialises") + "\n";
    set.write("orbits.json", json.as_bytes())
        .map_err(|e| exit::publish_failure(&e))?;
    set.commit().map_err(|e| exit::publish_failure(&e))?;
    outln!(
        "{}: period {}, {} start{}, {} orbit{} ({} start{} did not converge)",
        scene.origin,
        report.period,
        report.starts,
        if report.starts == 1 { "" } else { "s" },
        report.orbits.len(),
        if report.orbits.len() == 1 { "" } else { "s" },
        report.misses,
        if report.misses == 1 { "" } else { "s" }
    )?;
    for (i, o) in report.orbits.iter().enumerate() {
        outln!(
            "orbit {}: {:?}, contacts {:?}, found from {} start{}, residual {:.1e}",
            i + 1,
            o.verdict,
            o.boundaries,
            o.found_from,
            if o.found_from == 1 { "" } else { "s" },
            o.residual
        )?;
        outln!("  start [x, u, U] = [{}]", show(&o.start))?;
        let e: Vec<String> = o
            .eigenvalues
            .iter()
            .map(|(re, im)| format!("{re:+.9}{im:+.9}i"))
            .collect();
        outln!("  eigenvalues: {}", e.join(", "))?;
    }
    for (i, e) in report.exact.iter().enumerate() {
        match e {
            Some(r) => {
                outln!(
                    "exact, --from[{i}]: contacts {:?}, {}periodic; characteristic polynomial of the section map: {}",
                    r.boundaries,
                    if r.periodic { "" } else { "not " },
                    r.charpoly
                )?;
            }
            None => outln!("exact, --from[{i}]: not computed (a contact time or the start's projection is irrational)")?,
        }
    }
    outln!("wrote {}", out.display())?;
    Ok(Exit::Success)
}
