//! A run's output files published as one set, and single files written atomically.
//!
//! [`Staging`] collects a run's files in a staging directory beside the output directory
//! `D`, then [`Staging::commit`] switches it in, so that a reader, or a run killed at any
//! moment (`kill -9`, a crash), finds in `D` the whole old set or the whole new set, never a
//! mix of the two:
//!
//! - **Marker.** Every directory noslip publishes holds the file [`MARKER`]. `D` is replaced
//!   only if it carries the marker, is empty, or does not exist; a non-empty directory
//!   without the marker is refused ([`PublishError::NotOurs`]): noslip never wipes a
//!   directory it did not create.
//! - **Switch.** On Linux, `renameat2(RENAME_EXCHANGE)` swaps the staging directory and `D`
//!   in one atomic step; the old set, now under the staging name, is then removed. Elsewhere,
//!   or where the file system refuses the exchange, `D` is renamed aside to
//!   `.NAME.noslip-old-PID`, the staging directory renamed to `D`, and the old set removed.
//! - **Recovery.** A run killed between those two renames leaves no `D` and the aside copy:
//!   the next publish to `D` first renames the aside copy back (the old set), then proceeds.
//! - **Temporaries.** The staging directory (`.NAME.noslip-new-PID`) is removed on every
//!   error path (a drop guard); the temporaries of killed runs (their process no longer
//!   exists) are removed by the next publish to the same `D`. A set is removed marker last,
//!   so a removal cut short leaves a directory the next run still recognises as noslip's.
//!
//! - **Side outputs.** A file of the run outside `D` ([`Staging::side`]: `simulate --log
//!   FILE`) is staged as a member of the set, and `FILE` is made a link to that member in
//!   `D` just before the switch, so `FILE` and `D` always show one run ([`link`]).
//!
//! Files are written with `sync_all` before the switch, so the switch never publishes a
//! file whose contents are still in flight.
//!
//! Test hook: the environment variable `NOSLIP_FAULT` names a step at which the process
//! aborts (as if killed there) or a write fails as on a full disk; see [`Fault`].

use std::fmt;
use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// The file that marks a directory as a noslip output directory, replaceable as a whole.
pub const MARKER: &str = ".noslip-output";

const MARKER_TEXT: &str = "This directory is a noslip output set: each run replaces it as a \
                           whole (see docs/reliability.md, \"Outputs\").\n";

/// Why a set could not be published.
#[derive(Debug)]
#[non_exhaustive]
pub enum PublishError {
    /// The output directory exists, is not empty and has no [`MARKER`]; or it is a file.
    NotOurs(PathBuf),
    /// The output path has no last component to name the set (`.`, `..`, `/`): the set is
    /// published by renaming a sibling directory onto it.
    NoName(PathBuf),
    /// An I/O failure at `path`.
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The failure.
        source: io::Error,
    },
}

impl fmt::Display for PublishError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PublishError::NotOurs(path) => write!(
                f,
                "{} exists and was not made by noslip (not an empty directory, no {MARKER} \
                 marker): refusing to replace it; choose another output directory or remove it",
                path.display()
            ),
            PublishError::NoName(path) => write!(
                f,
                "{} names no directory of its own (the set replaces a directory by name): give \
                 one, such as {}",
                path.display(),
                path.join("run").display()
            ),
            PublishError::Io { path, source } => write!(f, "{}: {source}", path.display()),
        }
    }
}

impl std::error::Error for PublishError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            PublishError::Io { source, .. } => Some(source),
            PublishError::NotOurs(_) | PublishError::NoName(_) => None,
        }
    }
}

fn at(path: &Path) -> impl FnOnce(io::Error) -> PublishError + '_ {
    move |source| PublishError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// A fault injected by the test hook `NOSLIP_FAULT=<name>`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Fault {
    /// `staged`: abort once the staging directory is complete, before the switch.
    Staged,
    /// `aside`: abort after `D` was renamed aside (the rename fallback only).
    Aside,
    /// `linked`: abort after the side outputs' links are in place, before the switch.
    Linked,
    /// `switched`: abort after the switch, before the old set is removed.
    Switched,
    /// `full-disk`: the first file staged after the marker fails with "no space left" after
    /// half its bytes.
    FullDisk,
}

