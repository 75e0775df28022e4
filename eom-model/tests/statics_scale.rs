//! Scale-aware statics and redundant constraints, on the eigenvalues and warnings that
//! [`Linearizer::run`] returns to users.
//!
//! * Two vertical strings holding a block, one string moved sideways by an offset: every
//!   offset from 1e-15 to 1e-3 (of a 1 m model) gives eigenvalues within a few times the offset
//!   of the exact-0 model, and a coordinate written `0.5*sin(2*pi)` works on every path.
//! * Over-constrained mechanisms built in 3-D with hinges only (a parallelogram four-bar and a
//!   planar five-bar; each planar loop carries three redundant out-of-plane rows): the
//!   redundant rows are found and named, the indeterminate preloads (weight across the plane)
//!   are the minimum-norm ones with a warning, and the eigenvalues agree to 1e-10 with the same
//!   mechanism whose redundant rows were removed by hand (one hinge made a joint that carries
//!   in-plane forces only).
//! * The orthogonal Bricard linkage, a spatial 6R loop that moves although its constraints
//!   count as many as its coordinates: one redundant row found, and its one mode equal to the
//!   50-digit reference of `tests/data/bricard_reference.py` to 1e-10 on every path.

use eom_model::{Linearization, Linearizer, Method, ModelError, Warning, file};
use num_complex::Complex64;

/// The linearization of the model file `text` (which must load).
fn run(text: &str, method: Method, at: &[(&str, f64)]) -> Result<Linearization, ModelError> {
    let m = file::from_str(text, "test.toml", &[]).unwrap_or_else(|e| panic!("{e}"));
    Linearizer::new(&m).method(method).at(at).run()
}

fn eigs(l: &Linearization) -> Vec<Complex64> {
    eom_num::modes::eigenvalues(&l.state_space.a).expect("eigenvalues")
}

/// The largest distance between the eigenvalues of `a` and `b`, each matched to its nearest
/// unmatched partner (the lists must have the same length).
fn distance(a: &[Complex64], b: &[Complex64]) -> f64 {
    assert_eq!(a.len(), b.len(), "{a:?} vs {b:?}");
    let mut left: Vec<Complex64> = b.to_vec();
    let mut worst = 0.0f64;
    for x in a {
        let (k, d) = left
            .iter()
            .enumerate()
            .map(|(k, y)| (k, (x - y).norm()))
            .min_by(|p, q| p.1.total_cmp(&q.1))
            .expect("partner");
        worst = worst.max(d);
        left.remove(k);
    }
    worst
}

/// A 2 kg block hanging from two vertical 1 m links at x = ±1; the right link's y
/// coordinate is `y`.
fn strings(y: &str) -> String {
    format!(
        r#"
[model]
name = "strings"
[parameters]
m = {{ value = 2, unit = "kg", description = "mass", range = "> 0" }}
g = {{ value = 9.81, unit = "m/s^2", description = "gravity", range = "> 0" }}
off = {{ value = 0, unit = "m", description = "offset of the right string" }}
[[body]]
name = "block"
at = [0, 0, 0]
mass = "m"
moments = [1, 2, 3]
[[load]]
name = "weight"
body = "block"
frame = "ground"
at = [0, 0, 0]
force = [0, 0, "-m*g"]
[[link]]
name = "left"
between = ["block", "ground"]
ends = [[-1, 0, 0], [-1, 0, 1]]
[[link]]
name = "right"
between = ["block", "ground"]
ends = [[1, "{y}", 0], [1, "{y}", 1]]
"#
    )
}

#[test]
fn geometric_offsets_give_continuous_eigenvalues() {
    let text = strings("off");
    for method in [Method::Numeric, Method::Robust, Method::Symbolic] {
        let exact = eigs(&run(&text, method, &[]).expect("exact model"));
        // The pendulum and twist modes are there (nonzero), so continuity means something.
        assert!(
            exact.iter().filter(|l| l.norm() > 1.0).count() >= 4,
            "{exact:?}"
        );
        for off in [1e-15, 1e-12, 1e-9, 1e-6, 1e-3] {
            let l = run(&text, method, &[("off", off)])
                .unwrap_or_else(|e| panic!("{method:?}, offset {off:e}: {e}"));
            let d = distance(&eigs(&l), &exact);
            // By symmetry the eigenvalues move with the square of the offset (0.8 off² here).
            // The robust path's orthonormal basis turns the double zero eigenvalue (roll angle
            // and rate, on which nothing acts) into a defective pair that any eigensolver
            // resolves only to about √ε.
            let floor = if method == Method::Robust {
                1e-7
            } else {
                1e-12
            };
            assert!(
                d <= 10.0 * off * off + floor,
                "{method:?}, offset {off:e}: moved {d:e}"
            );
            // Beyond rounding, the residual moment is reported (the symbolic path checks the
            // statics at its nominal point, where the offset is 0).
            if method != Method::Symbolic {
                let warned = l
                    .warnings
                    .iter()
                    .any(|w| matches!(w, Warning::NearEquilibrium { .. }));
                assert_eq!(warned, off >= 1e-6, "{method:?} {off:e}: {:?}", l.warnings);
            }
        }
    }
}

