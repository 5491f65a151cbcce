//! `report.md` and `report.json`: provenance, sampling, and per dimension and regime the
//! table of every variant.

use crate::method::{has_fma, Method};
use crate::report::{DimResult, MethodResult, Options, RegimeResult};
use serde::Serialize;
use std::fmt::Write;

/// The bound on the rounding part of the difference across a limit, in eps.
pub const CONTINUITY_BOUND_EPS: f64 = 64.0;

/// Where and how the numbers were made.
#[derive(Clone, Debug, Serialize)]
pub struct Provenance {
    /// The command that reproduces the report.
    pub command: String,
    /// The git commit (12 hex digits), marked when the checkout had uncommitted changes.
    pub commit: String,
    /// `rustc --version` of the build.
    pub rustc: String,
    /// The cargo profile of the build (`release`, `debug`).
    pub profile: String,
    /// The target triple.
    pub target: String,
    /// The SIMD target features enabled at build time (`sse*`, `avx*`, `fma`, `neon`).
    pub target_features: String,
    /// The CPU's model name (from `/proc/cpuinfo`), or the architecture.
    pub cpu: String,
    /// Whether this CPU runs the FMA kernels with FMA instructions.
    pub cpu_has_fma: bool,
    /// The instruction set the batch variant runs at (`Exec::auto`).
    pub batch_isa: String,
}

impl Provenance {
    /// `out` is the report's own directory: regenerating a checked-in report there does not
    /// count as an uncommitted change.
    pub fn collect(command: String, out: &std::path::Path) -> Provenance {
        let git = |args: &[&str]| {
            std::process::Command::new("git")
                .args(args)
                .output()
                .ok()
                .filter(|o| o.status.success())
                .and_then(|o| String::from_utf8(o.stdout).ok())
                .map(|s| s.trim().to_string())
        };
        let exclude = format!(":(exclude){}", out.display());
        let commit = match git(&["rev-parse", "--short=12", "HEAD"]) {
            Some(c)
                if git(&[
                    "status",
                    "--porcelain",
                    "--untracked-files=no",
                    "--",
                    ".",
                    &exclude,
                ])
                .is_some_and(|s| !s.is_empty()) =>
            {
                format!("{c} (with uncommitted changes)")
            }
            Some(c) => c,
            None => "unknown (not a git checkout)".into(),
        };
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split(':').nth(1))
                    .map(|m| m.trim().to_string())
            })
            .unwrap_or_else(|| std::env::consts::ARCH.to_string());
        let features = env!("NOSLIP_TARGET_FEATURES");
        let simd: Vec<&str> = features
            .split(',')
            .filter(|f| f.starts_with("sse") || f.starts_with("avx") || *f == "fma" || *f == "neon")
            .collect();
        Provenance {
            command,
            commit,
            rustc: env!("NOSLIP_RUSTC_VERSION").into(),
            profile: env!("NOSLIP_PROFILE").into(),
            target: env!("NOSLIP_TARGET").into(),
            target_features: simd.join(","),
            cpu,
            cpu_has_fma: has_fma(),
            batch_isa: collision_core::batch::Exec::auto().isa().name().into(),
        }
    }
}

/// An accuracy report: `report.json`, and `report.md` made from it.
#[derive(Clone, Debug, Serialize)]
pub struct AccuracyReport {
    /// The program and its version (`noslip 0.1.0`).
    pub tool: String,
    /// Where and how the numbers were made.
    pub provenance: Provenance,
    /// What was sampled and timed.
    pub options: Options,
    /// One result per dimension.
    pub dims: Vec<DimResult>,
    /// Wall-clock seconds of the whole run.
    pub seconds: f64,
}

impl AccuracyReport {
    /// Every regime of every dimension meets the stability requirement, the rough-ball
    /// family's `f64` kernels give no NaN or infinity, and the rounding part of the
    /// difference across each limit stays within 64 eps.
    pub fn passed(&self) -> bool {
        self.dims.iter().all(|d| {
            d.regimes.iter().all(|r| r.stability.passed)
                && d.family.iter().all(|r| r.passed())
                && d.continuity.mass_1e15_vs_immovable.rounding_eps <= CONTINUITY_BOUND_EPS
                && d.continuity.gamma2_1e15_vs_zero.rounding_eps <= CONTINUITY_BOUND_EPS
        })
    }

