//! The one writer of every file eom writes — generated code, exported models, reports, plots,
//! bench tables, matrices. Every new output goes through it:
//!
//! * [`write_output`] for a path the user named (`-o FILE`, `--plot FILE.svg`);
//! * [`write_chosen`] for a name eom chose inside a directory the user named (`eom report -o
//!   DIR` writes `DIR/MODEL.html`, `eom bench … -o DIR` its tables);
//! * [`status_line`] for the line to print on standard error (never on standard output, which
//!   may be the output itself: `-o /dev/stdout`).
//!
//! What happens:
//!
//! * A regular file (or a new one) is written to a temporary file beside it
//!   (`.NAME.eom-PID-K.tmp`), synced, and renamed over it: a failed or interrupted write
//!   leaves the old file or the new one, never a torn one. On SIGINT, SIGTERM or SIGHUP
//!   during the write the temporary file is removed before the process ends as the signal
//!   would end it. The replaced file's permissions are kept.
//! * A read-only regular file is not replaced (an error), as writing into it would fail.
//! * A regular file that already holds exactly these bytes is not touched
//!   ([`Written::Unchanged`]); it is read only when it has their size.
//! * A symbolic link the user named is followed: its target is replaced, the link stays. A
//!   name eom chose is never followed: a link there is replaced by the file and its target is
//!   left alone ([`Written::ReplacedLink`]).
//! * A device, FIFO or socket — and any path under `/dev` or `/proc`, such as `/dev/stdout` —
//!   cannot be renamed into: it is opened without blocking and written directly (appending,
//!   so that `-o /dev/stdout >> log` appends). `/dev/full` fails at once with "No space left
//!   on device", a FIFO without a reader with a message saying so, a reader that takes no data
//!   for 10 s with a time-out.
//! * A missing directory is an error naming it, never created (the one exception, the
//!   directory `eom report -o DIR` is given, is created by [`create_output_dir`] when its
//!   parent exists, and said so).

use std::fs::{File, OpenOptions};
use std::io::{ErrorKind, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use crate::error::CliError;

/// What a write did.
// `Written::Written` is the name the callers have used since the first writer.
#[allow(clippy::enum_variant_names)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Written {
    /// The file already held exactly these bytes: not touched.
    Unchanged,
    /// The bytes were written.
    Written,
    /// A symbolic link stood at a name eom chose: it was replaced by the file, its target
    /// left alone.
    ReplacedLink,
}

/// The status line for standard error: `wrote PATH`, `unchanged PATH`, …, with a line feed.
pub fn status_line(path: &Path, written: Written) -> String {
    let path = eom_text::escaped(&path.display().to_string()).into_owned();
    match written {
        Written::Written => format!("wrote {path}\n"),
        Written::Unchanged => format!("unchanged {path} (it already holds this output)\n"),
        Written::ReplacedLink => format!(
            "wrote {path} (a symbolic link was there: replaced by the file, its target left \
             untouched)\n"
        ),
    }
}

/// How long a non-regular output (a FIFO, a terminal) may refuse more data before the write
/// is abandoned with an error.
const STALL_LIMIT: Duration = Duration::from_secs(10);

/// Links followed from a path the user named before giving up (as the kernel's `ELOOP`).
const MAX_LINKS: usize = 40;

fn io_error(path: &Path, source: std::io::Error) -> CliError {
    CliError::Io {
        path: eom_text::escaped(&path.display().to_string()).into_owned(),
        source,
    }
}

fn error(path: &Path, kind: ErrorKind, why: String) -> CliError {
    io_error(path, std::io::Error::new(kind, why))
}

/// Writes `bytes` to `path`, a path the user named (see the module documentation).
///
/// Errors: [`CliError::Io`] naming the path (or its missing directory) for every failure,
/// including a device that refuses the data (`/dev/full`: "No space left on device") and a
/// FIFO without a reader.
pub fn write_output(path: &Path, bytes: impl AsRef<[u8]>) -> Result<Written, CliError> {
    write(path, bytes.as_ref(), false)
}

/// Writes `bytes` to `path`, a name eom chose inside a directory the user named: a symbolic
/// link there is not followed but replaced.
pub fn write_chosen(path: &Path, bytes: impl AsRef<[u8]>) -> Result<Written, CliError> {
    write(path, bytes.as_ref(), true)
}

