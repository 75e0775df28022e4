//! `eom codegen -o PATH` writes safely: a device that refuses data fails at once, a FIFO
//! does not block, an unchanged file is reported as such, a missing directory is an error.

mod common;

use common::eom;
use std::time::{Duration, Instant};

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("eom-output-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

#[cfg(target_os = "linux")]
#[test]
fn dev_full_fails_at_once_with_a_write_error() {
    let t = Instant::now();
    let r = eom(&["codegen", "smd", "-o", "/dev/full"]);
    assert_eq!(r.code, 1, "{}", r.stderr);
    assert!(r.stderr.contains("/dev/full"), "{}", r.stderr);
    assert!(r.stderr.to_lowercase().contains("no space"), "{}", r.stderr);
    assert!(t.elapsed() < Duration::from_secs(60), "{:?}", t.elapsed());
}

#[cfg(unix)]
#[test]
fn a_fifo_without_a_reader_does_not_block() {
    let dir = scratch("fifo");
    let fifo = dir.join("out.fifo");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    let (tx, rx) = std::sync::mpsc::channel();
    let path = fifo.display().to_string();
    std::thread::spawn(move || {
        tx.send(eom(&["codegen", "smd", "-o", &path])).ok();
    });
    let r = rx
        .recv_timeout(Duration::from_secs(120))
        .expect("eom codegen -o FIFO returns instead of blocking");
    assert_eq!(r.code, 1, "{}", r.stderr);
    assert!(r.stderr.contains("no process is reading"), "{}", r.stderr);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn unchanged_is_reported_and_missing_directories_are_not_created() {
    let dir = scratch("files");
    let out = dir.join("smd.rs");
    let path = out.display().to_string();
    let first = eom(&["codegen", "smd", "-o", &path]);
    assert_eq!(first.code, 0, "{}", first.stderr);
    assert!(first.stdout.is_empty(), "{}", first.stdout);
    assert!(first.stderr.starts_with("wrote "), "{}", first.stderr);
    let second = eom(&["codegen", "smd", "-o", &path]);
    assert_eq!(second.code, 0, "{}", second.stderr);
    assert!(second.stderr.starts_with("unchanged"), "{}", second.stderr);
    // Another content of the same path is written again.
    std::fs::write(&out, "// edited\n").expect("edit");
    let third = eom(&["codegen", "smd", "-o", &path]);
    assert!(third.stderr.starts_with("wrote "), "{}", third.stderr);
    let missing = dir.join("no/such/dir/smd.rs");
    let r = eom(&["codegen", "smd", "-o", &missing.display().to_string()]);
    assert_eq!(r.code, 1, "{}", r.stderr);
    assert!(r.stderr.contains("no/such/dir") && r.stderr.contains("does not exist"));
    assert!(!dir.join("no").exists(), "the directory was created");
    std::fs::remove_dir_all(&dir).ok();
}