#[test]
fn a_coordinate_written_as_a_rounded_zero_works_on_every_path() {
    let exact = eigs(&run(&strings("0"), Method::Numeric, &[]).expect("exact"));
    for method in [Method::Numeric, Method::Robust, Method::Symbolic] {
        let l = run(&strings("0.5*sin(2*pi)"), method, &[]).expect("0.5 sin 2π");
        // The robust path: a defective double zero, resolved to about √ε (see above).
        let tol = if method == Method::Robust {
            1e-7
        } else {
            1e-12
        };
        let d = distance(&eigs(&l), &exact);
        assert!(d < tol, "{method:?}: {d:e}");
    }
}

#[test]
fn a_real_offset_is_still_an_error() {
    // 5 cm on a 1 m model: the weight's moment about x is unbalanced by 2.5 % of the largest.
    let e = run(&strings("off"), Method::Numeric, &[("off", 0.05)]).unwrap_err();
    assert!(
        matches!(&e, ModelError::Equilibrium { equation, ratio, .. }
            if equation.starts_with("body `block`") && *ratio > 1e-3),
        "{e:?}"
    );
}

fn body(name: &str, at: [f64; 3], mass: f64, moments: [f64; 3]) -> String {
    format!("[[body]]\nname = \"{name}\"\nat = {at:?}\nmass = {mass}\nmoments = {moments:?}\n")
}

/// A hinge about z (`forces = 3, moments = 2`), or with `in_plane` a joint that carries the
/// two in-plane forces only: the hinge with its three out-of-plane rows removed by hand.
fn hinge(name: &str, b1: &str, b2: &str, at: [f64; 3], in_plane: bool) -> String {
    let (f, m) = if in_plane { (2, 0) } else { (3, 2) };
    format!(
        "[[rigid_point]]\nname = \"{name}\"\nbetween = [\"{b1}\", \"{b2}\"]\nforces = {f}\nmoments = {m}\nat = {at:?}\naxis = [0, 0, 1]\n"
    )
}

fn torsion(name: &str, b: &str, at: [f64; 3], k: f64) -> String {
    format!(
        "[[flex_point]]\nname = \"{name}\"\nbetween = [\"{b}\", \"ground\"]\nforces = 0\nmoments = 1\nat = {at:?}\naxis = [0, 0, 1]\nstiffness = [0, {k}]\ndamping = [0, 0.1]\n"
    )
}

fn header(name: &str, gravity: bool) -> String {
    let g = if gravity {
        "gravity = [0, 0, -9.81]\n"
    } else {
        ""
    };
    format!("[model]\nname = \"{name}\"\n{g}")
}

/// A parallelogram four-bar in the horizontal plane: cranks A–B and D–C, coupler B–C, a
/// torsion spring at A; weight (if any) across the plane. `by_hand`: hinge B in-plane only.
fn four_bar(gravity: bool, by_hand: bool) -> String {
    [
        header("four-bar", gravity),
        body("crank1", [0.0, 0.5, 0.0], 1.0, [0.1, 0.1, 0.1]),
        body("crank2", [2.0, 0.5, 0.0], 1.5, [0.1, 0.1, 0.1]),
        body("coupler", [1.0, 1.0, 0.0], 2.0, [0.2, 0.3, 0.4]),
        hinge("A", "crank1", "ground", [0.0, 0.0, 0.0], false),
        hinge("B", "crank1", "coupler", [0.0, 1.0, 0.0], by_hand),
        hinge("C", "crank2", "coupler", [2.0, 1.0, 0.0], false),
        hinge("D", "crank2", "ground", [2.0, 0.0, 0.0], false),
        torsion("spring", "crank1", [0.0, 0.0, 0.0], 5.0),
    ]
    .join("\n")
}

