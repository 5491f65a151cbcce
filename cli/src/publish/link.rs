//! Side outputs: a file outside the output set (`simulate --log FILE`, `--boundary-map
//! FILE`) that must change with the set, never apart from it.
//!
//! Two names cannot be switched by one atomic step, so the file is made a member of the set
//! (written and published with it) and `FILE` becomes a symbolic link to that member in the
//! set's final place, `OUT/MEMBER` (absolute). The link is put in place just before the set
//! is switched (by a rename over `FILE`), and it never needs to change again: before the
//! switch it shows the old set's member (absent if the old set has none), after it the new
//! set's. So a kill at any moment leaves `FILE` and the set of one run.
//!
//! Temporaries beside `FILE`: the link is made as `.NAME.noslip-link-PID` and renamed;
//! `.NAME.tmpPID` is the temporary of an atomic write ([`super::write_atomic`], and the events
//! log of noslip before this protocol). Those of processes that no longer run are removed
//! by the next run that writes `FILE` ([`remove_stale`]).

use super::MARKER;
use std::fs;
use std::io;
use std::path::Path;

/// Whether `path` is a link this protocol made: it points at `target`, or at a file of a
/// directory carrying the [`MARKER`] (a set of another `--out`).
pub fn ours(path: &Path, target: &Path) -> bool {
    let Ok(to) = fs::read_link(path) else {
        return false;
    };
    to == target || to.parent().is_some_and(|d| d.join(MARKER).is_file())
}

/// Whether `path` is written directly, as a stream: it exists and is neither a regular file
/// nor a link of [`ours`] (`/dev/stdout`, a pipe, a device, the user's own link).
pub fn is_stream(path: &Path, target: &Path) -> bool {
    fs::symlink_metadata(path).is_ok_and(|m| !m.is_file()) && !ours(path, target)
}

/// Make `path` a link to `target` (a member of the set `set`, not yet switched) in one
/// rename. A regular file at `path` (a log written before this protocol) is first hard
/// linked into the old set as that member if the set has none, so the old set keeps showing
/// it until the switch (best effort: not across file systems).
pub(super) fn place(path: &Path, target: &Path, set: &Path) -> io::Result<()> {
    if fs::read_link(path).is_ok_and(|to| to == target) {
        return Ok(());
    }
    if fs::symlink_metadata(path).is_ok_and(|m| m.is_file())
        && set.join(MARKER).is_file()
        && fs::symlink_metadata(target).is_err()
    {
        let _ = fs::hard_link(path, target);
    }
    let dir = parent(path);
    fs::create_dir_all(dir)?;
    let tmp = dir.join(temporary(path, "noslip-link-"));
    let _ = fs::remove_file(&tmp);
    symlink(target, &tmp)?;
    fs::rename(&tmp, path).inspect_err(|_| {
        let _ = fs::remove_file(&tmp);
    })
}

/// The directory of `path` (`.` for a bare name).
pub(super) fn parent(path: &Path) -> &Path {
    path.parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// `.NAME.KINDPID`: this process's temporary beside `path`.
pub(super) fn temporary(path: &Path, kind: &str) -> String {
    let name = path
        .file_name()
        .map_or_else(|| "file".into(), |n| n.to_string_lossy().into_owned());
    format!(".{name}.{kind}{}", std::process::id())
}

/// Remove the temporaries beside `path` (`.NAME.tmpPID`, `.NAME.noslip-link-PID`) left by
/// processes that no longer run. Files only; errors are ignored (a temporary that cannot be
/// removed now is removed by a later run).
pub fn remove_stale(path: &Path) {
    let Some(name) = path.file_name().and_then(|n| n.to_str()) else {
        return;
    };
    let Ok(entries) = fs::read_dir(parent(path)) else {
        return;
    };
    for entry in entries.flatten() {
        let file = entry.file_name();
        let Some(rest) = file
            .to_str()
            .and_then(|f| f.strip_prefix('.'))
            .and_then(|f| f.strip_prefix(name))
            .and_then(|f| f.strip_prefix('.'))
        else {
            continue;
        };
        let pid = rest
            .strip_prefix("tmp")
            .or_else(|| rest.strip_prefix("noslip-link-"))
            .and_then(|p| p.parse::<u32>().ok());
        let file_like = entry.file_type().is_ok_and(|t| !t.is_dir());
        if pid.is_some_and(|p| !super::running(p)) && file_like {
            let _ = fs::remove_file(entry.path());
        }
    }
}

#[cfg(unix)]
fn symlink(target: &Path, link: &Path) -> io::Result<()> {
    std::os::unix::fs::symlink(target, link)
}

#[cfg(windows)]
fn symlink(target: &Path, link: &Path) -> io::Result<()> {
    std::os::windows::fs::symlink_file(target, link)
}
