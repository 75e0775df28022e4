//! The small models of the structural regions, as model files: a chain of masses on sliders,
//! two vertical strings holding a block, and over-constrained planar mechanisms built in 3-D
//! (a parallelogram four-bar and a five-bar), and the spatial Bricard linkage.

use std::fmt::Write;

/// A chain of `masses.len()` bodies on sliders along x, each tied to the previous one (the
/// first to the ground) by an undamped spring. Parameters `m1…mn`, `k1…kn` with the given
/// nominal values; a mass may be 0 (`range = ">= 0"`).
pub fn chain(masses: &[f64], springs: &[f64]) -> String {
    let mut s = String::from("[model]\nname = \"chain\"\n[parameters]\n");
    for (i, m) in masses.iter().enumerate() {
        let _ = writeln!(s, "m{} = {{ value = {m:e}, range = \">= 0\" }}", i + 1);
    }
    for (i, k) in springs.iter().enumerate() {
        let _ = writeln!(s, "k{} = {{ value = {k:e}, range = \"> 0\" }}", i + 1);
    }
    for i in 1..=masses.len() {
        let prev = if i == 1 {
            "ground".to_string()
        } else {
            format!("b{}", i - 1)
        };
        let _ = write!(
            s,
            "[[body]]\nname = \"b{i}\"\nat = [{i}, 0, 0]\nmass = \"m{i}\"\nmoments = [1, 1, 1]\n\
             [[rigid_point]]\nname = \"slider{i}\"\nbetween = [\"b{i}\", \"ground\"]\nat = [{i}, 0, 0]\n\
             forces = 2\nmoments = 3\naxis = [1, 0, 0]\n\
             [[spring]]\nname = \"link{i}\"\nbetween = [\"b{i}\", \"{prev}\"]\nends = [[{i}, 0, 0], [{}, 0, 0]]\n\
             stiffness = \"k{i}\"\n",
            i - 1
        );
    }
    s
}

/// A 2 kg block hanging from two vertical 1 m links at x = ±1; the right link's y
/// coordinate is the parameter `off` (0 nominal).
pub fn strings() -> String {
    r#"
[model]
name = "strings"
[parameters]
m = { value = 2, unit = "kg", description = "mass", range = "> 0" }
g = { value = 9.81, unit = "m/s^2", description = "gravity", range = "> 0" }
off = { value = 0, unit = "m", description = "offset of the right string" }
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
ends = [[1, "off", 0], [1, "off", 1]]
"#
    .to_string()
}

fn body(name: &str, at: [f64; 3], mass: f64, moments: [f64; 3]) -> String {
    format!("[[body]]\nname = \"{name}\"\nat = {at:?}\nmass = {mass}\nmoments = {moments:?}\n")
}

/// A hinge about z, or with `in_plane` a joint carrying the two in-plane forces only (the
/// hinge with its three out-of-plane rows removed by hand).
fn hinge(name: &str, b1: &str, b2: &str, at: [f64; 3], in_plane: bool) -> String {
    let (f, m) = if in_plane { (2, 0) } else { (3, 2) };
    format!(
        "[[rigid_point]]\nname = \"{name}\"\nbetween = [\"{b1}\", \"{b2}\"]\nforces = {f}\nmoments = {m}\nat = {at:?}\naxis = [0, 0, 1]\n"
    )
}

/// A torsion spring to the ground about z with stiffness `k` (an expression).
fn torsion(name: &str, b: &str, at: [f64; 3], k: &str) -> String {
    format!(
        "[[flex_point]]\nname = \"{name}\"\nbetween = [\"{b}\", \"ground\"]\nforces = 0\nmoments = 1\nat = {at:?}\naxis = [0, 0, 1]\nstiffness = [0, \"{k}\"]\ndamping = [0, 0.1]\n"
    )
}

/// The parameter `k` (torsion stiffness, nominal 5).
const STIFFNESS: &str = "[parameters]\nk = { value = 5, range = \"> 0\" }\n";