/// A planar five-bar (two degrees of freedom): ground A–D, links A–B, B–C, C–E, E–D, torsion
/// springs at A and D. `by_hand`: hinge C in-plane only.
fn five_bar(gravity: bool, by_hand: bool) -> String {
    [
        header("five-bar", gravity),
        body("l1", [0.0, 0.5, 0.0], 1.0, [0.1, 0.1, 0.1]),
        body("l2", [0.75, 1.25, 0.0], 1.2, [0.1, 0.1, 0.1]),
        body("l3", [2.25, 1.25, 0.0], 0.8, [0.1, 0.1, 0.1]),
        body("l4", [3.0, 0.5, 0.0], 1.1, [0.1, 0.1, 0.1]),
        hinge("A", "l1", "ground", [0.0, 0.0, 0.0], false),
        hinge("B", "l1", "l2", [0.0, 1.0, 0.0], false),
        hinge("C", "l2", "l3", [1.5, 1.5, 0.0], by_hand),
        hinge("E", "l3", "l4", [3.0, 1.0, 0.0], false),
        hinge("D", "l4", "ground", [3.0, 0.0, 0.0], false),
        torsion("s1", "l1", [0.0, 0.0, 0.0], 5.0),
        torsion("s4", "l4", [3.0, 0.0, 0.0], 7.0),
    ]
    .join("\n")
}

fn check_mechanism(build: fn(bool, bool) -> String, dof: usize) {
    for gravity in [false, true] {
        let by_hand = run(&build(gravity, true), Method::Numeric, &[]).expect("by hand");
        let reference = eigs(&by_hand);
        assert_eq!(reference.len(), 2 * dof);
        assert!(by_hand.warnings.is_empty(), "{:?}", by_hand.warnings);
        for method in [Method::Numeric, Method::Robust, Method::Symbolic] {
            let full = run(&build(gravity, false), method, &[]);
            if method == Method::Symbolic && gravity {
                // The self-stress cannot be chosen for every parameter value: a typed error.
                let e = full.unwrap_err();
                assert!(
                    matches!(&e, ModelError::NonUniquePreloads { moved } if *moved > 0.0),
                    "{e:?}"
                );
                continue;
            }
            let full = full.unwrap_or_else(|e| panic!("{method:?}, gravity {gravity}: {e}"));
            let d = distance(&eigs(&full), &reference);
            assert!(d < 1e-10, "{method:?}, gravity {gravity}: {d:e}");
            let w = &full.warnings;
            // The redundant rows are reported, by item and direction, on every path.
            assert!(
                w.iter().any(|w| matches!(
                    w,
                    Warning::StaticsRedundant { .. }
                        | Warning::ReductionRedundant { .. }
                        | Warning::RobustRedundant { .. }
                )),
                "{method:?}: {w:?}"
            );
            if gravity {
                assert!(
                    w.iter().any(|w| matches!(
                        w,
                        Warning::StaticsRedundant { rows, .. }
                            if rows.len() == 3 && rows[0].starts_with("rigid point `")
                    )),
                    "{w:?}"
                );
            }
        }
    }
}

#[test]
fn parallelogram_four_bar_in_3d() {
    check_mechanism(four_bar, 1);
}

#[test]
fn planar_five_bar_in_3d() {
    check_mechanism(five_bar, 2);
}

/// The orthogonal Bricard linkage, a spatial 6R loop with as many constraint rows as
/// coordinates that still moves (`tests/data/bricard.toml` describes it; the torsion spring
/// `k` = 5 N m/rad at its nominal value).
fn bricard() -> String {
    include_str!("data/bricard.toml").to_string()
}

#[test]
#[allow(clippy::excessive_precision)]
fn bricard_linkage_moves_with_one_degree_of_freedom() {
    // λ = (−c ± √(c² − 4 m k)) / 2m with the effective inertia m = 2.89210019455361372887 of
    // the motion (joint rates 1, −0.32252, 1, −0.32252, …), from the null space of the six
    // hinge screws (tests/data/bricard_reference.py, 50 digits).
    let want = Complex64::new(-0.017288474339222309549, 1.3147427666951634561);
    for method in [Method::Numeric, Method::Robust, Method::Symbolic] {
        let l = run(&bricard(), method, &[]).unwrap_or_else(|e| panic!("{method:?}: {e}"));
        let e = eigs(&l);
        let d = distance(&e, &[want, want.conj()]);
        assert!(
            d < 1e-10 * want.norm(),
            "{method:?}: {e:?} vs {want}: {d:e}"
        );
        let w = &l.warnings;
        // One row (of 30) on the elimination paths; the robust path counts position and
        // velocity rows (one each of 60).
        let counted = w.iter().any(|w| match w {
            Warning::RobustRedundant {
                redundant, rows, ..
            } => method == Method::Robust && (*redundant, *rows) == (2, 60),
            Warning::ReductionRedundant { rows, .. } => method != Method::Robust && rows.len() == 1,
            _ => false,
        });
        assert!(counted, "{method:?}: {w:?}");
    }
}
