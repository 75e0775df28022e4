//! Hostile input (issue 27), through the built binary: names with every control character,
//! names that are legal but full of quotes and comment delimiters through check, analyze,
//! export, codegen and report with the outputs loaded back; huge and unprintable text cut
//! short; symbolic links and FIFOs at every writer's output; SIGINT during a write; inputs too
//! large for the memory limit refused with their sizes. The generated code of hostile names
//! is compiled by the `tests` crate (`tests/build.rs`, `tests/tests/codegen/hostile.rs`).

mod common;

use common::{Run, eigenvalues, eom, eom_json};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eom-hostile-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

/// No character that could act on a terminal reaches standard error or output.
fn assert_printable(r: &Run) {
    for (what, text) in [("stderr", &r.stderr), ("stdout", &r.stdout)] {
        let bad = text
            .chars()
            .find(|&c| c != '\n' && c != '\t' && eom_text::is_unsafe(c));
        assert!(bad.is_none(), "{what} holds {bad:?}: {text:?}");
    }
}

/// The smd model file with `[model] name`, the body's name, the spring's name and a unit
/// replaced (TOML text: escapes allowed).
fn smd_with(model: &str, body: &str, spring: &str, unit: &str) -> String {
    format!(
        r#"[model]
name = "{model}"
[parameters]
m = {{ value = 1, unit = "{unit}", range = "> 0" }}
k = {{ value = 10, unit = "N/m", range = "> 0" }}
c = {{ value = 0.1, unit = "N s/m", range = "> 0" }}
[[body]]
name = "{body}"
mass = "m"
[[rigid_point]]
name = "slider"
between = ["{body}", "ground"]
forces = 2
moments = 3
axis = [0, 0, 1]
[[flex_point]]
name = "{spring}"
between = ["{body}", "ground"]
forces = 1
axis = [0, 0, 1]
stiffness = ["k", 0]
damping = ["c", 0]
[[actuator]]
name = "force"
between = ["{body}", "ground"]
ends = [[0, 0, 1], [0, 0, 0]]
[[sensor]]
name = "z"
between = ["{body}", "ground"]
ends = [[0, 0, 1], [0, 0, 0]]
"#
    )
}

/// Every character a name may not hold: C0, DEL, C1, line and paragraph separators, the
/// bidirectional controls.
fn unsafe_chars() -> Vec<char> {
    (0u32..0x20)
        .chain(0x7f..0xa0)
        .chain([0x2028, 0x2029, 0x061c, 0x200e, 0x200f])
        .chain(0x202a..=0x202e)
        .chain(0x2066..=0x2069)
        .filter_map(char::from_u32)
        .collect()
}

