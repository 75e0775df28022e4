//! Writing a generated file (`eom codegen -o PATH`, `eom export -o PATH`, `eom report -o DIR`)
//! safely: the existing file is read (to leave it untouched when it already holds the text)
//! only when it is a regular file of exactly the new text's size; anything else (a device such
//! as `/dev/full`, a FIFO, a terminal) is opened for writing without blocking and written
//! once; a missing directory is an error naming it, never created silently (the one exception,
//! the output directory `eom report` is given, is created only when its parent exists, and
//! said so).

use std::fs::{File, OpenOptions};
use std::io::{ErrorKind, Read, Write};
use std::path::Path;
use std::time::{Duration, Instant};

use crate::error::CliError;

/// What [`write_output`] did.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Written {
    /// The file already held exactly this text: not touched.
    Unchanged,
    /// The text was written.
    Written,
}

/// How long a non-regular output (a FIFO, a terminal) may refuse more data before the write
/// is abandoned with an error.
const STALL_LIMIT: Duration = Duration::from_secs(10);

fn io_error(path: &Path, source: std::io::Error) -> CliError {
    CliError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// Writes `text` to `path` unless it is a regular file that already holds exactly `text`.
///
/// Errors: [`CliError::Io`] naming the path (or its missing directory) for every failure,
/// including a device that refuses the data (`/dev/full`: "No space left on device") and a
/// FIFO without a reader.
pub fn write_output(path: &Path, text: &str) -> Result<Written, CliError> {
    write_output_bytes(path, text.as_bytes())
}

/// [`write_output`] of binary data (`eom analyze --matrices FILE.npz`).
pub fn write_output_bytes(path: &Path, text: &[u8]) -> Result<Written, CliError> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty())
        && !dir.is_dir()
    {
        return Err(io_error(
            dir,
            std::io::Error::new(
                ErrorKind::NotFound,
                format!(
                    "the directory of the output file {} does not exist (create it first)",
                    path.display()
                ),
            ),
        ));
    }
    let meta = std::fs::metadata(path).ok();
    let regular = meta.as_ref().is_none_or(|m| m.is_file());
    if let Some(m) = &meta {
        if m.is_dir() {
            return Err(io_error(
                path,
                std::io::Error::new(ErrorKind::IsADirectory, "is a directory"),
            ));
        }
        if m.is_file() && m.len() == text.len() as u64 && same_content(path, text) {
            return Ok(Written::Unchanged);
        }
    }
    let mut opts = OpenOptions::new();
    opts.write(true);
    if regular {
        opts.create(true).truncate(true);
    } else {
        nonblocking(&mut opts);
    }
    let file = opts.open(path).map_err(|e| io_error(path, explain(e)))?;
    write_patiently(file, text, regular).map_err(|e| io_error(path, explain(e)))?;
    Ok(Written::Written)
}

/// An output directory named on the command line (`eom report -o DIR`), checked before the
/// work starts: `Ok(false)` when it is an existing directory, `Ok(true)` when it is missing
/// but its parent exists (then [`create_output_dir`] makes it once there is something to
/// write). Anything else is an error naming the path: a missing parent (never created), a
/// path that is not a directory.
pub fn check_output_dir(dir: &Path) -> Result<bool, CliError> {
    match std::fs::metadata(dir) {
        Ok(m) if m.is_dir() => return Ok(false),
        Ok(_) => {
            return Err(io_error(
                dir,
                std::io::Error::new(ErrorKind::NotADirectory, "is not a directory"),
            ));
        }
        Err(e) if e.kind() != ErrorKind::NotFound => return Err(io_error(dir, e)),
        Err(_) => {}
    }
    if let Some(parent) = dir.parent().filter(|d| !d.as_os_str().is_empty())
        && !parent.is_dir()
    {
        return Err(io_error(
            parent,
            std::io::Error::new(
                ErrorKind::NotFound,
                format!(
                    "the directory containing the output directory {} does not exist (create \
                     it first)",
                    dir.display()
                ),
            ),
        ));
    }
    Ok(true)
}

/// Creates the output directory [`check_output_dir`] found missing (one level: its parent
/// exists).
pub fn create_output_dir(dir: &Path) -> Result<(), CliError> {
    match std::fs::create_dir(dir) {
        Ok(()) => Ok(()),
        // Made in the meantime by someone else: as good.
        Err(e) if e.kind() == ErrorKind::AlreadyExists && dir.is_dir() => Ok(()),
        Err(e) => Err(io_error(dir, e)),
    }
}

/// Whether the regular file at `path` holds exactly `text` (read up to its known size).
fn same_content(path: &Path, text: &[u8]) -> bool {
    let Ok(f) = File::open(path) else {
        return false;
    };
    let mut old = Vec::with_capacity(text.len());
    // One byte more than expected: a file that grew since its metadata was read differs.
    match f.take(text.len() as u64 + 1).read_to_end(&mut old) {
        Ok(_) => old == text,
        Err(_) => false,
    }
}

#[cfg(unix)]
fn nonblocking(opts: &mut OpenOptions) {
    use std::os::unix::fs::OpenOptionsExt;
    opts.custom_flags(libc::O_NONBLOCK);
}

#[cfg(not(unix))]
fn nonblocking(_: &mut OpenOptions) {}

/// Writes all of `data`; on a non-blocking output, waits for room in short sleeps, giving up
/// after [`STALL_LIMIT`] without progress. Flushed at the end so that a device's refusal is
/// reported.
fn write_patiently(mut f: File, mut data: &[u8], regular: bool) -> std::io::Result<()> {
    let mut last_progress = Instant::now();
    while !data.is_empty() {
        match f.write(data) {
            Ok(0) => return Err(ErrorKind::WriteZero.into()),
            Ok(k) => {
                data = &data[k..];
                last_progress = Instant::now();
            }
            Err(e) if e.kind() == ErrorKind::Interrupted => {}
            Err(e) if e.kind() == ErrorKind::WouldBlock && !regular => {
                if last_progress.elapsed() > STALL_LIMIT {
                    return Err(std::io::Error::new(
                        ErrorKind::TimedOut,
                        format!("the reader took no data for {} s", STALL_LIMIT.as_secs()),
                    ));
                }
                std::thread::sleep(Duration::from_millis(5));
            }
            Err(e) => return Err(e),
        }
    }
    f.flush()?;
    if regular { f.sync_data() } else { Ok(()) }
}

/// A FIFO opened without a reader fails with ENXIO, whose standard text ("No such device or
/// address") does not say why.
fn explain(e: std::io::Error) -> std::io::Error {
    #[cfg(unix)]
    if e.raw_os_error() == Some(libc::ENXIO) {
        return std::io::Error::new(
            e.kind(),
            "no process is reading from this FIFO (start the reader first)",
        );
    }
    e
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unchanged_only_when_the_same_text_is_there() {
        let dir = std::env::temp_dir().join(format!("eom-output-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("a.rs");
        assert_eq!(write_output(&p, "abc").unwrap(), Written::Written);
        assert_eq!(write_output(&p, "abc").unwrap(), Written::Unchanged);
        assert_eq!(write_output(&p, "abd").unwrap(), Written::Written);
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "abd");
        let e = write_output(&dir.join("missing/b.rs"), "x").unwrap_err();
        assert!(e.to_string().contains("missing") && e.to_string().contains("does not exist"));
        assert!(!dir.join("missing").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
