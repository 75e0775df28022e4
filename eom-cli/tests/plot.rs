//! `--plot` and `--plot-poles`: the SVG files exist, are SVG, hold one curve per branch or
//! pair (curves are the only polylines drawn 2 pixels wide), name the signals and the swept
//! parameter; bad file names fail before anything is computed, with exit code 1 (a path that
//! cannot be written) or 2 (a malformed argument).

mod common;
use common::{eom, eom_json};
use std::path::PathBuf;

/// An empty directory of this test's own under Cargo's scratch directory for integration
/// tests (tests run in parallel: one directory each).
fn scratch(test: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("plot-tests")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

/// Reads a plot and checks that it is a whole SVG document.
fn read_svg(path: &std::path::Path) -> String {
    let svg = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{} was not written: {e}", path.display()));
    assert!(svg.starts_with("<svg"), "{}", &svg[..svg.len().min(80)]);
    assert!(svg.trim_end().ends_with("</svg>"), "the SVG is not closed");
    svg
}

/// Data curves: polylines 2 pixels wide (grid, axes and dashed lines are 1 pixel wide).
fn curves(svg: &str) -> usize {
    svg.matches("stroke-width=\"2\" points=").count()
}

/// Whether `text` is the whole content of a `<text>` element.
fn has_text(svg: &str, text: &str) -> bool {
    svg.contains(&format!(">\n{text}\n</text>"))
}

/// Runs `eom` and requires failure with `code`, nothing on standard output and every needle
/// in the message.
fn assert_fails(args: &[&str], code: i32, needles: &[&str]) {
    let r = eom(args);
    assert_eq!(r.code, code, "eom {args:?}: stderr {}", r.stderr);
    assert!(r.stdout.is_empty(), "eom {args:?} wrote {}", r.stdout);
    for n in needles {
        assert!(r.stderr.contains(n), "`{n}` not in: {}", r.stderr);
    }
}

#[test]
fn sweep_plot_has_two_curves_per_branch_and_marks_the_boundaries() {
    let dir = scratch("sweep");
    let file = dir.join("bicycle-v.svg");
    let f = file.to_str().unwrap();
    let j = eom_json(&[
        "sweep",
        "bicycle",
        "--param",
        "v=0:10:101",
        "--format",
        "json",
        "--plot",
        f,
    ]);
    let svg = read_svg(&file);
    let branches = j["branches"].as_array().unwrap();
    let drawn = branches.iter().filter(|b| b["neutral"] == false).count();
    assert!(drawn >= 4 && drawn < branches.len(), "{branches:?}");
    // Real parts on top, damped frequencies below.
    assert_eq!(curves(&svg), 2 * drawn);
    // The axis label names the parameter with its unit, in both panels.
    assert_eq!(svg.matches(">\nv [m/s]\n</text>").count(), 2);
    assert!(has_text(&svg, "Re λ [1/s]") && has_text(&svg, "|Im λ|/2π [Hz]"));
    // Weave (stabilizing) and capsize (destabilizing) speeds are listed in the legend.
    let boundaries = j["boundaries"].as_array().unwrap();
    assert_eq!(boundaries.len(), 2);
    // The speeds as the legend prints them (6 digits), from the bicycle's sidecar.
    let refs = tests::references::sidecar("bicycle");
    let speeds = refs.boundary_in("v", &[]).expected();
    let (weave, capsize) = (format!("{:.5}", speeds[0]), format!("{:.5}", speeds[1]));
    assert_eq!(
        svg.matches(&format!("\nstabilizing: v = {weave}")).count(),
        1
    );
    assert_eq!(
        svg.matches(&format!("\ndestabilizing: v = {capsize}"))
            .count(),
        1
    );
    // The stable interval is shaded (two panels) and drawn as a legend swatch.
    let shade = svg.matches("fill=\"#D6F0D6\"").count();
    assert_eq!(shade, 3, "stable shading in both panels and the legend");
}

#[test]
fn sweep_plot_of_a_unitless_parameter_names_it() {
    let dir = scratch("unitless");
    let file = dir.join("shimmy.svg");
    let r = eom(&[
        "sweep",
        "shimmy",
        "--param",
        "x=0:1:21",
        "--plot",
        file.to_str().unwrap(),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(
        r.stdout.contains("Stable intervals of x"),
        "text output kept"
    );
    let svg = read_svg(&file);
    assert_eq!(curves(&svg), 6, "three branches, two panels");
    assert!(has_text(&svg, "x"));
}

#[test]
fn sweep_plot_needs_a_range_of_nonzero_width() {
    let dir = scratch("zero-width");
    let file = dir.join("one.svg");
    let f = file.to_str().unwrap();
    assert_fails(
        &["sweep", "shimmy", "--param", "x=0.5:0.5:1", "--plot", f],
        2,
        &["--param x=0.5:0.5:1", "--plot", "nonzero width"],
    );
    assert!(!file.exists());
    // Without --plot a single value is a valid sweep.
    let r = eom(&["sweep", "shimmy", "--param", "x=0.5:0.5:1"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
}

#[test]
fn bode_plot_has_one_curve_per_pair_in_each_panel_and_a_legend() {
    let dir = scratch("bode");
    let file = dir.join("smd.svg");
    let f = file.to_str().unwrap();
    // --plot implies --freq: the JSON holds the frequency response too.
    let j = eom_json(&[
        "analyze", "smd", "--points", "50", "--format", "json", "--plot", f,
    ]);
    let pairs = j["frequency_response"]["pairs"].as_array().unwrap();
    assert_eq!(pairs.len(), 3);
    let svg = read_svg(&file);
    assert_eq!(curves(&svg), 2 * pairs.len());
    for label in ["f → z [m/N]", "f → z dot [m/s/N]", "f → kz [N/N]"] {
        assert!(has_text(&svg, label), "legend `{label}` missing");
    }
    assert!(has_text(&svg, "magnitude [dB]") && has_text(&svg, "phase [deg]"));
    assert_eq!(svg.matches(">\nfrequency [Hz]\n</text>").count(), 2);
}

#[test]
fn bode_plot_of_a_single_frequency_draws_dots() {
    let dir = scratch("bode-single");
    let file = dir.join("one.svg");
    let r = eom(&[
        "analyze",
        "pendulum",
        "--freq-range",
        "1:2",
        "--points",
        "1",
        "--plot",
        file.to_str().unwrap(),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let svg = read_svg(&file);
    assert_eq!(curves(&svg), 0);
    // pendulum: two inputs, two outputs — four pairs, a dot each in both panels.
    assert_eq!(svg.matches("<circle").count(), 8);
}

#[test]
fn pole_map_tells_seen_and_hidden_modes_apart() {
    let dir = scratch("poles");
    let file = dir.join("disk.svg");
    let f = file.to_str().unwrap();
    let j = eom_json(&["analyze", "disk", "--format", "json", "--plot-poles", f]);
    let removed = j["minimal"]["removed"].as_array().unwrap();
    let count = |reason: &str| removed.iter().filter(|r| r["reason"] == reason).count();
    let (unc, uno) = (count("uncontrollable"), count("unobservable"));
    assert!(unc > 0 && uno > 0, "{removed:?}");
    let svg = read_svg(&file);
    // The legend rows are wrapped; their ends hold the counts.
    assert!(svg.contains("hidden: uncontrollable") && svg.contains("hidden: unobservable"));
    assert!(svg.contains(&format!("cannot excite it) ({unc})")), "{svg}");
    assert!(svg.contains(&format!("cannot see it) ({uno})")), "{svg}");
    // Uncontrollable modes are filled triangles (one more in the legend).
    assert_eq!(svg.matches("<polygon").count(), unc + 1);
    assert!(has_text(&svg, "Re λ [1/s]") && has_text(&svg, "Im λ [1/s]"));
    assert!(
        j.get("frequency_response").is_none(),
        "--plot-poles alone adds no --freq"
    );
}

#[test]
fn pole_map_draws_the_transmission_zeros_as_rings() {
    let dir = scratch("zeros");
    let poles = dir.join("chain3-poles.svg");
    let bode = dir.join("chain3-bode.svg");
    let r = eom(&[
        "analyze",
        "chain3",
        "--plot-poles",
        poles.to_str().unwrap(),
        "--plot",
        bode.to_str().unwrap(),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let svg = read_svg(&poles);
    assert!(svg.contains("transmission zero (4)"));
    let rings = svg.matches("<circle").count();
    assert_eq!(rings, 4 + 1, "four zeros and the legend's ring");
    assert_eq!(curves(&read_svg(&bode)), 2, "one pair: f → x");
}

#[test]
fn bad_plot_paths_fail_before_the_computation() {
    let dir = scratch("bad");
    let missing = dir.join("no-such-dir").join("p.svg");
    assert_fails(
        &["analyze", "smd", "--plot", missing.to_str().unwrap()],
        1,
        &["--plot", "no-such-dir", "does not exist"],
    );
    assert_fails(
        &[
            "sweep",
            "shimmy",
            "--param",
            "x=0:1:5",
            "--plot",
            missing.to_str().unwrap(),
        ],
        1,
        &["cannot write the plot", "does not exist"],
    );
    let as_dir = dir.join("d.svg");
    std::fs::create_dir_all(&as_dir).unwrap();
    assert_fails(
        &["analyze", "smd", "--plot-poles", as_dir.to_str().unwrap()],
        1,
        &["--plot-poles", "is a directory"],
    );
    let file = dir.join("file");
    std::fs::write(&file, "").unwrap();
    let below_file = file.join("p.svg");
    assert_fails(
        &["analyze", "smd", "--plot", below_file.to_str().unwrap()],
        1,
        &["is not a directory"],
    );
    let png = dir.join("p.png");
    assert_fails(
        &["analyze", "smd", "--plot", png.to_str().unwrap()],
        2,
        &["--plot", "ending in .svg"],
    );
    let same = dir.join("same.svg");
    let s = same.to_str().unwrap();
    assert_fails(
        &["analyze", "smd", "--plot", s, "--plot-poles", s],
        2,
        &["--plot-poles", "same file"],
    );
    assert!(!png.exists() && !same.exists());
}

/// A file that passes the early checks but cannot be created: the write itself fails.
#[cfg(target_os = "linux")]
#[test]
fn a_failed_write_exits_1_and_names_the_file() {
    assert_fails(
        &["analyze", "smd", "--plot-poles", "/proc/eom-plot-test.svg"],
        1,
        &["cannot write the plot `/proc/eom-plot-test.svg` (--plot-poles)"],
    );
}

#[test]
fn locus_zoom_and_mode_shapes_are_drawn() {
    let dir = scratch("pictures");
    let (locus, zoom, modes) = (
        dir.join("locus.svg"),
        dir.join("zoom.svg"),
        dir.join("modes.svg"),
    );
    let r = eom(&[
        "sweep",
        "bicycle",
        "--param",
        "v=0:10:101",
        "--plot",
        zoom.to_str().unwrap(),
        "--zoom",
        "0.5",
        "--plot-locus",
        locus.to_str().unwrap(),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let svg = read_svg(&locus);
    // The benchmark's weave and capsize speeds (Meijaard et al. 2007) at the crossings.
    let speed = |label: &str| -> f64 {
        let i = svg.find(label).unwrap_or_else(|| panic!("no `{label}`")) + label.len();
        svg[i..].split(' ').next().unwrap().parse().unwrap()
    };
    assert!((speed("\nstabilizing: v = ") - 4.292_382_731_5).abs() < 1e-6);
    assert!((speed("destabilizing: v = ") - 6.024_262_376_7).abs() < 1e-6);
    let svg = read_svg(&zoom);
    assert!(has_text(&svg, "Re λ near 0 [1/s]"));
    let r = eom(&[
        "analyze",
        "quarter_car",
        "--plot-modes",
        modes.to_str().unwrap(),
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let svg = read_svg(&modes);
    // Two oscillatory modes (wheel hop, body bounce), one side view each, animated.
    assert_eq!(svg.matches("side view").count(), 2);
    assert!(svg.contains("<animate attributeName=\"y1\""));
    assert_fails(&["analyze", "quarter_car", "--mode", "1"], 2, &["--mode"]);
    assert_fails(
        &["sweep", "shimmy", "--param", "x=0:1:11", "--zoom"],
        2,
        &["--zoom", "--plot"],
    );
}
