//! `eom report`: the page's structure (every section and figure, the formulas as MathML with
//! their LaTeX), the numbers it shows against published values (the shimmy's stable interval
//! 0.3 < a/l < 0.7 from its closed form; the bicycle's weave and capsize speeds from the
//! benchmark of Meijaard et al., Proc. R. Soc. A 463 (2007)), and bad arguments.

mod common;
use common::eom;
use std::path::{Path, PathBuf};

/// An empty scratch directory of this test's own.
fn scratch(test: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("report-tests")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

/// Writes the report and returns its HTML.
fn report(args: &[&str], dir: &Path, name: &str) -> String {
    let mut all = vec!["report"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", dir.to_str().unwrap()]);
    let r = eom(&all);
    assert_eq!(r.code, 0, "eom {all:?}: {}", r.stderr);
    assert!(r.stdout.is_empty(), "{}", r.stdout);
    std::fs::read_to_string(dir.join(format!("{name}.html"))).expect("the page was written")
}

/// The numbers in the first column of the table after `heading`.
fn first_column_after(html: &str, heading: &str) -> Vec<f64> {
    let start = html
        .find(heading)
        .unwrap_or_else(|| panic!("no `{heading}`"));
    let table = &html[start..];
    let end = table.find("</table>").unwrap();
    table[..end]
        .split("<tr><td>")
        .skip(1)
        .filter_map(|row| row.split("</td>").next()?.parse().ok())
        .collect()
}

#[test]
fn the_shimmy_report_has_every_part_and_the_published_boundaries() {
    let dir = scratch("shimmy");
    let html = report(&["shimmy", "--sweep", "x=0:1:101"], &dir, "shimmy");
    assert!(html.starts_with("<!DOCTYPE html>"));
    for id in [
        "parameters",
        "items",
        "picture",
        "modes",
        "shapes",
        "io",
        "gains",
        "zeros",
        "bode",
        "time",
        "sweep",
        "closed",
    ] {
        assert!(
            html.contains(&format!("<h2 id=\"{id}\">")),
            "no section {id}"
        );
    }
    // Nothing is loaded from elsewhere.
    for remote in ["src=\"http", "href=\"http", "@import", "url("] {
        assert!(!html.contains(remote), "the page loads `{remote}`");
    }
    // Figures: model, pole map, ≥ 1 mode shape, Bode, step/impulse, free response, sweep,
    // root locus; each an inline SVG with drawn content.
    let figures: Vec<&str> = html.split("<figure>").skip(1).collect();
    assert!(figures.len() >= 8, "{} figures", figures.len());
    for f in &figures {
        assert!(
            f.trim_start().starts_with("<svg"),
            "{}",
            &f[..80.min(f.len())]
        );
        assert!(f.contains("<line") || f.contains("<polyline") || f.contains("<path"));
    }
    // The mode shapes are animated.
    assert!(html.contains("<animate attributeName=\"x1\""));
    // Boundaries at a/l = 0.3 and 0.7 (the closed form's roots).
    let b = first_column_after(&html, "boundary x");
    assert_eq!(b.len(), 2, "{b:?}");
    assert!(
        (b[0] - 0.3).abs() < 1e-8 && (b[1] - 0.7).abs() < 1e-8,
        "{b:?}"
    );
    // Closed forms: MathML with the LaTeX beside it.
    assert!(html.matches("<math display=\"block\">").count() >= 3);
    assert!(html.contains("<pre>") && html.contains("\\frac"));
}

#[test]
fn the_bicycle_report_shows_the_benchmark_speeds() {
    let dir = scratch("bicycle");
    let html = report(&["bicycle", "--sweep", "v=0:10:201"], &dir, "bicycle");
    let b = first_column_after(&html, "boundary v");
    assert_eq!(b.len(), 2, "{b:?}");
    // Weave and capsize speeds of the benchmark bicycle (Meijaard et al. 2007, the
    // closed-form values of docs/references.md §A), printed to ten digits.
    assert!((b[0] - 4.292_382_536_341_104).abs() < 1e-9, "{b:?}");
    assert!((b[1] - 6.024_262_015_388_359).abs() < 1e-9, "{b:?}");
    // Three views per mode shape for a 3-D model.
    assert!(html.contains("side view") && html.contains("front view") && html.contains("top view"));
    assert!(
        html.contains("class=\"centre\""),
        "no centre of rotation marked"
    );
}

#[test]
fn bad_report_arguments_fail_before_writing() {
    let dir = scratch("bad");
    let d = dir.to_str().unwrap();
    let r = eom(&["report", "shimmy", "--sweep", "nope=0:1:11", "-o", d]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stderr.contains("nope"), "{}", r.stderr);
    let r = eom(&["report", "shimmy", "--sweep", "x=0:1:1", "-o", d]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(std::fs::read_dir(&dir).unwrap().next().is_none());
}

/// The page goes through the safe writer of `eom codegen -o`: the output directory is created
/// only when its parent exists (and said so), a missing parent is an error before any work and
/// nothing is created, an unchanged page is left alone, a FIFO without a reader does not block.
#[test]
fn the_page_is_written_safely() {
    let dir = scratch("safe");
    let missing = dir.join("no/such");
    let r = eom(&["report", "smd", "-o", missing.to_str().unwrap()]);
    assert_eq!(r.code, 1, "{}", r.stderr);
    let parent = dir.join("no").display().to_string();
    assert!(
        r.stderr.contains(&parent) && r.stderr.contains("does not exist"),
        "{}",
        r.stderr
    );
    assert!(!dir.join("no").exists(), "a directory was created");

    let out = dir.join("pages");
    let d = out.to_str().unwrap();
    let first = eom(&["report", "smd", "-o", d]);
    assert_eq!(first.code, 0, "{}", first.stderr);
    assert!(
        first.stderr.contains(&format!("created directory {d}")),
        "{}",
        first.stderr
    );
    assert!(first.stderr.contains("wrote "), "{}", first.stderr);
    let page = std::fs::read_to_string(out.join("smd.html")).expect("the page");
    assert!(page.contains("<html"), "not a page");
    let second = eom(&["report", "smd", "-o", d]);
    assert_eq!(second.code, 0, "{}", second.stderr);
    assert!(second.stderr.contains("unchanged"), "{}", second.stderr);
    assert!(!second.stderr.contains("created"), "{}", second.stderr);

    // A regular file where the directory should be.
    let file = dir.join("a-file");
    std::fs::write(&file, "x").expect("file");
    let r = eom(&["report", "smd", "-o", file.to_str().unwrap()]);
    assert_eq!(r.code, 1, "{}", r.stderr);
    assert!(r.stderr.contains("not a directory"), "{}", r.stderr);

    #[cfg(unix)]
    {
        let fifo_dir = dir.join("fifo");
        std::fs::create_dir(&fifo_dir).expect("fifo dir");
        let made = std::process::Command::new("mkfifo")
            .arg(fifo_dir.join("smd.html"))
            .status()
            .expect("mkfifo runs");
        assert!(made.success());
        let (tx, rx) = std::sync::mpsc::channel();
        let path = fifo_dir.display().to_string();
        std::thread::spawn(move || {
            tx.send(eom(&["report", "smd", "-o", &path])).ok();
        });
        let r = rx
            .recv_timeout(std::time::Duration::from_secs(120))
            .expect("eom report -o DIR with a FIFO returns instead of blocking");
        assert_eq!(r.code, 1, "{}", r.stderr);
        assert!(r.stderr.contains("no process is reading"), "{}", r.stderr);
    }
    std::fs::remove_dir_all(&dir).ok();
}