    /// `report.json`: the report as indented JSON, ending in a newline.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("report serialises") + "\n"
    }

    /// `report.md`: provenance, sampling, and per dimension and regime the table of every method.
    pub fn to_markdown(&self) -> String {
        let mut m = String::new();
        let p = &self.provenance;
        let o = &self.options;
        let _ = writeln!(m, "# Error against run time of the no-slip kernels\n");
        let _ = writeln!(m, "Reproduce: `{}`\n", p.command);
        let _ = writeln!(
            m,
            "How to read this report: `docs/accuracy.md` in the repository.\n"
        );
        let _ = writeln!(m, "| provenance | |\n|---|---|");
        let _ = writeln!(m, "| commit | {} |", p.commit);
        let _ = writeln!(m, "| compiler | {} |", p.rustc);
        let _ = writeln!(
            m,
            "| build | profile `{}`, target `{}`, SIMD features `{}` |",
            p.profile, p.target, p.target_features
        );
        let _ = writeln!(
            m,
            "| CPU | {} (FMA instructions: {}; batch kernels run at `{}`) |",
            p.cpu,
            if p.cpu_has_fma {
                "yes, used by the FMA variant"
            } else {
                "no: the FMA variant calls libm"
            },
            p.batch_isa
        );
        let _ = writeln!(m, "| run time | {:.1} s |\n", self.seconds);
        let _ = writeln!(
            m,
            "**Sampling.** Per dimension and regime, {} cases from a ChaCha8 stream seeded with {} \
             (distributions below); cases that fail validation are excluded and counted. \
             Inputs are `f64`; each variant's error is against the exact rational result of the \
             generated map on the same inputs, converted exactly (for `f32`: on the inputs \
             rounded to `f32`; points not representable in `f32` are excluded from it and counted). \
             Times: median over {} timed samples of passes over a batch of {} cases in cache \
             ({} for the exact variant); the spread is the 25th to 75th percentile.\n",
            o.samples, o.seed, o.timing_samples, o.batch, o.exact_batch
        );
        let _ = writeln!(
            m,
            "**Error measures.** *bits*: `log2(ulps + 1)` per output component against the \
             correctly rounded exact value (0 = correctly rounded). *normwise*: per movable body, \
             `|computed - exact| / |exact|` in that body's kinetic-energy norm, in units of the \
             format's epsilon (`2^-52` for f64, `2^-23` for f32). *kappa*: the body's estimated \
             condition number (relative change of the exact result under relative input \
             perturbations of `2^-53`, per unit perturbation).\n"
        );
        summary(&mut m, self);
        for d in &self.dims {
            let _ = writeln!(m, "## n = {}\n", d.dim);
            let _ = writeln!(
                m,
                "![error against time, n = {}](error-vs-time-n{}.svg)\n",
                d.dim, d.dim
            );
            for r in &d.regimes {
                regime(&mut m, r);
            }
        }
        let family: Vec<(usize, &[crate::family::FamilyResult])> =
            self.dims.iter().map(|d| (d.dim, &d.family[..])).collect();
        crate::family::markdown(&mut m, &family);
        m
    }
}