impl Fault {
    fn from_env() -> Option<Fault> {
        match std::env::var("NOSLIP_FAULT").ok()?.as_str() {
            "staged" => Some(Fault::Staged),
            "aside" => Some(Fault::Aside),
            "linked" => Some(Fault::Linked),
            "switched" => Some(Fault::Switched),
            "full-disk" => Some(Fault::FullDisk),
            _ => None,
        }
    }
}

/// How the staging directory replaces `D`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Switch {
    /// `renameat2(RENAME_EXCHANGE)` (Linux); where the file system refuses it,
    /// [`Switch::Renames`].
    Exchange,
    /// Rename `D` aside, rename the staging directory to `D`.
    Renames,
}

/// What to do at a step where a fault may be injected.
enum Injected {
    /// Carry on.
    No,
    /// Stop here as a killed process would: nothing after this step runs, no cleanup.
    Kill,
}

/// The staging directory of one run's output set.
#[derive(Debug)]
pub struct Staging {
    target: PathBuf,
    dir: PathBuf,
    files: usize,
    /// Side outputs: (the path outside the set, the member it links to).
    links: Vec<(PathBuf, String)>,
    fault: Option<Fault>,
    /// In-process stand-in for a kill at `fault` (tests): stop instead of aborting.
    stop_at_fault: bool,
    /// Published or abandoned as if killed: the drop guard leaves the disk alone.
    done: bool,
}

impl Staging {
    /// Prepare to publish into `target`: check that it may be replaced, restore an old set a
    /// killed run left aside, remove stale temporaries, and create the staging directory
    /// (holding the marker) beside `target`.
    pub fn new(target: &Path) -> Result<Staging, PublishError> {
        Self::with_fault(target, Fault::from_env(), false)
    }

    fn with_fault(
        target: &Path,
        fault: Option<Fault>,
        stop_at_fault: bool,
    ) -> Result<Staging, PublishError> {
        let name = target
            .file_name()
            .and_then(|n| n.to_str())
            .ok_or_else(|| PublishError::NoName(target.to_path_buf()))?
            .to_string();
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        fs::create_dir_all(&parent).map_err(at(&parent))?;
        recover_and_clean(&parent, &name, target)?;
        if !replaceable(target)? {
            return Err(PublishError::NotOurs(target.to_path_buf()));
        }
        let dir = parent.join(temporary(&name, "new", std::process::id()));
        if dir.exists() {
            remove_set(&dir).map_err(at(&dir))?;
        }
        fs::create_dir(&dir).map_err(at(&dir))?;
        let staging = Staging {
            target: target.to_path_buf(),
            dir,
            files: 0,
            links: Vec::new(),
            fault,
            stop_at_fault,
            done: false,
        };
        staging.write_file(MARKER, MARKER_TEXT.as_bytes())?;
        Ok(staging)
    }

    /// The directory the set will be published as.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Where file `name` of the set is staged, for writers that take a path (write it
    /// completely before [`Staging::commit`]).
    pub fn path(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }

    /// Where to write the side output `path` (a file outside the set that belongs to it):
    /// the staged member `member`, with `path` made a link to it at [`Staging::commit`]; or
    /// `path` itself if it is a stream ([`link::is_stream`]: `/dev/stdout`, a pipe, a device,
    /// a link that is not noslip's), which cannot be published atomically. Removes the
    /// temporaries that killed runs left beside `path`.
    pub fn side(&mut self, path: &Path, member: &str) -> Result<PathBuf, PublishError> {
        let target = std::path::absolute(&self.target)
            .map_err(at(&self.target))?
            .join(member);
        if link::is_stream(path, &target) {
            return Ok(path.to_path_buf());
        }
        link::remove_stale(path);
        self.links.push((path.to_path_buf(), member.to_string()));
        Ok(self.path(member))
    }

    /// Stage file `name` with `contents` (written and synced).
    pub fn write(&mut self, name: &str, contents: &[u8]) -> Result<(), PublishError> {
        self.files += 1;
        if self.fault == Some(Fault::FullDisk) && self.files == 1 {
            let path = self.path(name);
            let mut file = fs::File::create(&path).map_err(at(&path))?;
            file.write_all(&contents[..contents.len() / 2])
                .map_err(at(&path))?;
            return Err(PublishError::Io {
                path,
                source: io::Error::from_raw_os_error(28), // ENOSPC
            });
        }
        self.write_file(name, contents)
    }

