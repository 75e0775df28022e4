//! The report in a real browser: Debian's `chromium`, headless, loads the pages of the
//! shimmy and the bicycle, and the test checks that they rendered without a script or
//! console error, that every figure is an SVG with drawn content of nonzero extent (measured
//! by the browser's layout, `getBBox`), and that a screenshot is not blank.
//!
//! Without chromium the test is skipped with a message, unless `EOM_REQUIRE_BROWSER` is set
//! (CI sets it, and `.ci/run` installs chromium): then a missing browser fails.

mod common;
use common::eom;
use std::path::{Path, PathBuf};
use std::process::Command;

fn scratch(test: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("browser-tests")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

/// The browser, if installed (`EOM_CHROMIUM` overrides the name).
fn chromium() -> Option<String> {
    let names = match std::env::var("EOM_CHROMIUM") {
        Ok(n) => vec![n],
        Err(_) => vec!["chromium".into(), "chromium-browser".into()],
    };
    names.into_iter().find(|n| {
        Command::new(n)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
    })
}

/// Runs headless chromium on `page` with `args`; returns (stdout, stderr).
fn headless(browser: &str, page: &Path, profile: &Path, args: &[&str]) -> (String, String) {
    let url = format!("file://{}", page.display());
    let out = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--hide-scrollbars",
            &format!("--user-data-dir={}", profile.display()),
            "--virtual-time-budget=10000",
            "--enable-logging=stderr",
            "--v=0",
        ])
        .args(args)
        .arg(&url)
        .output()
        .expect("chromium runs");
    (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The value of `data-NAME="…"` on the dumped `<html>` element.
fn attribute<'a>(dom: &'a str, name: &str) -> Option<&'a str> {
    let key = format!("data-{name}=\"");
    let i = dom.find(&key)? + key.len();
    Some(&dom[i..i + dom[i..].find('"')?])
}

/// Whether a PNG has more than `min_fraction` of pixels that are not the background (the
/// colour of the first pixel).
fn not_blank(png: &Path, min_fraction: f64) -> bool {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(png).expect("the screenshot exists"),
    ));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size().expect("size")];
    let info = reader.next_frame(&mut buf).expect("a frame");
    let bytes = &buf[..info.buffer_size()];
    let px = info.color_type.samples();
    let background = &bytes[..px];
    let differing = bytes
        .chunks_exact(px)
        .filter(|p| p[..3.min(px)] != background[..3.min(px)])
        .count();
    differing as f64 / (bytes.len() / px) as f64 > min_fraction
}

fn check_page(browser: &str, dir: &Path, args: &[&str], name: &str) {
    let mut all = vec!["report"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", dir.to_str().unwrap()]);
    let r = eom(&all);
    assert_eq!(r.code, 0, "eom {all:?}: {}", r.stderr);
    let page = dir.join(format!("{name}.html"));
    let html = std::fs::read_to_string(&page).unwrap();
    let figures = html.matches("<figure><svg").count();
    assert!(figures >= 7, "{figures} figures in the page");

    let profile = dir.join("profile");
    let (dom, log) = headless(browser, &page, &profile, &["--dump-dom"]);
    assert!(
        dom.contains("<h1>"),
        "the page did not render: {dom:.300}\n{log}"
    );
    let title = dom
        .split("<title>")
        .nth(1)
        .and_then(|t| t.split("</title>").next())
        .expect("a title");
    assert!(
        !title.contains("EOM-ERROR"),
        "script or console error: {title}"
    );
    for line in log.lines() {
        let console = line.contains("CONSOLE") || line.contains(":console(");
        assert!(
            !(console || line.contains("Uncaught")),
            "console message: {line}"
        );
    }
    assert_eq!(attribute(&dom, "rendered"), Some("yes"), "{log}");
    assert_eq!(
        attribute(&dom, "figures"),
        Some(figures.to_string().as_str())
    );
    assert_eq!(attribute(&dom, "empty-svgs"), Some("0"));
    // Text measured by the browser's layout: inside its figure, over no other text, and no
    // heading or LaTeX cut off.
    let problems = attribute(&dom, "text-problems")
        .unwrap_or("")
        .replace("&quot;", "\"");
    for what in ["text-outside", "text-overlaps", "text-clipped"] {
        assert_eq!(
            attribute(&dom, what),
            Some("0"),
            "{name}: {what}: {problems}"
        );
    }

    let shot = dir.join(format!("{name}.png"));
    let (_, log) = headless(
        browser,
        &page,
        &profile,
        &[
            &format!("--screenshot={}", shot.display()),
            "--window-size=1280,2400",
        ],
    );
    assert!(shot.exists(), "no screenshot: {log}");
    assert!(not_blank(&shot, 0.02), "the screenshot is blank");
    // Kept for the pictures in docs/ when asked for.
    if let Ok(to) = std::env::var("EOM_SCREENSHOTS") {
        let _ = std::fs::copy(&shot, Path::new(&to).join(format!("report-{name}.png")));
    }
}

#[test]
fn reports_render_in_headless_chromium_without_errors() {
    let Some(browser) = chromium() else {
        assert!(
            std::env::var_os("EOM_REQUIRE_BROWSER").is_none(),
            "EOM_REQUIRE_BROWSER is set but chromium is not installed"
        );
        println!("skipped: chromium is not installed (apt-get install chromium)");
        return;
    };
    check_page(
        &browser,
        &scratch("shimmy"),
        &["shimmy", "--sweep", "x=0:1:101"],
        "shimmy",
    );
    check_page(
        &browser,
        &scratch("bicycle"),
        &["bicycle", "--sweep", "v=0:10:201"],
        "bicycle",
    );
}

/// The pictures of the complaints: the quarter car (a purely real locus over its
/// damping), the hanging double pendulum from its model file (a long title, undamped modes),
/// the undamped pendulum's sweep (real parts that are rounding noise).
#[test]
fn report_text_stays_inside_its_figures_for_more_models() {
    let Some(browser) = chromium() else {
        assert!(
            std::env::var_os("EOM_REQUIRE_BROWSER").is_none(),
            "EOM_REQUIRE_BROWSER is set but chromium is not installed"
        );
        println!("skipped: chromium is not installed (apt-get install chromium)");
        return;
    };
    let pendulum_file = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../models/double_pendulum.toml"
    );
    let cases: [(&str, Vec<&str>, &str); 3] = [
        (
            "quarter_car",
            vec!["quarter_car", "--sweep", "cs=100:4000:79"],
            "quarter_car",
        ),
        ("double_pendulum", vec![pendulum_file], "double_pendulum"),
        (
            "pendulum",
            vec!["pendulum", "--sweep", "g=1:10:21"],
            "pendulum",
        ),
    ];
    for (dir, args, name) in cases {
        check_page(&browser, &scratch(dir), &args, name);
    }
}
