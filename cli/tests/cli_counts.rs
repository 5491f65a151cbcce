//! Counts with a cost: `verify --points`, `report --samples`, `gen --check` and `lyapunov
//! --blocks` take a bounded range. Outside it the command exits 2 at once with one line naming
//! the option (a huge count used to run for ever or grow memory without limit; `gen --check
//! 0` passed without checking anything).

use crate::support;
use support::{noslip, temp};

#[test]
fn counts_out_of_range_exit_2_naming_the_option() {
    let out_dir = temp("counts");
    let out = out_dir.to_str().unwrap();
    let huge = "99999999999999";
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["verify", "--points", "0"],
            "--points: must be in 1..=1024, got 0",
        ),
        (
            vec!["verify", "--points", "1025"],
            "--points: must be in 1..=1024, got 1025",
        ),
        (
            vec!["verify", "--points", huge],
            "--points: must be in 1..=1024",
        ),
        (
            vec!["report", "--samples", "0"],
            "--samples: must be in 1..=100000, got 0",
        ),
        (
            vec!["report", "--samples", "100001"],
            "--samples: must be in 1..=100000",
        ),
        (
            vec!["report", "--samples", huge],
            "--samples: must be in 1..=100000",
        ),
        (
            vec!["gen", "--scene", "scenes/sinai.toml", "--check", "0"],
            "--check: must be in 1..=1024, got 0",
        ),
        (
            vec!["gen", "--scene", "scenes/sinai.toml", "--check", huge],
            "--check: must be in 1..=1024",
        ),
        (
            vec!["lyapunov", "scenes/sinai.toml", "--blocks", huge],
            "--blocks: must be in 1..=10000",
        ),
    ];
    for (args, message) in cases {
        let mut command = noslip();
        command.args(&args);
        if args[0] != "gen" {
            // gen --lang rust prints; the others would write here.
            command.args(["--out", out]);
        }
        let run = command.output().unwrap();
        let err = String::from_utf8(run.stderr).unwrap();
        assert_eq!(run.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(message), "{args:?}: {err}");
        assert!(!out_dir.exists(), "{args:?} wrote {out}");
    }
}
