//! Output files and standard output for the commands.
//!
//! [`Output::open`] is called before any work: an `--out` that cannot be written (a directory,
//! a missing or read-only folder) is reported at once, not after a long render. The bytes go to
//! a temporary file next to the target, renamed over it only once everything is written, so a
//! failed run never leaves a half-written file nor clobbers the previous one. A target that
//! exists and is not a regular file (`/dev/stdout`, a FIFO) is written directly.
//!
//! [`print()`] writes to standard output and treats a closed pipe (`zrow-sim convert … | head`)
//! as the reader having seen enough: the command ends quietly, with success, instead of
//! panicking as `println!` does.

use crate::SimError;
use std::fs::{File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// A file being written; see the module doc.
#[derive(Debug)]
pub struct Output {
    path: PathBuf,
    file: File,
    /// The temporary file renamed over `path` at the end, or `None` when `path` is written
    /// directly.
    temp: Option<PathBuf>,
}

impl Output {
    /// Checks that `path` can be written and opens what will be written. Errors name `path`.
    pub fn open(path: &Path) -> Result<Self, SimError> {
        let error = |source: io::Error| SimError::Io {
            path: path.display().to_string(),
            action: "write",
            source,
        };
        if let Ok(meta) = std::fs::metadata(path) {
            if meta.is_dir() {
                return Err(error(io::Error::new(
                    io::ErrorKind::InvalidInput,
                    "is a directory",
                )));
            }
            if !meta.is_file() {
                let file = OpenOptions::new().write(true).open(path).map_err(error)?;
                return Ok(Output {
                    path: path.to_owned(),
                    file,
                    temp: None,
                });
            }
        }
        let name = path
            .file_name()
            .ok_or_else(|| error(io::Error::new(io::ErrorKind::InvalidInput, "no file name")))?;
        let mut temp_name = std::ffi::OsString::from(".");
        temp_name.push(name);
        temp_name.push(format!(".{}.part", std::process::id()));
        let temp = path.with_file_name(temp_name);
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&temp)
            .map_err(error)?;
        Ok(Output {
            path: path.to_owned(),
            file,
            temp: Some(temp),
        })
    }

    /// Writes `bytes` and puts the file in place.
    pub fn write(mut self, bytes: &[u8]) -> Result<(), SimError> {
        let error = |source: io::Error| SimError::Io {
            path: self.path.display().to_string(),
            action: "write",
            source,
        };
        self.file
            .write_all(bytes)
            .and_then(|()| self.file.flush())
            .map_err(error)?;
        if let Some(temp) = self.temp.take() {
            if let Err(e) = std::fs::rename(&temp, &self.path) {
                let _ = std::fs::remove_file(&temp);
                return Err(error(e));
            }
        }
        Ok(())
    }
}

impl Drop for Output {
    /// A run that failed before [`Output::write`] leaves nothing behind.
    fn drop(&mut self) {
        if let Some(temp) = self.temp.take() {
            let _ = std::fs::remove_file(temp);
        }
    }
}

/// Writes `text` and a newline to standard output. A closed pipe is not an error (the reader
/// has what it wanted); any other failure is.
pub fn print(text: &str) -> Result<(), SimError> {
    let mut out = io::stdout().lock();
    match writeln!(out, "{text}").and_then(|()| out.flush()) {
        Err(e) if e.kind() != io::ErrorKind::BrokenPipe => Err(SimError::Io {
            path: "standard output".into(),
            action: "write",
            source: e,
        }),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("zrow-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn bad_targets_fail_before_any_work() {
        let d = dir("bad");
        for (path, says) in [
            (d.clone(), "is a directory"),
            (d.join("missing/a.png"), "No such file"),
        ] {
            let e = Output::open(&path).unwrap_err().to_string();
            assert!(
                e.contains(&path.display().to_string()) && e.contains(says),
                "{e}"
            );
        }
        std::fs::remove_dir_all(d).unwrap();
    }

    #[test]
    fn the_target_changes_only_when_written() {
        let d = dir("swap");
        let target = d.join("a.png");
        std::fs::write(&target, b"old").unwrap();
        let out = Output::open(&target).unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        drop(out); // a failed run
        assert_eq!(std::fs::read(&target).unwrap(), b"old");
        Output::open(&target).unwrap().write(b"new").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        let left: Vec<_> = std::fs::read_dir(&d).unwrap().collect();
        assert_eq!(left.len(), 1, "no temporary file left behind");
        std::fs::remove_dir_all(d).unwrap();
    }
}