fn summary(m: &mut String, report: &AccuracyReport) {
    let _ = writeln!(m, "## Stability of the generated f64 kernel\n");
    let _ = writeln!(
        m,
        "Max normwise error per body, in f64 epsilons, against the bound (16 typical, 64 \
         elsewhere). A body above the bound passes only if its error is within its \
         conditioning (`error <= kappa eps`): the problem, not the kernel, limits it. \
         NaN or infinity anywhere fails.\n"
    );
    let regimes: Vec<&str> = report.dims[0]
        .regimes
        .iter()
        .map(|r| r.name.as_str())
        .collect();
    let _ = writeln!(m, "| n | {} |", regimes.join(" | "));
    let _ = writeln!(m, "|---|{}", "---|".repeat(regimes.len()));
    for d in &report.dims {
        let cells: Vec<String> = d
            .regimes
            .iter()
            .map(|r| {
                let s = &r.stability;
                let mark = if !s.passed {
                    "FAIL"
                } else if s.over_bound > 0 {
                    "ok (conditioning)"
                } else {
                    "ok"
                };
                format!("{:.2} / {} {}", s.max_normwise_eps, s.bound_eps, mark)
            })
            .collect();
        let _ = writeln!(m, "| {} | {} |", d.dim, cells.join(" | "));
    }
    let _ = writeln!(m);
    let _ = writeln!(
        m,
        "**Continuity at the limits** (generated f64; the kernel has no branch). Largest \
         normwise difference, in eps, between `m_1 = 1e15 m_2` and an immovable body 1 (body \
         2's result) and between `gamma2_1 = 1e-15` and `0` (both bodies), over {} typical \
         cases: of the f64 results, of the exact results (the model's own difference at these \
         parameters, not rounding: `1e-15` times a factor that grows as the other body's \
         `gamma2` shrinks or the mass ratio grows), \
         and of the two (the rounding part, which must stay within 64 eps: no jump at the limit).\n",
        report.dims.first().map_or(0, |d| d.continuity.cases)
    );
    tightness(m, report);
    static_bounds(m, report);
    let _ = writeln!(
        m,
        "| n | mass: f64 | mass: exact | mass: rounding | gamma: f64 | gamma: exact | gamma: rounding |\n|---|---:|---:|---:|---:|---:|---:|"
    );
    for d in &report.dims {
        let (a, b) = (
            &d.continuity.mass_1e15_vs_immovable,
            &d.continuity.gamma2_1e15_vs_zero,
        );
        let _ = writeln!(
            m,
            "| {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} |",
            d.dim,
            a.computed_eps,
            a.exact_eps,
            a.rounding_eps,
            b.computed_eps,
            b.exact_eps,
            b.rounding_eps
        );
    }
    let _ = writeln!(m);
}

/// The proven bounds' tightness: per kernel, n and regime, the largest proven bound over the
/// largest measured error.
fn tightness(m: &mut String, report: &AccuracyReport) {
    let _ = writeln!(
        m,
        "**Proven bounds** (`noslip_codegen::bound`, docs/accuracy.md): for every case, a \
         rigorous bound of each movable body's normwise error, derived from the kernel's \
         operations under the standard model of rounding (per output the smaller of a \
         running error analysis of that call and a mean-value bound along its roundings, both \
         evaluated in upward-rounded arithmetic). Cell: largest bound / largest \
         measured error over the regime's cases (the tightness; 1 would be exact), and the \
         largest bound in eps. A measured error above its bound fails the report.\n"
    );
    regime_tables(m, report, |v| {
        let (t, p) = (v.tightness()?, v.proven_eps?.max);
        let broken = if v.proven_broken > 0 { " BROKEN" } else { "" };
        Some(format!("{t:.1}x ({p:.1}){broken}"))
    });
}

/// The static bounds: per kernel, n and regime, the bound over the regime's box against the
/// largest error measured over the regime's cases in the box.
fn static_bounds(m: &mut String, report: &AccuracyReport) {
    let _ = writeln!(
        m,
        "**Static bounds** (`noslip_accuracy::static_box`, docs/accuracy.md): one bound of \
         the absolute error of every movable body's output component that holds for every \
         input in the regime's box (the same rules over intervals, parameters cut into \
         geometric pieces). The typical box: per body inv_mass in [1/4, 4], R in [1/2, 2], \
         gamma2 in [g/8, g] (g = 2/n), entries of nu, U_i and u_i in [-1, 1]. Cell: bound / \
         largest absolute component error measured over the regime's cases in the box, the \
         bound in eps, and how many of the regime's cases lie in the box. A measured error \
         above the static bound fails the report.\n"
    );
    if let Some(d) = report.dims.first() {
        for r in &d.regimes {
            let _ = writeln!(m, "- {}: {}", r.name, r.static_box);
        }
        let _ = writeln!(m);
    }
    regime_tables(m, report, |v| {
        let s = v.static_bound?;
        if !s.bound_eps.is_finite() {
            return Some(format!("no finite bound ({} in box)", s.in_box));
        }
        let broken = if s.broken > 0 { " BROKEN" } else { "" };
        let ratio = s.tightness().map_or("-".into(), |t| format!("{t:.0}x"));
        Some(format!(
            "{ratio} ({:.3e}; {}){broken}",
            s.bound_eps, s.in_box
        ))
    });
}

