//! `verify.md` and `verify.json`, and the golden-copy comparison.

use serde::{Deserialize, Serialize};

/// What a passing check establishes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Proof {
    /// A rational-function identity checked exactly at random points of `S^k`; a false one
    /// passes with probability at most `bound = (degree / set_size)^points`.
    Identity {
        /// A bound on the degree of the identity's numerator.
        degree: u64,
        /// `|S|`: every free input is drawn uniformly from `S = {1, .., set_size}`.
        set_size: u64,
        /// `min(1, degree / set_size)^points`.
        bound: f64,
    },
    /// Exact facts at the sampled configurations (ranks, orthogonality).
    ExactAtConfigurations,
    /// An exact computation (closed-form integrals, sequences).
    ExactComputation,
}

/// One check's outcome: a row of the report.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CheckResult {
    /// The dimension `n`.
    pub dim: usize,
    /// `free`, `fixed`, or `any` for a check of no kernel.
    pub variant: String,
    /// What is checked, in words (`conserved: kinetic energy`).
    pub check: String,
    /// Whether it holds.
    pub passed: bool,
    /// What it was checked at: random points, configurations, sequence terms or densities.
    pub points: usize,
    /// What a pass establishes.
    pub proof: Proof,
    /// Why it failed, or figures it computed; often empty.
    pub detail: String,
    /// Wall-clock seconds it took (0 in the golden copy).
    pub seconds: f64,
}

/// The results of a verification run: `verify.json` and `verify.md`.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Report {
    /// The program and its version (`noslip 0.1.0`).
    pub tool: String,
    /// The seed the sample points are drawn from.
    pub seed: u64,
    /// Random points per identity check.
    pub points: usize,
    /// Every check's result, in the order run.
    pub results: Vec<CheckResult>,
    /// Wall-clock seconds of the whole run (0 in the golden copy).
    pub seconds: f64,
}

impl Report {
    /// Whether every check passed.
    pub fn passed(&self) -> bool {
        self.results.iter().all(|r| r.passed)
    }

    /// The report without timings: what the golden copy holds.
    pub fn without_timings(&self) -> Report {
        let mut r = self.clone();
        r.seconds = 0.0;
        r.results.iter_mut().for_each(|c| c.seconds = 0.0);
        r
    }

    /// `verify.json`: the report as indented JSON, ending in a newline.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("report serialises") + "\n"
    }

    /// `verify.md`: a summary, then per dimension a table of the checks.
    pub fn to_markdown(&self) -> String {
        let mut md = format!(
            "# Exact verification of the generated kernels\n\n\
             {} checks, {} failed; seed {}, {} points per identity; {:.1} s.\n\n\
             Identity checks run the compiled kernels in exact rationals at random points with \
             every free input uniform in S = {{1..2^20}}; *bound* is the Schwartz-Zippel \
             probability that a false identity passed, (degree / |S|)^points. See \
             `docs/verification.md`.\n",
            self.results.len(),
            self.results.iter().filter(|r| !r.passed).count(),
            self.seed,
            self.points,
            self.seconds
        );
        let mut dim = 0;
        for r in &self.results {
            if r.dim != dim {
                dim = r.dim;
                md.push_str(&format!(
                    "\n## n = {dim}\n\n| variant | check | result | points | degree | bound | time (s) |\n|---|---|---|---|---|---|---|\n"
                ));
            }
            let (degree, bound) = match &r.proof {
                Proof::Identity { degree, bound, .. } => {
                    (degree.to_string(), format!("{bound:.1e}"))
                }
                Proof::ExactAtConfigurations => ("-".into(), "exact at configurations".into()),
                Proof::ExactComputation => ("-".into(), "exact".into()),
            };
            let result = match (r.passed, r.detail.is_empty()) {
                (true, true) => "pass".to_string(),
                (true, false) => format!("pass ({})", r.detail),
                (false, _) => format!("**FAIL**: {}", r.detail),
            };
            md.push_str(&format!(
                "| {} | {} | {} | {} | {} | {} | {:.3} |\n",
                r.variant, r.check, result, r.points, degree, bound, r.seconds
            ));
        }
        md
    }
}