fn write(path: &Path, bytes: &[u8], chosen: bool) -> Result<Written, CliError> {
    check_directory(path)?;
    if is_stream_path(path) {
        write_stream(path, bytes)?;
        return Ok(Written::Written);
    }
    let target = if chosen {
        path.to_path_buf()
    } else {
        let t = resolve_links(path)?;
        check_directory(&t)?;
        t
    };
    let meta = std::fs::symlink_metadata(&target).ok();
    let Some(m) = meta else {
        replace(&target, bytes, None)?;
        return Ok(Written::Written);
    };
    let kind = m.file_type();
    if kind.is_dir() {
        return Err(error(
            &target,
            ErrorKind::IsADirectory,
            "is a directory".into(),
        ));
    }
    if kind.is_symlink() {
        replace(&target, bytes, None)?;
        return Ok(Written::ReplacedLink);
    }
    if !kind.is_file() {
        write_stream(&target, bytes)?;
        return Ok(Written::Written);
    }
    if m.len() == bytes.len() as u64 && same_content(&target, bytes) {
        return Ok(Written::Unchanged);
    }
    // Renaming would replace a file its owner made read-only, which writing in place (what
    // the user expects of `-o`) would not.
    if m.permissions().readonly() {
        return Err(error(
            &target,
            ErrorKind::PermissionDenied,
            "the file is read-only: not replaced".into(),
        ));
    }
    replace(&target, bytes, Some(m.permissions()))?;
    Ok(Written::Written)
}

/// The directory of an output must exist: eom never creates it silently.
fn check_directory(path: &Path) -> Result<(), CliError> {
    match path.parent().filter(|d| !d.as_os_str().is_empty()) {
        Some(dir) if !dir.is_dir() => Err(error(
            dir,
            ErrorKind::NotFound,
            format!(
                "the directory of the output file {} does not exist (create it first)",
                eom_text::escaped(&path.display().to_string())
            ),
        )),
        _ => Ok(()),
    }
}

/// Paths that name a stream rather than a file (under `/dev` and `/proc`), even when they lead
/// to one (`/dev/stdout` redirected to a file): renaming into them would replace the wrong
/// thing.
pub fn is_stream_path(path: &Path) -> bool {
    path.starts_with("/dev") || path.starts_with("/proc")
}

/// The file a user-named path ends at, following symbolic links (a dangling link gives its
/// missing target, which is then created).
fn resolve_links(path: &Path) -> Result<PathBuf, CliError> {
    let mut p = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = std::fs::read_link(&p).map_err(|e| io_error(&p, e))?;
                p = match p.parent() {
                    Some(dir) if to.is_relative() => dir.join(to),
                    _ => to,
                };
            }
            _ => return Ok(p),
        }
    }
    Err(error(
        path,
        ErrorKind::InvalidInput,
        format!("more than {MAX_LINKS} symbolic links in a row"),
    ))
}

/// Temporary files being written, removed by the signal handler.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// Numbers the temporary files of this process.
static COUNTER: AtomicUsize = AtomicUsize::new(0);

fn pending() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

/// Writes `bytes` to a temporary file beside `target` and renames it over `target`.
fn replace(
    target: &Path,
    bytes: &[u8],
    permissions: Option<std::fs::Permissions>,
) -> Result<(), CliError> {
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let Some(name) = target.file_name() else {
        return Err(error(
            target,
            ErrorKind::InvalidInput,
            "not a file name".into(),
        ));
    };
    let name = name.to_string_lossy();
    // Within the file-name limit of 255 bytes, however long the name.
    let short = &name[..name.floor_char_boundary(180)];
    let tmp = dir.join(format!(
        ".{short}.eom-{}-{}.tmp",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    remove_on_signal();
    pending().push(tmp.clone());
    let written = write_new(&tmp, bytes, permissions).map_err(|e| {
        io_error(
            target,
            std::io::Error::new(
                e.kind(),
                format!(
                    "writing the temporary file {} failed (eom writes beside the output and \
                     renames into place): {e}",
                    eom_text::escaped(&tmp.display().to_string())
                ),
            ),
        )
    });
    // The rename and the bookkeeping under the lock: a signal handler that holds it sees the
    // temporary file either still there or renamed.
    let mut list = pending();
    let result =
        written.and_then(|()| std::fs::rename(&tmp, target).map_err(|e| io_error(target, e)));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    list.retain(|p| p != &tmp);
    drop(list);
    // The rename itself durable too (best effort: not every file system syncs directories).
    if result.is_ok()
        && let Ok(d) = File::open(dir)
    {
        let _ = d.sync_all();
    }
    result
}

fn write_new(
    tmp: &Path,
    bytes: &[u8],
    permissions: Option<std::fs::Permissions>,
) -> std::io::Result<()> {
    let mut f = OpenOptions::new().write(true).create_new(true).open(tmp)?;
    if let Some(p) = permissions {
        f.set_permissions(p)?;
    }
    f.write_all(bytes)?;
    f.sync_data()
}

/// Installs, once, the handler that removes the temporary files on SIGINT, SIGTERM and
/// SIGHUP and then ends the process as the signal would. A signal this process ignores (a
/// background job's SIGINT, `nohup`'s SIGHUP) stays ignored.
#[cfg(unix)]
fn remove_on_signal() {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let ignored = ignored_signals();
        let wanted: Vec<i32> = [SIGINT, SIGTERM, SIGHUP]
            .into_iter()
            .filter(|s| ignored & (1u64 << (s - 1)) == 0)
            .collect();
        let Ok(mut signals) = signal_hook::iterator::Signals::new(&wanted) else {
            return;
        };
        let _ = std::thread::Builder::new()
            .name("eom-signals".into())
            .spawn(move || {
                if let Some(signal) = signals.forever().next() {
                    let list = pending();
                    for p in list.iter() {
                        let _ = std::fs::remove_file(p);
                    }
                    let _ = signal_hook::low_level::emulate_default_handler(signal);
                    std::process::exit(128 + signal);
                }
            });
    });
}