/// A parallelogram four-bar in the horizontal plane (no gravity): cranks A–B and D–C,
/// coupler B–C, a torsion spring `k` at A. Every hinge carries three out-of-plane rows, three
/// of which are redundant; `by_hand`: hinge B in-plane only (no redundant row).
pub fn four_bar(by_hand: bool) -> String {
    [
        "[model]\nname = \"four-bar\"\n".to_string(),
        STIFFNESS.to_string(),
        body("crank1", [0.0, 0.5, 0.0], 1.0, [0.1, 0.1, 0.1]),
        body("crank2", [2.0, 0.5, 0.0], 1.5, [0.1, 0.1, 0.1]),
        body("coupler", [1.0, 1.0, 0.0], 2.0, [0.2, 0.3, 0.4]),
        hinge("A", "crank1", "ground", [0.0, 0.0, 0.0], false),
        hinge("B", "crank1", "coupler", [0.0, 1.0, 0.0], by_hand),
        hinge("C", "crank2", "coupler", [2.0, 1.0, 0.0], false),
        hinge("D", "crank2", "ground", [2.0, 0.0, 0.0], false),
        torsion("spring", "crank1", [0.0, 0.0, 0.0], "k"),
    ]
    .join("\n")
}

/// A planar five-bar (two degrees of freedom): ground A–D, links A–B, B–C, C–E, E–D, torsion
/// springs `k` at A and `1.4 k` at D. `by_hand`: hinge C in-plane only.
pub fn five_bar(by_hand: bool) -> String {
    [
        "[model]\nname = \"five-bar\"\n".to_string(),
        STIFFNESS.to_string(),
        body("l1", [0.0, 0.5, 0.0], 1.0, [0.1, 0.1, 0.1]),
        body("l2", [0.75, 1.25, 0.0], 1.2, [0.1, 0.1, 0.1]),
        body("l3", [2.25, 1.25, 0.0], 0.8, [0.1, 0.1, 0.1]),
        body("l4", [3.0, 0.5, 0.0], 1.1, [0.1, 0.1, 0.1]),
        hinge("A", "l1", "ground", [0.0, 0.0, 0.0], false),
        hinge("B", "l1", "l2", [0.0, 1.0, 0.0], false),
        hinge("C", "l2", "l3", [1.5, 1.5, 0.0], by_hand),
        hinge("E", "l3", "l4", [3.0, 1.0, 0.0], false),
        hinge("D", "l4", "ground", [3.0, 0.0, 0.0], false),
        torsion("s1", "l1", [0.0, 0.0, 0.0], "k"),
        torsion("s4", "l4", [3.0, 0.0, 0.0], "1.4*k"),
    ]
    .join("\n")
}

/// The orthogonal Bricard linkage, a spatial 6R loop with 30 constraint rows for 30
/// coordinates that still moves with one degree of freedom (one row is redundant), with the
/// torsion spring `k` at hinge 1: the model file of eom-model's tests, which describes it
/// (`eom-model/tests/data/bricard.toml`, its reference `bricard_reference.py` beside it).
pub fn bricard() -> String {
    include_str!("../../../eom-model/tests/data/bricard.toml").to_string()
}

/// A pendulum on two hinges about y at (0, 0, 0) and (0, 1, 0), with a torsion spring of
/// 5 N m/rad about the first; the second hinge's axis is tilted to `[0, 1, d]`. At `d = 0`
/// the hinges are collinear (two redundant rows; one degree of freedom, ω² = 5/1.1); at any
/// other `d` the axes cross at the second hinge and the pendulum is locked (no state).
pub fn hinges() -> String {
    r#"
[model]
name = "hinges"
[parameters]
d = { value = 0, description = "tilt of the second hinge axis" }
[[body]]
name = "pendulum"
at = [0, 0.5, -1]
mass = 1
moments = [0.1, 0.1, 0.1]
[[rigid_point]]
name = "h1"
between = ["pendulum", "ground"]
at = [0, 0, 0]
forces = 3
moments = 2
axis = [0, 1, 0]
[[rigid_point]]
name = "h2"
between = ["pendulum", "ground"]
at = [0, 1, 0]
forces = 3
moments = 2
axis = [0, 1, "d"]
[[flex_point]]
name = "spring"
between = ["pendulum", "ground"]
forces = 0
moments = 1
at = [0, 0, 0]
axis = [0, 1, 0]
stiffness = [0, 5]
"#
    .to_string()
}
