//! `eom bench throughput`: the sweep's summary (stable points, range of the largest real part)
//! equals that of a plain loop over the same points through another path of the library (the
//! symbolic reduction evaluated on the tape, faer's eigenvalues), the generated verdict without
//! eigenvalues agrees wherever it decides, and bad arguments exit 2.

mod common;
use common::eom;
use eom_bench::throughput::{Options, largest_real_part, parameter_names, point};
use eom_model::Linearizer;

/// The number after `label` on the line that starts with it.
fn field<'a>(text: &'a str, label: &str) -> &'a str {
    text.lines()
        .find_map(|l| l.strip_prefix(label))
        .unwrap_or_else(|| panic!("no line `{label}` in:\n{text}"))
        .trim()
}

fn number(s: &str) -> f64 {
    s.trim_end_matches(|c: char| !c.is_ascii_digit())
        .parse()
        .unwrap_or_else(|e| panic!("`{s}`: {e}"))
}

#[test]
fn summary_equals_a_plain_loop_over_the_same_points() {
    let n = 1000;
    let r = eom(&[
        "bench",
        "throughput",
        "--points",
        &n.to_string(),
        "--threads",
        "2",
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let out = &r.stdout;
    assert_eq!(field(out, "generated code failures:"), "0", "{out}");
    assert_eq!(field(out, "eigenvalue failures:"), "0", "{out}");
    let stable: usize = field(out, "stable points:")
        .split_whitespace()
        .next()
        .and_then(|s| s.parse().ok())
        .expect("a count of stable points");
    let range: Vec<f64> = field(out, "largest real part of the non-zero eigenvalues: from")
        .split(" to ")
        .map(|s| number(s.split_whitespace().next().expect("a number")))
        .collect();
    for label in ["points/s:", "wall time:"] {
        let x = number(field(out, label).split_whitespace().next().expect("number"));
        assert!(x > 0.0 && x.is_finite(), "{label} {x}: {out}");
    }

    // The plain loop: the same points (by name), the tape, the library's eigenvalues.
    let model = models::build("bicycle", &[]).expect("bicycle");
    let sym = Linearizer::new(&model).symbolic().expect("symbolic");
    let compiled = sym.compiled();
    let scope = model.scope.names();
    let order: Vec<usize> = scope
        .iter()
        .map(|s| {
            parameter_names()
                .iter()
                .position(|n| n == s)
                .expect("the same parameters")
        })
        .collect();
    let opts = Options::default();
    let (mut want_stable, mut lo, mut hi) = (0, f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..n {
        let p = point(opts.seed, opts.spread, k as u64);
        let values: Vec<f64> = order.iter().map(|&j| p[j]).collect();
        let ss = compiled.evaluate(&values).expect("tape");
        // faer's solver, not the small kernel the sweep uses.
        let mut e = vec![num_complex::Complex64::new(0.0, 0.0); ss.a.nrows()];
        let mut ws = eom_num::modes::EigenvaluesWorkspace::new(ss.a.nrows());
        eom_num::modes::eigenvalues_faer_in(&ss.a, &mut ws, &mut e).expect("eigenvalues");
        let re = largest_real_part(&e);
        want_stable += usize::from(re < 0.0);
        lo = lo.min(re);
        hi = hi.max(re);
    }
    assert_eq!(stable, want_stable, "{out}");
    // The verdict without eigenvalues: decided where it says so, and then the same.
    let verdicts: Vec<usize> = field(out, "verdicts:")
        .split(|c: char| !c.is_ascii_digit())
        .filter(|w| !w.is_empty())
        .map(|w| w.parse().expect("a count"))
        .collect();
    let [v_stable, v_unstable, undecided, failed, differ, decided] = verdicts[..6] else {
        panic!("verdict counts: {out}");
    };
    assert_eq!((failed, differ), (0, 0), "{out}");
    assert_eq!(v_stable + v_unstable, decided, "{out}");
    assert_eq!(decided + undecided, n, "{out}");
    assert!(
        v_stable <= want_stable && want_stable <= v_stable + undecided,
        "{out}"
    );
    assert!(stable > 0 && stable < n, "both kinds of points: {out}");
    for (got, want) in range.iter().zip([lo, hi]) {
        assert!(
            (got - want).abs() <= 1e-6 * want.abs(),
            "printed {got}, plain loop {want}: {out}"
        );
    }
}

#[test]
fn bad_arguments_exit_2_naming_them() {
    for (args, needle) in [
        (&["bench", "throughput", "--points", "0"][..], "--points 0"),
        (&["bench", "throughput", "--threads", "0"], "--threads 0"),
    ] {
        let r = eom(args);
        assert_eq!(r.code, 2, "{args:?}: {}", r.stderr);
        assert!(r.stderr.contains(needle), "{args:?}: {}", r.stderr);
    }
}
