//! The events log file of `noslip simulate --log FILE`: complete or absent.
//!
//! Lines go to a temporary file beside `FILE` (`.NAME.tmpPID`, in `FILE`'s directory, which is
//! created if missing); [`LogFile::finish`] flushes it, syncs it to disk and renames it over
//! `FILE`. The first write error drops the temporary file at once, and later writes are
//! discarded, so the run goes on to its end and its summary is still written; the error is
//! returned by [`LogFile::finish`]. A log that is never finished (an early error) removes its
//! temporary file when dropped. When `FILE` exists and is not a regular file (`/dev/stdout`,
//! a pipe, a device, a symbolic link), lines are written to it directly: a stream cannot be
//! replaced atomically, and renaming over a link would replace the link, not its target.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// See the module docs.
#[derive(Debug)]
pub struct LogFile {
    path: PathBuf,
    /// The temporary file, `None` when writing to a stream directly.
    tmp: Option<PathBuf>,
    writer: Option<BufWriter<File>>,
    error: Option<io::Error>,
}

impl LogFile {
    /// Open the log for `path` (creating its directory).
    pub fn create(path: &Path) -> io::Result<LogFile> {
        let stream = std::fs::symlink_metadata(path).is_ok_and(|m| !m.is_file());
        if stream {
            let file = std::fs::OpenOptions::new()
                .write(true)
                .create(true)
                .truncate(true)
                .open(path)?;
            return Ok(LogFile {
                path: path.to_path_buf(),
                tmp: None,
                writer: Some(BufWriter::new(file)),
                error: None,
            });
        }
        let dir = path
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        std::fs::create_dir_all(dir)?;
        let name = path
            .file_name()
            .map_or_else(|| "log".into(), |n| n.to_string_lossy().into_owned());
        let tmp = dir.join(format!(".{name}.tmp{}", std::process::id()));
        let file = File::create(&tmp)?;
        Ok(LogFile {
            path: path.to_path_buf(),
            tmp: Some(tmp),
            writer: Some(BufWriter::new(file)),
            error: None,
        })
    }

    /// Record the first error, drop the writer and the temporary file.
    fn fail(&mut self, e: io::Error) {
        self.writer = None;
        if let Some(tmp) = self.tmp.take() {
            let _ = std::fs::remove_file(tmp);
        }
        self.error.get_or_insert(e);
    }

    /// Flush, sync and publish the log; the first write error if there was one (the log is
    /// then absent).
    pub fn finish(mut self) -> io::Result<()> {
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        let mut writer = self.writer.take().expect("a log that has not failed");
        let done = writer
            .flush()
            .and_then(|()| match &self.tmp {
                Some(_) => writer.get_ref().sync_all(),
                None => Ok(()),
            })
            .and_then(|()| match &self.tmp {
                Some(tmp) => std::fs::rename(tmp, &self.path),
                None => Ok(()),
            });
        drop(writer);
        match done {
            Ok(()) => {
                self.tmp = None;
                Ok(())
            }
            Err(e) => {
                self.fail(e);
                Err(self.error.take().expect("just recorded"))
            }
        }
    }
}

impl Write for LogFile {
    /// Writes go to the temporary file; after an error they are discarded (and succeed), so
    /// the run is not stopped by its log.
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        if let Some(w) = &mut self.writer {
            if let Err(e) = w.write_all(buf) {
                self.fail(e);
            }
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> io::Result<()> {
        if let Some(w) = &mut self.writer {
            if let Err(e) = w.flush() {
                self.fail(e);
            }
        }
        Ok(())
    }
}

impl Drop for LogFile {
    fn drop(&mut self) {
        self.writer = None;
        if let Some(tmp) = self.tmp.take() {
            let _ = std::fs::remove_file(tmp);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("noslip-log-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn the_log_appears_only_when_finished_in_a_new_directory() {
        let d = dir("finish");
        let path = d.join("sub").join("events.jsonl");
        let mut log = LogFile::create(&path).unwrap();
        writeln!(log, "one").unwrap();
        assert!(!path.exists(), "not published before finish");
        log.finish().unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "one\n");
        let names: Vec<_> = std::fs::read_dir(d.join("sub")).unwrap().collect();
        assert_eq!(names.len(), 1, "no temporary file left");
        std::fs::remove_dir_all(d).unwrap();
    }

    #[test]
    fn an_unfinished_log_leaves_nothing() {
        let d = dir("drop");
        let path = d.join("events.jsonl");
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(&path, "old\n").unwrap();
        {
            let mut log = LogFile::create(&path).unwrap();
            writeln!(log, "new").unwrap();
        }
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old\n");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        std::fs::remove_dir_all(d).unwrap();
    }

    #[test]
    fn devices_and_links_are_written_directly() {
        use std::os::unix::fs::FileTypeExt;
        let mut log = LogFile::create(Path::new("/dev/null")).unwrap();
        writeln!(log, "gone").unwrap();
        log.finish().unwrap();
        assert!(std::fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device());
        // A link stays a link; its target gets the lines.
        let d = dir("link");
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("target.jsonl"), "a much longer old content\n").unwrap();
        std::os::unix::fs::symlink("target.jsonl", d.join("link.jsonl")).unwrap();
        let mut log = LogFile::create(&d.join("link.jsonl")).unwrap();
        writeln!(log, "new").unwrap();
        log.finish().unwrap();
        assert!(std::fs::symlink_metadata(d.join("link.jsonl"))
            .unwrap()
            .is_symlink());
        assert_eq!(
            std::fs::read_to_string(d.join("target.jsonl")).unwrap(),
            "new\n"
        );
        std::fs::remove_dir_all(d).unwrap();
    }
}
