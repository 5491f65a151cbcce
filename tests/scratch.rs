//! Scratch directories for tests, removed when a test is done with them: at its end, and
//! also when it returns early (a compiler or an OpenCL platform missing: the test skips) or
//! panics. One file for the two test crates that use it: this one (`backend`) and the
//! command line's (`cli/tests/support`, which includes it by path).

use std::path::{Path, PathBuf};

/// A path in the temporary directory, unique to `name` and this process:
/// `noslip-{name}-{pid}`.
pub fn temp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("noslip-{name}-{}", std::process::id()))
}

/// A fresh empty directory at [`temp`]`(name)`, removed with its contents when the returned
/// [`Scratch`] is dropped.
pub fn scratch(name: &str) -> Scratch {
    let dir = temp(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

/// [`scratch`]'s directory: a path, removed with its contents on drop.
pub struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<std::ffi::OsStr> for Scratch {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.0.as_os_str()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        // Already removed by a test that checks its own removal, or never written: either
        // way nothing is left.
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