    fn write_file(&self, name: &str, contents: &[u8]) -> Result<(), PublishError> {
        let path = self.path(name);
        let mut file = fs::File::create(&path).map_err(at(&path))?;
        file.write_all(contents).map_err(at(&path))?;
        file.sync_all().map_err(at(&path))
    }

    fn injected(&mut self, step: Fault) -> Injected {
        if self.fault != Some(step) {
            return Injected::No;
        }
        if !self.stop_at_fault {
            std::process::abort();
        }
        self.done = true;
        Injected::Kill
    }

    /// Switch the staged set in as the target directory, and remove the old set.
    pub fn commit(self) -> Result<(), PublishError> {
        self.commit_with(if cfg!(target_os = "linux") {
            Switch::Exchange
        } else {
            Switch::Renames
        })
    }

    fn commit_with(mut self, switch: Switch) -> Result<(), PublishError> {
        if let Injected::Kill = self.injected(Fault::Staged) {
            return Ok(());
        }
        sync_dir(&self.dir);
        if !replaceable(&self.target)? {
            return Err(PublishError::NotOurs(self.target.clone()));
        }
        if !self.links.is_empty() {
            let set = std::path::absolute(&self.target).map_err(at(&self.target))?;
            for (path, member) in &self.links {
                link::place(path, &set.join(member), &set).map_err(at(path))?;
            }
            if let Injected::Kill = self.injected(Fault::Linked) {
                return Ok(());
            }
        }
        let old = if !self.target.exists() {
            fs::rename(&self.dir, &self.target).map_err(at(&self.target))?;
            None
        } else if switch == Switch::Exchange && exchange(&self.dir, &self.target).is_ok() {
            // The staging name now holds the old set.
            Some(self.dir.clone())
        } else {
            let aside = self
                .dir
                .with_file_name(temporary(&self.name(), "old", std::process::id()));
            fs::rename(&self.target, &aside).map_err(at(&self.target))?;
            if let Injected::Kill = self.injected(Fault::Aside) {
                return Ok(());
            }
            if let Err(e) = fs::rename(&self.dir, &self.target) {
                // Put the old set back; the staging directory goes with the guard.
                let _ = fs::rename(&aside, &self.target);
                return Err(at(&self.target)(e));
            }
            Some(aside)
        };
        self.done = true;
        if let Some(parent) = self.target.parent() {
            sync_dir(parent);
        }
        if let Injected::Kill = self.injected(Fault::Switched) {
            return Ok(());
        }
        if let Some(old) = old {
            remove_set(&old).map_err(at(&old))?;
        }
        Ok(())
    }

    fn name(&self) -> String {
        self.target
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
    }
}

impl Drop for Staging {
    fn drop(&mut self) {
        if !self.done {
            let _ = remove_set(&self.dir);
        }
    }
}

/// `.NAME.noslip-KIND-PID`: a temporary beside the output directory `NAME`.
fn temporary(name: &str, kind: &str, pid: u32) -> String {
    format!(".{name}.noslip-{kind}-{pid}")
}

/// The kind (`new` or `old`) and process id of a temporary of `name`, from its file name.
fn parse_temporary<'a>(file: &'a str, name: &str) -> Option<(&'a str, u32)> {
    let rest = file.strip_prefix('.')?.strip_prefix(name)?;
    let (kind, pid) = rest.strip_prefix(".noslip-")?.split_once('-')?;
    Some((kind, pid.parse().ok()?))
}

/// Whether another process `pid` still runs (Linux: `/proc`; elsewhere assumed gone). This
/// process's own temporaries of the target are leftovers: it publishes one set at a time.
fn running(pid: u32) -> bool {
    pid != std::process::id() && Path::new("/proc").join(pid.to_string()).exists()
}

