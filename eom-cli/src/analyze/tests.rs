//! Unit tests of the analysis steps on small hand-made state-space models.

use super::*;
use nalgebra::dmatrix;

/// A double integrator `ÿ = u` observed by y: G(s) = 1/s², an integrating pair of order 2
/// with coefficient 1, and a double zero mode.
#[test]
fn integrating_pairs_are_reported_as_such() {
    let ss = StateSpace::new(
        dmatrix![0.0, 1.0; 0.0, 0.0],
        dmatrix![0.0; 1.0],
        dmatrix![1.0, 0.0; 0.0, 1.0],
        dmatrix![0.0; 0.0],
    )
    .unwrap();
    let r = analyze_state_space(&ss, Vec::new(), None, 0).unwrap();
    let g = r.steady_state_gain.as_ref().unwrap();
    let i = g[0]
        .integrating
        .as_ref()
        .expect("position integrates twice");
    assert_eq!(i.order, 2);
    assert!((i.coefficient - 1.0).abs() < 1e-12, "{}", i.coefficient);
    let i = g[1].integrating.as_ref().expect("velocity integrates once");
    assert_eq!(i.order, 1);
    assert!((i.coefficient - 1.0).abs() < 1e-12, "{}", i.coefficient);
    assert!(g.iter().all(|e| e.value.is_none()));
    assert!(
        r.modes
            .iter()
            .all(|m| m.kind == "zero" && m.stability == "marginal")
    );
    let text = r.to_text();
    assert!(
        text.contains("integrating (pole of order 2 at s = 0)"),
        "{text}"
    );
    assert!(
        text.contains("a unit step gives a ramp of slope 1"),
        "{text}"
    );
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["steady_state_gain"][0]["integrating"]["order"], 2);
    assert!(json["steady_state_gain"][0].get("value").is_none());
}

/// An unstable mode that the output cannot see must be listed, never hidden.
#[test]
fn unobservable_unstable_modes_are_reported() {
    // ẋ1 = −x1 + u, ẋ2 = 0.5 x2 + u, y = x1: the growing x2 is invisible at the output.
    let ss = StateSpace::new(
        dmatrix![-1.0, 0.0; 0.0, 0.5],
        dmatrix![1.0; 1.0],
        dmatrix![1.0, 0.0],
        dmatrix![0.0],
    )
    .unwrap();
    let r = analyze_state_space(&ss, Vec::new(), None, 0).unwrap();
    assert_eq!(r.stability, "unstable");
    let m = r.minimal.as_ref().unwrap();
    assert_eq!(m.states, 1);
    assert_eq!(m.removed.len(), 1);
    let rm = &m.removed[0];
    assert_eq!(
        (rm.reason, rm.stability, rm.kind),
        ("unobservable", "unstable", "real")
    );
    assert!((rm.eigenvalue.re - 0.5).abs() < 1e-12);
    assert!(
        r.to_text()
            .contains("UNSTABLE real mode 0.5 is unobservable"),
        "{}",
        r.to_text()
    );
}