#[cfg(not(unix))]
fn remove_on_signal() {}

/// The signals this process ignores (bit `s − 1` for signal `s`), from `/proc/self/status`;
/// all of them where that cannot be read, so that no handler changes a disposition unseen.
#[cfg(unix)]
fn ignored_signals() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find_map(|l| l.strip_prefix("SigIgn:"))
                .and_then(|h| u64::from_str_radix(h.trim(), 16).ok())
        })
        .unwrap_or(u64::MAX)
}

/// Writes to a device, FIFO or socket directly, without blocking on a missing reader.
fn write_stream(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    let mut opts = OpenOptions::new();
    opts.append(true);
    nonblocking(&mut opts);
    let file = opts.open(path).map_err(|e| io_error(path, explain(e)))?;
    write_patiently(file, bytes).map_err(|e| io_error(path, explain(e)))
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
            return Err(error(
                dir,
                ErrorKind::NotADirectory,
                "is not a directory".into(),
            ));
        }
        Err(e) if e.kind() != ErrorKind::NotFound => return Err(io_error(dir, e)),
        Err(_) => {}
    }
    if let Some(parent) = dir.parent().filter(|d| !d.as_os_str().is_empty())
        && !parent.is_dir()
    {
        return Err(error(
            parent,
            ErrorKind::NotFound,
            format!(
                "the directory containing the output directory {} does not exist (create \
                 it first)",
                eom_text::escaped(&dir.display().to_string())
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

/// Whether the regular file at `path` holds exactly `bytes` (read up to its known size).
fn same_content(path: &Path, bytes: &[u8]) -> bool {
    let Ok(f) = File::open(path) else {
        return false;
    };
    let mut old = Vec::with_capacity(bytes.len());
    // One byte more than expected: a file that grew since its metadata was read differs.
    match f.take(bytes.len() as u64 + 1).read_to_end(&mut old) {
        Ok(_) => old == bytes,
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

/// Writes all of `data` to a non-blocking output, waiting for room in short sleeps and giving
/// up after [`STALL_LIMIT`] without progress. Flushed at the end so that a device's refusal
/// is reported.
fn write_patiently(mut f: File, mut data: &[u8]) -> std::io::Result<()> {
    let mut last_progress = Instant::now();
    while !data.is_empty() {
        match f.write(data) {
            Ok(0) => return Err(ErrorKind::WriteZero.into()),
            Ok(k) => {
                data = &data[k..];
                last_progress = Instant::now();
            }
            Err(e) if e.kind() == ErrorKind::Interrupted => {}
            Err(e) if e.kind() == ErrorKind::WouldBlock => {
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
    f.flush()
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

    fn scratch(tag: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("eom-output-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn leftovers(dir: &Path) -> Vec<String> {
        std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".tmp"))
            .collect()
    }

    #[test]
    fn unchanged_only_when_the_same_bytes_are_there() {
        let dir = scratch("unchanged");
        let p = dir.join("a.rs");
        assert_eq!(write_output(&p, "abc").unwrap(), Written::Written);
        assert_eq!(write_output(&p, "abc").unwrap(), Written::Unchanged);
        assert_eq!(write_output(&p, b"abd").unwrap(), Written::Written);
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "abd");
        let e = write_output(&dir.join("missing/b.rs"), "x").unwrap_err();
        assert!(e.to_string().contains("missing") && e.to_string().contains("does not exist"));
        assert!(!dir.join("missing").exists());
        assert!(leftovers(&dir).is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn links_are_followed_when_named_and_replaced_when_chosen() {
        use std::os::unix::fs::{PermissionsExt, symlink};
        let dir = scratch("links");
        let target = dir.join("target.txt");
        std::fs::write(&target, "old").unwrap();
        std::fs::set_permissions(&target, std::fs::Permissions::from_mode(0o640)).unwrap();
        let link = dir.join("link.txt");
        symlink("target.txt", &link).unwrap();
        // Named by the user: the target gets the bytes (and keeps its mode), the link stays.
        assert_eq!(write_output(&link, "new").unwrap(), Written::Written);
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        let mode = std::fs::metadata(&target).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o640);
        // Chosen by eom: the link is replaced, its target untouched.
        assert_eq!(write_chosen(&link, "page").unwrap(), Written::ReplacedLink);
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "new");
        assert!(std::fs::symlink_metadata(&link).unwrap().is_file());
        assert_eq!(std::fs::read_to_string(&link).unwrap(), "page");
        // A dangling link the user named: its target is created.
        symlink("made.txt", dir.join("dangling.txt")).unwrap();
        write_output(&dir.join("dangling.txt"), "made").unwrap();
        assert_eq!(
            std::fs::read_to_string(dir.join("made.txt")).unwrap(),
            "made"
        );
        assert!(leftovers(&dir).is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