/// Restore an old set left aside by a killed run (if `target` is missing), then remove the
/// temporaries of `name` left by processes that no longer run.
fn recover_and_clean(parent: &Path, name: &str, target: &Path) -> Result<(), PublishError> {
    let entries = match fs::read_dir(parent) {
        Ok(e) => e,
        Err(e) => return Err(at(parent)(e)),
    };
    let mut stale: Vec<(String, PathBuf)> = Vec::new();
    for entry in entries.flatten() {
        let file = entry.file_name();
        let Some(file) = file.to_str() else { continue };
        if let Some((kind, pid)) = parse_temporary(file, name) {
            let path = entry.path();
            let ours = path.join(MARKER).exists()
                || fs::read_dir(&path).is_ok_and(|mut d| d.next().is_none());
            if !running(pid) && ours {
                stale.push((kind.to_string(), path));
            }
        }
    }
    for (kind, path) in &stale {
        if kind == "old" && !target.exists() {
            fs::rename(path, target).map_err(at(target))?;
        }
    }
    for (_, path) in stale {
        if path.exists() {
            remove_set(&path).map_err(at(&path))?;
        }
    }
    Ok(())
}

/// Remove a set's directory, its marker last: a removal cut short still leaves a marked
/// directory, which the next publish recognises and removes.
fn remove_set(dir: &Path) -> io::Result<()> {
    for entry in fs::read_dir(dir)? {
        let entry = entry?;
        if entry.file_name() == MARKER {
            continue;
        }
        if entry.file_type()?.is_dir() {
            fs::remove_dir_all(entry.path())?;
        } else {
            fs::remove_file(entry.path())?;
        }
    }
    match fs::remove_file(dir.join(MARKER)) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => return Err(e),
        _ => {}
    }
    fs::remove_dir(dir)
}

/// `target` may be replaced: it does not exist, is an empty directory, or carries the marker.
fn replaceable(target: &Path) -> Result<bool, PublishError> {
    match fs::symlink_metadata(target) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => Ok(true),
        Err(e) => Err(at(target)(e)),
        Ok(m) if !m.is_dir() => Ok(false),
        Ok(_) => Ok(target.join(MARKER).is_file()
            || fs::read_dir(target).map_err(at(target))?.next().is_none()),
    }
}

/// Flush a directory's entries to disk (best effort: not every platform can).
fn sync_dir(dir: &Path) {
    if let Ok(d) = fs::File::open(dir) {
        let _ = d.sync_all();
    }
}

/// Swap two directories atomically (Linux `renameat2(RENAME_EXCHANGE)`).
#[cfg(target_os = "linux")]
fn exchange(a: &Path, b: &Path) -> io::Result<()> {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    let c = |p: &Path| {
        CString::new(p.as_os_str().as_bytes())
            .map_err(|_| io::Error::new(io::ErrorKind::InvalidInput, "a NUL byte in a path"))
    };
    let (a, b) = (c(a)?, c(b)?);
    // SAFETY: both paths are NUL-terminated strings that outlive the call; renameat2 reads
    // them and touches no other memory.
    let r = unsafe {
        libc::syscall(
            libc::SYS_renameat2,
            libc::AT_FDCWD,
            a.as_ptr(),
            libc::AT_FDCWD,
            b.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if r == 0 {
        Ok(())
    } else {
        Err(io::Error::last_os_error())
    }
}

#[cfg(not(target_os = "linux"))]
fn exchange(_: &Path, _: &Path) -> io::Result<()> {
    Err(io::Error::new(
        io::ErrorKind::Unsupported,
        "no atomic directory exchange on this platform",
    ))
}

/// Write `contents` to `path` atomically: a temporary file in the same directory, synced,
/// then renamed over `path`, so a reader never sees a half-written file and the old one is
/// kept until the new one is complete. On any error the temporary is removed; the
/// temporaries of killed runs beside `path` are removed first ([`link::remove_stale`]).
pub fn write_atomic(path: &Path, contents: &str) -> io::Result<()> {
    let dir = link::parent(path);
    fs::create_dir_all(dir)?;
    link::remove_stale(path);
    let tmp = dir.join(link::temporary(path, "tmp"));
    let written = fs::File::create(&tmp).and_then(|mut f| {
        f.write_all(contents.as_bytes())?;
        f.sync_all()
    });
    match written.and_then(|()| fs::rename(&tmp, path)) {
        Ok(()) => Ok(()),
        Err(e) => {
            let _ = fs::remove_file(&tmp);
            Err(e)
        }
    }
}

pub mod link;
#[cfg(test)]
mod tests;