/// The golden copy: the results without timings of every dimension, compared and updated
/// by dimension.
///
/// A run of some dimensions is compared with the golden results of those dimensions only
/// (each dimension's checks draw from their own seeded streams, so a subset reproduces
/// exactly). The copy is read in its own schema ([`golden::Copy`]) whose numbers keep the
/// digits written: reading them as `f64` would round some of them differently.
pub mod golden {
    use super::Report;
    use serde::{Deserialize, Serialize};
    use serde_json::Number;

    /// The golden copy as written: [`Report`]'s fields in its order, numbers as digits.
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    pub struct Copy {
        tool: String,
        seed: u64,
        points: usize,
        results: Vec<Check>,
        seconds: Number,
    }

    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Check {
        dim: usize,
        variant: String,
        check: String,
        passed: bool,
        points: usize,
        proof: Proof,
        detail: String,
        seconds: Number,
    }

    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Proof {
        kind: String,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        degree: Option<Number>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        set_size: Option<Number>,
        #[serde(default, skip_serializing_if = "Option::is_none")]
        bound: Option<Number>,
    }

    impl Copy {
        /// Read a golden copy.
        pub fn parse(text: &str) -> Result<Copy, String> {
            serde_json::from_str(text).map_err(|e| format!("not a verify report: {e}"))
        }

        /// A run's results without timings, as a golden copy.
        pub fn of(run: &Report) -> Result<Copy, String> {
            Copy::parse(&run.without_timings().to_json())
                .map_err(|e| format!("this run's report: {e}"))
        }

        /// The text of the file: [`Report::to_json`]'s layout.
        pub fn to_json(&self) -> String {
            serde_json::to_string_pretty(self).expect("golden copy serialises") + "\n"
        }

        /// The results for the dimensions in `dims` only, in increasing dimension.
        pub fn restricted(&self, dims: &[usize]) -> Copy {
            let mut c = self.clone();
            c.results.retain(|r| dims.contains(&r.dim));
            c.results.sort_by_key(|r| r.dim);
            c
        }
    }

    /// The unified diff of the golden copy against `run` (timings removed), over the
    /// dimensions in `dims`: `Ok(None)` if they agree.
    pub fn compare(golden: &str, run: &Report, dims: &[usize]) -> Result<Option<String>, String> {
        let (golden, fresh) = (Copy::parse(golden)?, Copy::of(run)?);
        // Other random points give other counts everywhere: say that, not a diff of every
        // line.
        same_sampling(
            &golden,
            &fresh,
            "it",
            "compare with the same --points (and seed)",
        )?;
        let golden = golden.restricted(dims).to_json();
        let fresh = fresh.restricted(dims).to_json();
        Ok(crate::diff::unified(
            "golden copy",
            "this run",
            &golden,
            &fresh,
            3,
        ))
    }

    /// The golden copy updated with `run`: its results replace those of its dimensions, the
    /// other dimensions' results are kept, in dimension order. A run of only some dimensions
    /// must use the golden copy's seed and points (else the copy would mix two samplings).
    pub fn update(golden: Option<&str>, run: &Report, dims: &[usize]) -> Result<Copy, String> {
        let fresh = Copy::of(run)?;
        let Some(golden) = golden else {
            return Ok(fresh);
        };
        let old = Copy::parse(golden)?;
        let kept: Vec<Check> = old
            .results
            .iter()
            .filter(|c| !dims.contains(&c.dim))
            .cloned()
            .collect();
        if !kept.is_empty() {
            same_sampling(
                &old,
                &fresh,
                "the golden copy",
                "update it with the same --points, or with every dimension it holds",
            )?;
        }
        let mut merged = fresh;
        merged.results.extend(kept);
        merged.results.sort_by_key(|c| c.dim);
        Ok(merged)
    }