#[test]
fn every_control_character_in_a_name_is_refused_naming_the_field() {
    let dir = scratch("controls");
    let file = dir.join("m.toml");
    for (k, c) in unsafe_chars().into_iter().enumerate() {
        let esc = format!("\\u{:04X}", u32::from(c));
        // The model's name, a body's, an item's, a unit, in turn.
        let (text, field) = match k % 4 {
            0 => (
                smd_with(&format!("smd{esc}x"), "block", "spring", "kg"),
                "[model], field `name`",
            ),
            1 => (
                smd_with("smd", &format!("blo{esc}ck"), "spring", "kg"),
                "body #1, field `name`",
            ),
            2 => (
                smd_with("smd", "block", &format!("spr{esc}ing"), "kg"),
                "flex_point #1, field `name`",
            ),
            _ => (
                smd_with("smd", "block", "spring", &format!("k{esc}g")),
                "parameter `m`, field `unit`",
            ),
        };
        std::fs::write(&file, text).unwrap();
        let command: &[&str] = match k % 5 {
            0 => &["check"],
            1 => &["analyze"],
            2 => &["export"],
            3 => &["codegen", "-o", "/dev/null"],
            _ => &["report", "-o", "/dev/null/x"],
        };
        let mut args = vec![command[0], s(&file)];
        args.extend(&command[1..]);
        let r = eom(&args);
        assert_eq!(r.code, 2, "{c:?} {args:?}: {}", r.stderr);
        assert!(r.stderr.contains(field), "{c:?}: {}", r.stderr);
        assert!(
            r.stderr.contains(&format!("U+{:04X}", u32::from(c))),
            "{}",
            r.stderr
        );
        assert!(r.stdout.is_empty());
        assert_printable(&r);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// Names a model may hold, chosen to break out of TOML strings, Rust comments, string
/// literals and HTML: every command works on them, the export loads back to the same
/// eigenvalues, the generated code keeps them in comments and literals.
#[test]
fn legal_but_hostile_names_go_through_every_command() {
    let dir = scratch("legal");
    let file = dir.join("hostile.toml");
    let body = r#"blo\"ck \\ */ /* // <b>&amp;</b> ü 漢"#;
    let model = r#"smd\" pub fn injected() {} // ''' \"\"\" {{}}"#;
    std::fs::write(&file, smd_with(model, body, "spring */ #[x]", "kg \\\"")).unwrap();
    let f = s(&file);
    let check = eom(&["check", f]);
    assert_eq!(check.code, 0, "{}", check.stderr);
    assert!(
        check
            .stdout
            .contains("blo\"ck \\ */ /* // <b>&amp;</b> ü 漢"),
        "{}",
        check.stdout
    );
    let base = eigenvalues(&eom_json(&["analyze", f, "--format", "json"]));
    // The export loads back to the same model.
    let exported = dir.join("exported.toml");
    let r = eom(&["export", f, "-o", s(&exported)]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(
        r.stdout.is_empty() && r.stderr.starts_with("wrote "),
        "{r:?}",
        r = r.stderr
    );
    let again = eigenvalues(&eom_json(&["analyze", s(&exported), "--format", "json"]));
    assert_eq!(base, again);
    let text = std::fs::read_to_string(&exported).unwrap();
    assert_eq!(text.matches("[[flex_point]]").count(), 1, "{text}");
    // The generated code: the name only in comments (compiled in tests/tests/codegen/hostile.rs).
    let code = dir.join("hostile.rs");
    let r = eom(&["codegen", f, "-o", s(&code)]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let src = std::fs::read_to_string(&code).unwrap();
    for line in src.lines().filter(|l| l.contains("fn injected")) {
        assert!(
            line.trim_start().starts_with("//"),
            "outside a comment: {line}"
        );
    }
    assert!(
        src.contains(r#""blo\"ck \\ */ /* // <b>&amp;</b>"#),
        "BODY_NAMES"
    );
    // The report escapes the HTML.
    let r = eom(&["report", f, "-o", s(&dir)]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let page = std::fs::read_to_string(dir.join("hostile.html")).unwrap();
    assert!(
        !page.contains("<b>&amp;</b>") && page.contains("&lt;b&gt;"),
        "HTML not escaped"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_huge_unknown_key_with_escapes_is_shown_cut_and_escaped() {
    let dir = scratch("huge-key");
    let file = dir.join("m.toml");
    // TOML escapes: the key itself holds ESC and BEL.
    let key = format!("\\u001B[2J\\u0007{}", "k".repeat(10_000_000));
    let text = smd_with("smd", "block", "spring", "kg").replacen(
        "[[body]]\n",
        &format!("[[body]]\n\"{key}\" = 1\n"),
        1,
    );
    std::fs::write(&file, text).unwrap();
    let r = eom(&["check", s(&file)]);
    assert_eq!(r.code, 2, "{}", &r.stderr[..r.stderr.len().min(500)]);
    assert!(r.stderr.len() < 2000, "{} bytes of error", r.stderr.len());
    assert!(
        r.stderr.contains("unknown key `\\u{1b}[2J\\u{7}kkk"),
        "{}",
        r.stderr
    );
    assert!(r.stderr.contains("(10000005 characters)"), "{}", r.stderr);
    assert_printable(&r);
    // An expression of 10 MB that does not parse: the same.
    let text = smd_with("smd", "block", "spring", "kg").replace(
        "mass = \"m\"",
        &format!("mass = \"\\u001B m + {}\"", "1 + ".repeat(2_500_000)),
    );
    std::fs::write(&file, text).unwrap();
    let r = eom(&["check", s(&file)]);
    assert_eq!(r.code, 2);
    assert!(r.stderr.len() < 2000, "{} bytes of error", r.stderr.len());
    assert_printable(&r);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn starter_files_load_whatever_the_name() {
    let dir = scratch("new");
    for (k, name) in [
        "a\"b",
        "back\\slash",
        "ü 漢 'q' \"\"\"",
        "#[x] */",
        "a\u{2060}b",
    ]
    .into_iter()
    .enumerate()
    {
        let r = eom(&["new", name]);
        assert_eq!(r.code, 0, "{name:?}: {}", r.stderr);
        let file = dir.join(format!("n{k}.toml"));
        std::fs::write(&file, &r.stdout).unwrap();
        let c = eom(&["check", s(&file), "--format", "json"]);
        assert_eq!(c.code, 0, "{name:?}: {}\n{}", c.stderr, r.stdout);
        let exported = eom(&["export", s(&file)]);
        assert!(
            exported
                .stdout
                .contains(&format!("name = {}", toml_quote(name)))
        );
    }
    for name in ["a\nb", "a\r\nb", "a\rb", "a\u{1b}b", "a\u{202e}b"] {
        let r = eom(&["new", name]);
        assert_eq!(r.code, 2, "{name:?}");
        assert!(r.stdout.is_empty() && r.stderr.contains("the model name contains"));
        assert_printable(&r);
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// How the exporter quotes a string without control characters.
fn toml_quote(s: &str) -> String {
    format!("\"{}\"", s.replace('\\', "\\\\").replace('"', "\\\""))
}

#[test]
fn a_file_named_like_a_built_in_model_is_not_taken_silently() {
    let dir = scratch("shadow");
    std::fs::write(dir.join("shimmy"), "not a model").unwrap();
    let r = Command::new(env!("CARGO_BIN_EXE_eom"))
        .args(["check", "shimmy"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8(r.stderr).unwrap();
    assert!(r.status.success(), "{stderr}");
    assert!(
        stderr.contains("built-in model is used (write ./shimmy for the file)"),
        "{stderr}"
    );
    let r = Command::new(env!("CARGO_BIN_EXE_eom"))
        .args(["check", "./shimmy"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(r.status.code(), Some(2), "the file is read with ./");
    std::fs::remove_dir_all(&dir).ok();
}

// ------------------------------------------------------------------------------ writers

/// Every writer, as (arguments before the output path, option, file name): the output path
/// is put after the option.
fn writers() -> Vec<(Vec<&'static str>, &'static str, &'static str)> {
    vec![
        (vec!["codegen", "smd"], "-o", "out.rs"),
        (vec!["export", "smd"], "-o", "out.toml"),
        (vec!["analyze", "smd"], "--plot", "bode.svg"),
        (vec!["analyze", "smd"], "--plot-poles", "poles.svg"),
        (vec!["analyze", "smd"], "--plot-step", "step.svg"),
        (vec!["analyze", "smd"], "--plot-initial", "initial.svg"),
        (vec!["analyze", "quarter_car"], "--plot-modes", "modes.svg"),
        (
            vec!["sweep", "smd", "--param", "k=1:2:3"],
            "--plot",
            "sweep.svg",
        ),
        (
            vec!["sweep", "smd", "--param", "k=1:2:3"],
            "--plot-locus",
            "locus.svg",
        ),
    ]
}

fn run_writer(args: &[&str], option: &str, path: &Path) -> Run {
    let mut a: Vec<&str> = vec!["--quiet"];
    a.extend(args);
    a.extend([option, s(path)]);
    eom(&a)
}

#[cfg(unix)]
#[test]
fn a_symbolic_link_the_user_names_is_followed_and_kept() {
    let dir = scratch("links");
    for (args, option, name) in writers() {
        let target = dir.join(format!("target-{name}"));
        std::fs::write(&target, "old").unwrap();
        let link = dir.join(name);
        let _ = std::fs::remove_file(&link);
        std::os::unix::fs::symlink(&target, &link).unwrap();
        let r = run_writer(&args, option, &link);
        assert_eq!(r.code, 0, "{args:?} {option}: {}", r.stderr);
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        let new = std::fs::read_to_string(&target).unwrap();
        assert!(
            new.len() > 100,
            "{args:?} {option}: the target was not written"
        );
    }
    assert_no_temporaries(&dir);
    std::fs::remove_dir_all(&dir).ok();
}

#[cfg(unix)]
#[test]
fn a_link_where_eom_chooses_the_name_is_replaced_not_followed() {
    let dir = scratch("chosen");
    let victim = dir.join("victim.txt");
    std::fs::write(&victim, "precious").unwrap();
    let out = dir.join("report");
    std::fs::create_dir(&out).unwrap();
    std::os::unix::fs::symlink(&victim, out.join("smd.html")).unwrap();
    let r = eom(&["--quiet", "report", "smd", "-o", s(&out)]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(
        r.stderr.contains("a symbolic link was there"),
        "{}",
        r.stderr
    );
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
    let page = out.join("smd.html");
    assert!(std::fs::symlink_metadata(&page).unwrap().is_file());
    assert!(std::fs::read_to_string(&page).unwrap().contains("<html"));
    // The same for the files of `eom bench … -o DIR`.
    let bench = dir.join("bench");
    std::fs::create_dir(&bench).unwrap();
    std::os::unix::fs::symlink(&victim, bench.join("stress.md")).unwrap();
    let r = eom(&["--quiet", "bench", "stress", "--quick", "-o", s(&bench)]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
    assert!(
        std::fs::symlink_metadata(bench.join("stress.md"))
            .unwrap()
            .is_file()
    );
    assert_no_temporaries(&out);
    assert_no_temporaries(&bench);
    std::fs::remove_dir_all(&dir).ok();
}

#[cfg(unix)]
#[test]
fn a_fifo_without_a_reader_blocks_no_writer() {
    let dir = scratch("fifos");
    let mut cases: Vec<(Vec<&str>, &str, &str)> = writers();
    cases.push((vec!["report", "smd"], "-o", "."));
    for (args, option, name) in cases {
        let (path, fifo) = if name == "." {
            let d = dir.join("report");
            std::fs::create_dir_all(&d).unwrap();
            (d.clone(), d.join("smd.html"))
        } else {
            (dir.join(name), dir.join(name))
        };
        let _ = std::fs::remove_file(&fifo);
        let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
        assert!(made.success());
        let t = Instant::now();
        let r = run_writer(&args, option, &path);
        assert_eq!(r.code, 1, "{args:?} {option}: {}", r.stderr);
        assert!(r.stderr.contains("no process is reading"), "{}", r.stderr);
        assert!(t.elapsed() < Duration::from_secs(60));
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[cfg(target_os = "linux")]
#[test]
fn dev_stdout_gets_the_output_and_no_status_line() {
    for (args, option, _) in writers().into_iter().take(3) {
        let r = run_writer(&args, option, Path::new("/dev/stdout"));
        assert_eq!(r.code, 0, "{args:?} {option}: {}", r.stderr);
        assert!(
            !r.stdout.contains("wrote "),
            "{args:?}: {}",
            &r.stdout[..200]
        );
        let first = r.stdout.lines().next().unwrap_or_default();
        assert!(
            first.starts_with("// @generated")
                || first.starts_with("# smd")
                || first.starts_with("<svg"),
            "{args:?}: {first}"
        );
    }
}

fn assert_no_temporaries(dir: &Path) {
    for e in std::fs::read_dir(dir).unwrap() {
        let n = e.unwrap().file_name().to_string_lossy().into_owned();
        assert!(!n.ends_with(".tmp"), "left behind: {n}");
    }
}

/// A reader polling the output while `eom codegen chain300 -o FILE` (1 MB) replaces it sees
/// the old file or the complete new one, never an empty or partial one (a write in place
/// truncates first).
#[test]
fn a_replaced_file_is_never_seen_half_written() {
    let dir = scratch("atomic");
    let out = dir.join("chain.rs");
    let old = b"// the previous code\n".to_vec();
    std::fs::write(&out, &old).unwrap();
    let stop = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let watcher = {
        let (out, stop, old) = (out.clone(), stop.clone(), old.clone());
        std::thread::spawn(move || {
            let mut seen = std::collections::BTreeSet::new();
            while !stop.load(std::sync::atomic::Ordering::Relaxed) {
                if let Ok(b) = std::fs::read(&out) {
                    seen.insert(if b == old { 0 } else { b.len() });
                }
            }
            seen
        })
    };
    let r = eom(&["codegen", "chain300", "-o", s(&out)]);
    stop.store(true, std::sync::atomic::Ordering::Relaxed);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let new_len = std::fs::metadata(&out).unwrap().len() as usize;
    assert!(new_len > 500_000, "{new_len} bytes");
    let seen = watcher.join().unwrap();
    assert!(
        seen.iter().all(|&n| n == 0 || n == new_len),
        "sizes seen: {seen:?}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// SIGINT at moments spread around the end of `eom report chain20 --sweep k=1:2:30` (a page of
/// 1.5 MB; the writer before issue 27 left a torn page in about one run of twenty): the page
/// is always the old one or the complete new one, and no temporary file is left behind.
#[cfg(unix)]
#[test]
fn sigint_during_a_write_leaves_the_old_file_or_the_new_one() {
    let dir = scratch("sigint");
    let page = dir.join("chain20.html");
    let args = [
        "--quiet",
        "report",
        "chain20",
        "--sweep",
        "k=1:2:30",
        "-o",
        s(&dir),
    ];
    let t = Instant::now();
    let r = eom(&args);
    let full = t.elapsed();
    assert_eq!(r.code, 0, "{}", r.stderr);
    let new = std::fs::read(&page).unwrap();
    assert!(new.len() > 1_000_000, "{} bytes", new.len());
    let runs = 30u32;
    let (mut old_seen, mut new_seen) = (0, 0);
    for k in 0..runs {
        std::fs::write(&page, "<p>the previous page</p>").unwrap();
        let mut child = Command::new(env!("CARGO_BIN_EXE_eom"))
            .args(args)
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(full.mul_f64(0.7 + 0.6 * f64::from(k) / f64::from(runs)));
        let _ = Command::new("kill")
            .args(["-INT", &child.id().to_string()])
            .status();
        child.wait().unwrap();
        let now = std::fs::read(&page).unwrap();
        if now == b"<p>the previous page</p>" {
            old_seen += 1;
        } else {
            assert!(
                now == new,
                "a torn page: {} of {} bytes",
                now.len(),
                new.len()
            );
            new_seen += 1;
        }
        assert_no_temporaries(&dir);
    }
    assert_eq!(old_seen + new_seen, runs);
    std::fs::remove_dir_all(&dir).ok();
}

// ------------------------------------------------------------------------------ sizes

#[test]
fn a_gigabyte_of_nul_bytes_is_refused_by_its_size() {
    let dir = scratch("nul");
    let file = dir.join("nul.toml");
    // Sparse: no disk space, no time.
    std::fs::File::create(&file)
        .unwrap()
        .set_len(1 << 30)
        .unwrap();
    let t = Instant::now();
    let r = eom(&["check", s(&file)]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(
        r.stderr.contains("more than the limit of 64 MiB"),
        "{}",
        r.stderr
    );
    assert!(t.elapsed() < Duration::from_secs(30));
    std::fs::remove_dir_all(&dir).ok();
}

fn avl(surfaces: usize, nchord: usize, nspan: usize) -> String {
    let mut t = String::from("big\n0\n0 0 0\n1 1 1\n0 0 0\n");
    for k in 0..surfaces {
        let z = k as f64;
        t.push_str(&format!(
            "SURFACE\nw{k}\n{nchord} 1.0 {nspan} 1.0\nSECTION\n0 0 {z} 1 0\nSECTION\n0 1 {z} 1 0\n"
        ));
    }
    t
}

#[test]
fn lattices_beyond_the_panel_limit_are_refused_before_they_are_built() {
    let dir = scratch("panels");
    for (name, text, expect) in [
        (
            "million.avl",
            avl(1, 1000, 1000),
            "more than the limit of 10000",
        ),
        (
            "surfaces.avl",
            avl(200, 12, 12),
            "more than the limit of 10000",
        ),
        (
            "count.avl",
            avl(1, 1, 100_000),
            "more than the limit of 10000 panels",
        ),
    ] {
        let file = dir.join(name);
        std::fs::write(&file, text).unwrap();
        let r = eom(&["aero", s(&file)]);
        assert_eq!(r.code, 2, "{name}: {}", r.stderr);
        assert!(r.stderr.contains(expect), "{name}: {}", r.stderr);
    }
    // Within the panel limit but not the memory limit: refused with both sizes.
    let file = dir.join("memory.avl");
    std::fs::write(&file, avl(1, 50, 100)).unwrap();
    let r = Command::new(env!("CARGO_BIN_EXE_eom"))
        .args(["aero", s(&file)])
        .env("EOM_MEMORY_LIMIT", "64M")
        .output()
        .unwrap();
    let stderr = String::from_utf8(r.stderr).unwrap();
    assert_eq!(r.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("influence matrix would need about"),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_robust_path_refuses_chain1000_with_the_sizes() {
    let t = Instant::now();
    let r = eom(&["analyze", "chain1000", "--method", "robust"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(
        r.stderr
            .contains("robust reduction's dense descriptor matrices")
            && r.stderr.contains("more than the limit of 8.0 GiB"),
        "{}",
        r.stderr
    );
    assert!(t.elapsed() < Duration::from_secs(60), "{:?}", t.elapsed());
}

// ------------------------------------------------------------------------------ numbers

const AERO_DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../eom-aero/tests/data");

#[test]
fn overflowing_aerodynamics_is_an_error_not_nan() {
    let fin = format!("{AERO_DATA}/seed_fin.avl");
    for args in [
        vec!["aero", fin.as_str(), "--rho", "1e308"],
        vec!["aero", fin.as_str(), "--speed", "1e308", "--rho", "10"],
    ] {
        let r = eom(&args);
        assert_eq!(r.code, 2, "{args:?}: {}", r.stderr);
        assert!(r.stderr.contains("ρ·V·S/2 overflows"), "{}", r.stderr);
        assert!(r.stdout.is_empty(), "{}", r.stdout);
    }
    // V = 1e308 at sea level: ∂F/∂x = ρ·V·S/2·(…) ≈ 1e307 is a number (V² was formed before,
    // and overflowed into NaN and ∞).
    let v = eom_json(&["aero", &fin, "--speed", "1e308", "--format", "json"]);
    let dyv = v["dimensional"][1][1].as_f64().unwrap();
    let cyv = v["derivatives"]["CYv"].as_f64().unwrap();
    let want = 0.5 * 1.225 * 1e308 * 0.5 * cyv;
    assert!((dyv / want - 1.0).abs() < 1e-12, "{dyv} against {want}");
    let dir = scratch("aero");
    let sb = std::fs::read_to_string(format!("{AERO_DATA}/seed_fin_a0_avl332.sb")).unwrap();
    assert!(sb.contains("Sref = 0.50000"));
    for (name, text, expect) in [
        (
            "zero.sb",
            sb.replace("Sref = 0.50000", "Sref = 0.00000"),
            "Sref must be positive, is 0",
        ),
        (
            "negative.sb",
            sb.replace("Sref = 0.50000", "Sref = -0.5000"),
            "Sref must be positive, is -0.5",
        ),
        ("huge.sb", huge_cyv(&sb), "CYv = -1e308 times"),
    ] {
        let file = dir.join(name);
        std::fs::write(&file, text).unwrap();
        let r = eom(&["aero", s(&file)]);
        assert_eq!(r.code, 2, "{name}: {}", r.stderr);
        assert!(r.stderr.contains(expect), "{name}: {}", r.stderr);
    }
    // A reference point so far that the rotations overflow: said so, not "singular", and a
    // usage error (the input's fault, exit 2).
    let r = eom(&["aero", &fin, "--ref", "1e308,0,0"]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(
        r.stderr.contains("Xref/Yref/Zref") && !r.stderr.contains("singular"),
        "{}",
        r.stderr
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The SB file with CYv replaced by −1e308.
fn huge_cyv(sb: &str) -> String {
    let at = sb.find("CYv =").expect("CYv");
    let end = at
        + 5
        + sb[at + 5..]
            .find(|c: char| c.is_ascii_alphabetic())
            .unwrap();
    format!("{}CYv = -1e308   {}", &sb[..at], &sb[end..])
}

#[test]
fn a_response_far_below_one_in_a_billion_is_computed_in_decibels() {
    let v = eom_json(&[
        "analyze",
        "smd",
        "--freq-range",
        "1e-170:1",
        "--points",
        "3",
        "--format",
        "json",
    ]);
    let f = &v["frequency_response"];
    assert_eq!(f["frequency_hz"][0].as_f64(), Some(1e-170));
    let pair = &f["pairs"][1];
    assert_eq!(pair["output"], "z dot");
    // z dot / f = s / (m s² + c s + k) with m = 1, c = 0.1, k = 10: at ω = 2π·1e-170 rad/s,
    // |G| = ω/k to 1e-339 relative, the phase +90°.
    let want = 20.0 * ((2.0 * std::f64::consts::PI).log10() - 171.0);
    let got = pair["magnitude_db"][0].as_f64().unwrap();
    assert!((got - want).abs() < 1e-9, "{got} dB, want {want}");
    assert!((pair["phase_deg"][0].as_f64().unwrap() - 90.0).abs() < 1e-9);
}

#[test]
fn an_exact_pole_of_tan_is_refused_like_a_division_by_zero() {
    let dir = scratch("tan");
    let file = dir.join("tan.toml");
    let text =
        smd_with("smd", "block", "spring", "kg").replace("mass = \"m\"", "mass = \"tan(pi/2)\"");
    std::fs::write(&file, text).unwrap();
    let r = eom(&["check", s(&file)]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert!(r.stderr.contains("body `block`, field `mass`") && r.stderr.contains("pole of tan"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_sweep_claims_only_what_its_grid_shows() {
    // x = 0 and x = 1 are unstable; 0.3 < x < 0.7 is stable (the shimmy's closed form).
    let r = eom(&["sweep", "shimmy", "--param", "x=0:1:2"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(!r.stdout.contains("whole range") && !r.stdout.contains("none in the range"));
    assert!(
        r.stdout.contains("none between the grid points"),
        "{}",
        r.stdout
    );
    assert!(
        r.stdout.contains("none at the grid points: all 2 values"),
        "{}",
        r.stdout
    );
}

// ------------------------------------------------------------------------------ messages

#[test]
fn messages_name_what_is_wrong() {
    let dir = scratch("messages");
    // A massless body: check names the command that reduces it, and it does.
    let file = dir.join("massless.toml");
    std::fs::write(
        &file,
        smd_with("smd", "block", "spring", "kg").replace("mass = \"m\"", "mass = 0"),
    )
    .unwrap();
    let r = eom(&["check", s(&file)]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let advice = format!("eom analyze {} --method robust", s(&file));
    assert!(
        r.stdout.contains(&advice) && !r.stdout.contains("robust numeric path"),
        "{}",
        r.stdout
    );
    let r = eom(&["analyze", s(&file), "--method", "robust"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    // The report's sweep is `--sweep`, not `--param`.
    for bad in ["k=1:2:0", "k", "k=1:2"] {
        let r = eom(&["report", "smd", "--sweep", bad, "-o", s(&dir)]);
        assert_eq!(r.code, 2, "{}", r.stderr);
        assert!(
            r.stderr.contains("`--sweep ") && !r.stderr.contains("--param"),
            "{}",
            r.stderr
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// A wing derivative whose damping would overflow is refused naming the wing and the
/// derivative (not found later as a non-finite entry of A).
#[test]
fn an_overflowing_wing_derivative_is_named() {
    let dir = scratch("wing_overflow");
    let exported = eom(&["export", "smd_wing"]);
    assert_eq!(exported.code, 0, "{}", exported.stderr);
    assert!(exported.stdout.contains("CZw = \"-CLa - CD\""));
    for value in ["-1e308", "-1e300"] {
        let file = dir.join("w.toml");
        std::fs::write(
            &file,
            exported
                .stdout
                .replace("CZw = \"-CLa - CD\"", &format!("CZw = \"{value}\"")),
        )
        .unwrap();
        let r = eom(&["analyze", s(&file)]);
        assert_eq!(r.code, 2, "{value}: {}", r.stderr);
        assert!(
            r.stderr.contains("wing `wing`, field `derivatives`: `CZw`")
                && r.stderr.contains("would overflow"),
            "{value}: {}",
            r.stderr
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