/// One table per float kernel form: a row per n, a cell per regime (`cell` of that regime's
/// result for the form; `-` without one).
fn regime_tables(
    m: &mut String,
    report: &AccuracyReport,
    cell: impl Fn(&MethodResult) -> Option<String>,
) {
    let regimes: Vec<&str> = report.dims[0]
        .regimes
        .iter()
        .map(|r| r.name.as_str())
        .collect();
    for method in [Method::F64, Method::F64Fma, Method::F32] {
        let _ = writeln!(m, "{}:\n", method.name());
        let _ = writeln!(m, "| n | {} |", regimes.join(" | "));
        let _ = writeln!(m, "|---|{}", "---|".repeat(regimes.len()));
        for d in &report.dims {
            let cells: Vec<String> = d
                .regimes
                .iter()
                .map(|r| {
                    let v = r.variants.iter().find(|v| v.variant == method);
                    v.and_then(&cell).unwrap_or_else(|| "-".into())
                })
                .collect();
            let _ = writeln!(m, "| {} | {} |", d.dim, cells.join(" | "));
        }
        let _ = writeln!(m);
    }
}

fn time_cell(v: &MethodResult) -> (String, String) {
    match v.timing {
        None => ("-".into(), "-".into()),
        Some(t) if v.variant == Method::Exact => (
            format!("{:.1} us", t.median_ns / 1e3),
            format!("{:.1}..{:.1} us", t.p25_ns / 1e3, t.p75_ns / 1e3),
        ),
        Some(t) => (
            format!("{:.2} ns", t.median_ns),
            format!("{:.2}..{:.2}", t.p25_ns, t.p75_ns),
        ),
    }
}

fn regime(m: &mut String, r: &RegimeResult) {
    let _ = writeln!(m, "### {}\n", r.name);
    let _ = writeln!(m, "{}.\n", r.about);
    let excluded: usize = r.excluded.values().sum();
    let _ = write!(m, "Sampled {}, excluded {}", r.sampled, excluded);
    for (why, count) in &r.excluded {
        let _ = write!(m, " ({count}: {why})");
    }
    let c = &r.conditioning;
    let _ = writeln!(
        m,
        ". Conditioning kappa per body: mean {:.3}, p99 {:.3}, max {:.3}.\n",
        c.mean, c.p99, c.max
    );
    let s = &r.stability;
    let _ = writeln!(
        m,
        "Generated f64: max normwise {:.2} eps (bound {}); {} bodies above the bound, {} of them beyond their conditioning; {} non-finite results. **{}**\n",
        s.max_normwise_eps,
        s.bound_eps,
        s.over_bound,
        s.over_conditioning,
        s.non_finite,
        if s.passed { "passes" } else { "FAILS" }
    );
    let _ = writeln!(
        m,
        "| variant | ops | time (median) | spread | bits mean | bits p99 | bits max | normwise mean | p99 | max (eps) | proven max (eps) | proven / max | dominant output (mean bits) | cases |"
    );
    let _ = writeln!(
        m,
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---|"
    );
    for v in &r.variants {
        let (t, spread) = time_cell(v);
        let ops = v.ops.map_or("-".into(), |o| o.to_string());
        let dominant = v
            .dominant
            .as_ref()
            .map_or("-".into(), |(c, b)| format!("`{c}` ({b:.2})"));
        let mut cases = v.evaluated.to_string();
        if v.non_finite > 0 {
            let _ = write!(cases, ", {} NON-FINITE", v.non_finite);
        }
        for (why, n) in &v.unsupported {
            let _ = write!(cases, ", {n} refused: {why}");
        }
        if v.proven_unbounded > 0 {
            let _ = write!(cases, ", {} without a finite bound", v.proven_unbounded);
        }
        if v.proven_broken > 0 {
            let _ = write!(cases, ", {} ABOVE THE PROVEN BOUND", v.proven_broken);
        }
        let proven = v.proven_eps.map_or("-".into(), |p| format!("{:.2}", p.max));
        let tight = v.tightness().map_or("-".into(), |t| format!("{t:.1}"));
        let (b, e) = (&v.bits, &v.normwise_eps);
        let _ = writeln!(
            m,
            "| {} | {} | {} | {} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {:.2} | {} | {} | {} | {} |",
            v.name, ops, t, spread, b.mean, b.p99, b.max, e.mean, e.p99, e.max, proven, tight, dominant, cases
        );
    }
    let _ = writeln!(m);
}