    /// `Err` when `fresh` was sampled otherwise than `golden` (another seed or number of
    /// points): "`subject` was made with seed .. and .. points, this run with ..: `advice`".
    fn same_sampling(
        golden: &Copy,
        fresh: &Copy,
        subject: &str,
        advice: &str,
    ) -> Result<(), String> {
        if (golden.seed, golden.points) == (fresh.seed, fresh.points) {
            return Ok(());
        }
        Err(format!(
            "{subject} was made with seed {} and {} points, this run with seed {} and {} \
             points: {advice}",
            golden.seed, golden.points, fresh.seed, fresh.points
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(dim: usize, name: &str, passed: bool) -> CheckResult {
        CheckResult {
            dim,
            variant: "free".into(),
            check: name.into(),
            passed,
            points: 4,
            proof: Proof::ExactComputation,
            detail: String::new(),
            seconds: 0.5,
        }
    }

    fn report(points: usize, results: Vec<CheckResult>) -> Report {
        Report {
            tool: "noslip test".into(),
            seed: 2026,
            points,
            results,
            seconds: 3.0,
        }
    }

    #[test]
    fn the_shipped_golden_copy_reads_back_to_the_same_text() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/reports/verify.json");
        let text = std::fs::read_to_string(path).unwrap();
        let copy = golden::Copy::parse(&text).unwrap();
        assert_eq!(copy.to_json(), text);
        // A run's report in the golden layout: the same text as the report's own JSON.
        let run = report(4, (2..=6).map(|n| check(n, "energy", true)).collect());
        assert_eq!(
            golden::Copy::of(&run).unwrap().to_json(),
            run.without_timings().to_json()
        );
    }

    #[test]
    fn a_run_of_some_dimensions_is_compared_with_those_only() {
        let all = report(4, (2..=6).map(|n| check(n, "energy", true)).collect());
        let golden = all.without_timings().to_json();
        let run3 = report(4, vec![check(3, "energy", true)]);
        assert_eq!(golden::compare(&golden, &run3, &[3]).unwrap(), None);
        // A change in n = 3 shows as a unified diff of that line.
        let failed3 = report(4, vec![check(3, "energy", false)]);
        let d = golden::compare(&golden, &failed3, &[3]).unwrap().unwrap();
        assert!(d.starts_with("--- golden copy\n+++ this run\n@@ "), "{d}");
        let changed: Vec<&str> = d
            .lines()
            .filter(|l| l.starts_with(['-', '+']) && !l.starts_with("---") && !l.starts_with("+++"))
            .collect();
        assert_eq!(
            changed,
            ["-      \"passed\": true,", "+      \"passed\": false,"]
        );
        // A dimension missing from the golden copy differs.
        let golden23 = report(4, vec![check(2, "energy", true)])
            .without_timings()
            .to_json();
        assert!(golden::compare(&golden23, &run3, &[3]).unwrap().is_some());
        // A run of other points is refused as such, not shown as a diff of every count.
        let other_points = report(5, vec![check(3, "energy", true)]);
        let e = golden::compare(&golden, &other_points, &[3]).unwrap_err();
        assert!(e.contains("4 points, this run with seed"), "{e}");
    }

    #[test]
    fn updating_with_some_dimensions_keeps_the_others() {
        let golden = report(4, (2..=4).map(|n| check(n, "energy", true)).collect())
            .without_timings()
            .to_json();
        let run3 = report(4, vec![check(3, "energy", false)]);
        let merged = golden::update(Some(&golden), &run3, &[3]).unwrap();
        let expected = report(
            4,
            vec![
                check(2, "energy", true),
                check(3, "energy", false),
                check(4, "energy", true),
            ],
        );
        assert_eq!(merged.to_json(), expected.without_timings().to_json());
        // Other points for only some dimensions would mix two samplings.
        let run3_other = report(8, vec![check(3, "energy", true)]);
        assert!(golden::update(Some(&golden), &run3_other, &[3]).is_err());
        let all8 = report(8, (2..=4).map(|n| check(n, "energy", true)).collect());
        assert_eq!(
            golden::update(Some(&golden), &all8, &[2, 3, 4])
                .unwrap()
                .to_json(),
            all8.without_timings().to_json()
        );
    }
}
