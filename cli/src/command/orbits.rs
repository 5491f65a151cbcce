//! `noslip orbits FILE --period K`: periodic orbits of a one-ball table's boundary map.

use crate::command::lyapunov::parse_law;
use crate::exit::{self, Exit, Failure};
use crate::out::outln;
use crate::progress::ProgressDisplay;
use crate::publish::Staging;
use collision_core::Exact;
use noslip_dynamics::orbits::search::DEFAULT_MAX_CONTACTS;
use noslip_dynamics::orbits::search::{search_observed, Progress, Search, SearchError};
use noslip_scene::{parse_exact, Scene};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

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

The work is bounded: every evaluation of P^K (with its derivative) follows K contacts, a
start takes at most 41 Newton steps of at most 31 evaluations, and the whole search follows
at most --max-contacts contacts (default 50000000, one to two minutes); when the bound is
reached the search stops, reports the orbits found so far and says how many starts it tried
(exit 0). Progress goes to stderr (a bar on a terminal, a line per tenth of the starts
elsewhere once the search has run a second); --quiet turns it off.
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
    /// The most contacts the search follows (each evaluation of P^K follows K); it stops
    /// there and says so.
    #[arg(long, default_value_t = DEFAULT_MAX_CONTACTS)]
    max_contacts: u64,
    /// No progress on stderr.
    #[arg(long)]
    quiet: bool,
    /// The output directory (default out/orbits/SCENE).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// Off a terminal, progress lines start once the search has run this long (a short search
/// prints none).
const QUIET_START: Duration = Duration::from_secs(1);

/// Progress of the search on stderr: a bar on a terminal; elsewhere a line at each tenth of
/// the starts once the search has run [`QUIET_START`].
struct Shown {
    display: ProgressDisplay,
    begun: Instant,
    tenth: usize,
}

impl Shown {
    fn new(starts: usize) -> Shown {
        Shown {
            display: ProgressDisplay::new(starts as u64, "starts"),
            begun: Instant::now(),
            tenth: 0,
        }
    }

    fn show(&mut self, p: Progress) {
        let line = progress_line(p, self.begun.elapsed(), &mut self.tenth);
        self.display
            .set_message(format!("{} orbits, {} contacts", p.orbits, p.contacts));
        self.display.inc(line);
    }
}

/// The progress line off a terminal after `p`, `elapsed` into the search: one each time a
/// new tenth of the starts is done (`tenth` is the last one shown), none before
/// [`QUIET_START`].
fn progress_line(p: Progress, elapsed: Duration, tenth: &mut usize) -> Option<String> {
    let now = p.done * 10 / p.starts.max(1);
    (now > *tenth && elapsed >= QUIET_START).then(|| {
        *tenth = now;
        format!(
            "orbits: {}/{} starts, {} orbit{}, {} contacts followed, {:.0} s",
            p.done,
            p.starts,
            p.orbits,
            if p.orbits == 1 { "" } else { "s" },
            p.contacts,
            elapsed.as_secs_f64()
        )
    })
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
        max_contacts: args.max_contacts,
    };
    let scene = Scene::from_file(&args.file).map_err(|e| Failure::bad_input(e.to_string()))?;
    let mut shown: Option<Shown> = None;
    let mut progress = |p: Progress| {
        if !args.quiet {
            shown.get_or_insert_with(|| Shown::new(p.starts)).show(p);
        }
    };
    let report = collision_core::with_dim!(
        scene.dim,
        |N, S| search_observed::<N, S>(&scene, &ask, &mut progress).map_err(failure),
        unreachable!("scene validation keeps dim in {:?}", collision_core::DIMS)
    );
    if let Some(s) = shown {
        s.display.finish();
    }
    let report = report?;
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
        "{}: period {}, {} start{}{}, {} orbit{} ({} start{} did not converge)",
        scene.origin,
        report.period,
        report.starts,
        if report.starts == 1 { "" } else { "s" },
        if report.tried < report.starts {
            format!(" ({} tried)", report.tried)
        } else {
            String::new()
        },
        report.orbits.len(),
        if report.orbits.len() == 1 { "" } else { "s" },
        report.misses,
        if report.misses == 1 { "" } else { "s" }
    )?;
    if let Some(why) = &report.stopped {
        outln!("stopped: {why}; raise --max-contacts or give fewer starts")?;
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Off a terminal: nothing in the first second; then a line at each new tenth of the
    /// starts, naming the starts done, the orbits and the contacts followed.
    #[test]
    fn progress_lines_come_per_tenth_after_a_second() {
        let p = |done| Progress {
            done,
            starts: 40,
            orbits: 1,
            contacts: 1234,
        };
        let mut tenth = 0;
        assert_eq!(
            progress_line(p(8), Duration::from_millis(500), &mut tenth),
            None
        );
        assert_eq!(
            progress_line(p(8), Duration::from_millis(1500), &mut tenth).as_deref(),
            Some("orbits: 8/40 starts, 1 orbit, 1234 contacts followed, 2 s")
        );
        assert_eq!(
            progress_line(p(9), Duration::from_secs(2), &mut tenth),
            None
        );
        assert!(progress_line(p(12), Duration::from_secs(2), &mut tenth).is_some());
        assert!(progress_line(p(40), Duration::from_secs(3), &mut tenth).is_some());
    }
}
