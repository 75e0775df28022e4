//! Exit codes and messages for bad input: 2 for unknown names and malformed arguments (with
//! the valid names listed on standard error), 1 for other failures.

mod common;
use common::eom;

const SHIMMY_PARAMS: &str = "m, I, k, l, x, u";

fn assert_fails(args: &[&str], code: i32, needles: &[&str]) {
    let r = eom(args);
    assert_eq!(r.code, code, "eom {args:?}: stderr {}", r.stderr);
    assert!(
        r.stdout.is_empty(),
        "eom {args:?} wrote to stdout: {}",
        r.stdout
    );
    for n in needles {
        assert!(
            r.stderr.contains(n),
            "eom {args:?}: `{n}` not in stderr: {}",
            r.stderr
        );
    }
}

#[test]
fn unknown_model_exits_2_and_lists_the_models() {
    // Every name of the catalogue (families as patterns), never a typed list.
    let models = models::names();
    for args in [
        &["analyze", "shimy"][..],
        &["sweep", "bicycel", "--param", "v=0:1:3"],
        &["codegen", "nosuch", "-o", "x.rs"],
        &["analyze", "chain0"],
    ] {
        let mut needles = vec!["unknown model"];
        needles.extend(models.iter().copied());
        assert_fails(args, 2, &needles);
    }
}

#[test]
fn unknown_parameter_exits_2_and_lists_the_parameters() {
    assert_fails(
        &["analyze", "shimmy", "--set", "q=1"],
        2,
        &["`q`", SHIMMY_PARAMS],
    );
    assert_fails(
        &["sweep", "shimmy", "--param", "speed=0:1:3"],
        2,
        &["`speed`", SHIMMY_PARAMS],
    );
    assert_fails(
        &["sweep", "shimmy", "--param", "x=0:1:3", "--set", "z=2"],
        2,
        &["`z`", SHIMMY_PARAMS],
    );
}

#[test]
fn malformed_set_exits_2_naming_the_argument() {
    for (arg, why) in [
        ("u", "NAME=VALUE"),
        ("u=abc", "`abc` is not a number"),
        ("=3", "name"),
        ("u=", "missing"),
        ("u=nan", "finite"),
    ] {
        assert_fails(
            &["analyze", "shimmy", "--set", arg],
            2,
            &[&format!("--set {arg}"), why, SHIMMY_PARAMS],
        );
    }
    assert_fails(
        &["analyze", "shimmy", "--set", "u=1", "--set", "u=2"],
        2,
        &["more than once"],
    );
}

#[test]
fn values_the_model_cannot_take_exit_2() {
    assert_fails(
        &["analyze", "shimmy", "--set", "m=-1"],
        2,
        &["`m`", "must be positive"],
    );
    // The sweep range is checked before anything is computed.
    assert_fails(
        &["sweep", "shimmy", "--param", "k=-1:1:5"],
        2,
        &["`k`", "must be positive"],
    );
}

#[test]
fn malformed_sweep_and_frequency_arguments_exit_2() {
    for p in ["x=0:1", "x", "x=0:1:0", "x=0:a:3", "x=1:1:3"] {
        assert_fails(
            &["sweep", "shimmy", "--param", p],
            2,
            &[&format!("--param {p}")],
        );
    }
    assert_fails(
        &["sweep", "shimmy", "--param", "x=0:1:3", "--set", "x=0.5"],
        2,
        &["swept parameter"],
    );
    for r in ["10:1", "0:1", "1-10"] {
        assert_fails(
            &["analyze", "shimmy", "--freq-range", r],
            2,
            &["--freq-range"],
        );
    }
    assert_fails(&["analyze", "shimmy", "--points", "0"], 2, &["--points"]);
    // clap's own errors use the same code.
    assert_fails(
        &["analyze", "shimmy", "--method", "exact"],
        2,
        &["symbolic", "numeric", "robust"],
    );
    assert_fails(&["sweep", "shimmy"], 2, &["--param"]);
}

/// With `--method symbolic` the pivots are chosen at the defaults: at trail c = −w the rear
/// tyre's pivot −w − c vanishes, which is a failure (1), not a usage error; the numeric method
/// chooses its pivots at the point and succeeds there.
#[test]
fn symbolic_breakdown_exits_1_with_a_clear_message() {
    assert_fails(
        &[
            "analyze", "bicycle", "--set", "c=-1.02", "--method", "symbolic",
        ],
        1,
        &["validity region", "front tyre", "--method numeric"],
    );
    let r = eom(&[
        "analyze", "bicycle", "--set", "c=-1.02", "--method", "numeric",
    ]);
    assert_eq!(r.code, 0, "{}", r.stderr);
}

/// A failure of the reduction itself (zero inertia about the pin) is reported, with code 1.
#[test]
fn singular_models_exit_1() {
    assert_fails(
        &["analyze", "pendulum", "--set", "Ix=-10"],
        1,
        &["error:", "singular"],
    );
}
