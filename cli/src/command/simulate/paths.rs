//! The output paths of `noslip simulate`: two spellings of one file or directory compared,
//! the side files' names in the set, and the checks made before a run starts (no output
//! path may be the scene or another output).

use super::Args;
use crate::exit::Failure;
use noslip_columnar::is_parquet;
use std::path::{Path, PathBuf};

/// `p` as an absolute path (against the current directory) without `.` and `..`
/// components: two spellings of one path (`o`, `./o`, `/cwd/o`, `o/../o`) compare equal
/// lexically. A `..` after a symbolic link is taken lexically, as `std::path::absolute`
/// takes the rest (neither need exist yet).
pub(super) fn lexical(p: &Path) -> PathBuf {
    use std::path::Component;
    let p = if p.as_os_str().is_empty() {
        Path::new(".")
    } else {
        p
    };
    let absolute = std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    let mut out = PathBuf::new();
    for c in absolute.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            _ => out.push(c),
        }
    }
    out
}

/// Whether `dir` (a log file's parent) is the output directory `out`, lexically (neither need
/// exist yet): `OUT/events.jsonl` is then a file of the published set.
pub(super) fn same_dir(dir: Option<&Path>, out: &Path) -> bool {
    dir.is_some_and(|d| lexical(d) == lexical(out))
}

/// Files of every simulate set; a side output may not take their names.
pub(super) const SET_FILES: [&str; 14] = [
    crate::publish::MARKER,
    "summary.json",
    "energy.svg",
    "trajectories.svg",
    "observables.csv",
    "observables.parquet",
    "observables.svg",
    "pair-correlation.csv",
    "pair-correlation.parquet",
    "self-diffusion.csv",
    "observables-pressure.svg",
    "observables-a2.svg",
    "observables-msd.svg",
    "pair-correlation.svg",
];

/// The member of the set that `--log` and `--boundary-map` become: the file's own name
/// when it is directly in `out`, else `events.jsonl` / `boundary-map.csv` (the file outside
/// becomes a link to it). Refused (exit 2): a file deeper inside `out` (the switch would
/// remove it), a name of the set's own files, or two side outputs on one member.
pub(super) fn side_members(args: &Args, out: &Path) -> Result<[Option<String>; 2], Failure> {
    let mut members = [None, None];
    let sides = [
        ("--log", &args.log, ["events.jsonl", "events.parquet"]),
        (
            "--boundary-map",
            &args.boundary_map,
            ["boundary-map.csv", "boundary-map.parquet"],
        ),
    ];
    for (i, (option, path, outside)) in sides.into_iter().enumerate() {
        let Some(p) = path else { continue };
        let name = p.file_name().map(|n| n.to_string_lossy().into_owned());
        if let Some(why) = not_a_file(p, out, outside[0]) {
            return Err(Failure::bad_input(format!("{option}: {why}")));
        }
        let member = match name {
            Some(name) if same_dir(p.parent(), out) => name,
            _ if lexical(p).starts_with(lexical(out)) => {
                return Err(Failure::bad_input(format!(
                    "{option}: {} is inside --out {} but not directly in it: the output set is \
                     replaced as a whole; put it in {} itself or outside",
                    p.display(),
                    out.display(),
                    out.display()
                )))
            }
            _ => outside[usize::from(is_parquet(p))].to_string(),
        };
        if SET_FILES.contains(&member.as_str()) || member.starts_with("portrait-") {
            return Err(Failure::bad_input(format!(
                "{option}: {} would replace the set's own file {member} in {}",
                p.display(),
                out.display()
            )));
        }
        if members[0].as_ref() == Some(&member) {
            return Err(Failure::bad_input(format!(
                "--boundary-map: {} would be the set's file {member}, as --log is; name them \
                 differently",
                p.display()
            )));
        }
        members[i] = Some(member);
    }
    Ok(members)
}

/// Why the file path `p` of a side output (`--log`, `--boundary-map`, `--html`) names no
/// file it could become: `--out` itself, or an existing directory (refused before the run,
/// exit 2, rather than failing to create it after).
pub(super) fn not_a_file(p: &Path, out: &Path, example: &str) -> Option<String> {
    if lexical(p) == lexical(out) {
        return Some(format!(
            "{} is --out itself, a directory; name a file in it (such as {}) or outside it",
            p.display(),
            out.join(example).display()
        ));
    }
    p.is_dir().then(|| {
        format!(
            "{} is a directory; name a file (the output is one file)",
            p.display()
        )
    })
}

/// `--time` and `--events` as the scene file has them: a positive finite time, at least one
/// contact (the fuzz target `cli_args` calls it too).
pub fn check_limits(args: &Args) -> Result<(), Failure> {
    if let Some(t) = args.time {
        noslip_sim::run::check_time(t).map_err(|m| Failure::bad_input(format!("--time: {m}")))?;
    }
    if args.events == Some(0) {
        return Err(Failure::bad_input(
            "--events: must be at least 1 (a run of no contacts has nothing to report)",
        ));
    }
    Ok(())
}

/// Whether `a` and `b` name one file: the same file if both exist, else the same absolute
/// path, lexically.
pub(super) fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => lexical(a) == lexical(b),
    }
}

/// `--log` and `--boundary-map` name two files, neither of them the scene: the run would
/// otherwise overwrite its own input, or one output with the other.
pub(super) fn check_paths(args: &Args) -> Result<(), Failure> {
    let outputs = [("--log", &args.log), ("--boundary-map", &args.boundary_map)];
    for (option, path) in outputs {
        if let Some(p) = path.as_deref().filter(|p| same_file(p, &args.file)) {
            return Err(Failure::bad_input(format!(
                "{option}: {} is the scene file; the run would write over it",
                p.display()
            )));
        }
    }
    if let (Some(log), Some(map)) = (&args.log, &args.boundary_map) {
        if same_file(log, map) {
            return Err(Failure::bad_input(format!(
                "--boundary-map: {} is also --log; the two need two files",
                map.display()
            )));
        }
    }
    Ok(())
}
