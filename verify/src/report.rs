//! `verify.md` and `verify.json`, written atomically, and the golden-copy comparison.

use serde::{Deserialize, Serialize};
use std::io;
use std::path::Path;

/// What a passing check establishes.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Proof {
    /// A rational-function identity checked exactly at random points of `S^k`; a false one
    /// passes with probability at most `bound = (degree / set_size)^points`.
    Identity {
        degree: u64,
        set_size: u64,
        bound: f64,
    },
    /// Exact facts at the sampled configurations (ranks, orthogonality).
    ExactAtConfigurations,
    /// An exact computation (closed-form integrals, sequences).
    ExactComputation,
}

#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct CheckResult {
    pub dim: usize,
    pub variant: String,
    pub check: String,
    pub passed: bool,
    pub points: usize,
    pub proof: Proof,
    pub detail: String,
    pub seconds: f64,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Report {
    pub tool: String,
    pub seed: u64,
    pub points: usize,
    pub results: Vec<CheckResult>,
    pub seconds: f64,
}

impl Report {
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

    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("report serialises") + "\n"
    }

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

/// Write `contents` to `path` atomically: a temporary file in the same directory, then a
/// rename, so a reader never sees a half-written report and an old one is never lost.
pub fn write_atomic(path: &Path, contents: &str) -> io::Result<()> {
    let dir = path
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir)?;
    let tmp = dir.join(format!(
        ".{}.tmp{}",
        path.file_name()
            .and_then(|n| n.to_str())
            .unwrap_or("report"),
        std::process::id()
    ));
    std::fs::write(&tmp, contents)?;
    std::fs::rename(&tmp, path)
}

/// A line diff of two texts: `None` if equal, else the differing lines as `-`/`+`.
pub fn diff(golden: &str, fresh: &str) -> Option<String> {
    if golden == fresh {
        return None;
    }
    let (a, b): (Vec<&str>, Vec<&str>) = (golden.lines().collect(), fresh.lines().collect());
    let mut out = String::new();
    for i in 0..a.len().max(b.len()) {
        match (a.get(i), b.get(i)) {
            (Some(x), Some(y)) if x == y => {}
            (x, y) => {
                if let Some(x) = x {
                    out.push_str(&format!("line {}: - {x}\n", i + 1));
                }
                if let Some(y) = y {
                    out.push_str(&format!("line {}: + {y}\n", i + 1));
                }
            }
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_replaces_whole_files() {
        let dir = std::env::temp_dir().join(format!("noslip-report-{}", std::process::id()));
        let path = dir.join("r.md");
        write_atomic(&path, "one").unwrap();
        write_atomic(&path, "two").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "two");
        assert_eq!(
            std::fs::read_dir(&dir).unwrap().count(),
            1,
            "no temporary left behind"
        );
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn diff_names_changed_lines() {
        assert_eq!(diff("a\nb\n", "a\nb\n"), None);
        assert_eq!(
            diff("a\nb\n", "a\nc\n").unwrap(),
            "line 2: - b\nline 2: + c\n"
        );
    }
}
