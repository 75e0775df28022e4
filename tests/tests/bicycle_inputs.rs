//! The bicycle's inputs as published: the benchmark's forcing vector f = [T_phi, T_delta]
//! (Meijaard, Papadopoulos, Ruina & Schwab 2007, Proc. R. Soc. A 463:1955–1982; docs/references.md §A):
//! M q̈ + v C1 q̇ + (g K0 + v² K2) q = f with q = [phi, delta]. Whatever basis a reduction path
//! chooses for its states, the outputs [delta, phi] then satisfy C B = 0 and C A B = M⁻¹ (the
//! inputs' instantaneous effect on the angles' accelerations) — checked against the published
//! M by all three paths at several speeds.

// Reference values are transcribed digit for digit from their source.
#![allow(clippy::excessive_precision)]

use eom_model::{Linearizer, Method};
use nalgebra::{DMatrix, Matrix2};

/// The published mass matrix of the benchmark (Meijaard et al. 2007, Appendix A, the values
/// for the Table 1 parameters to 14 decimals; docs/references.md §A), rows and columns
/// [phi, delta].
fn published_m() -> Matrix2<f64> {
    Matrix2::new(
        80.81722,
        2.31941332208709,
        2.31941332208709,
        0.29784188199686,
    )
}

fn index(names: &[String], name: &str) -> usize {
    names
        .iter()
        .position(|n| n == name)
        .unwrap_or_else(|| panic!("no signal {name} in {names:?}"))
}

#[test]
fn inputs_enter_through_the_published_inverse_mass_matrix() {
    let m = models::build("bicycle", &[]).expect("bicycle");
    let minv = published_m().try_inverse().expect("M is invertible");
    for method in [Method::Symbolic, Method::Numeric, Method::Robust] {
        for v in [0.5, 3.0, 5.0, 9.0] {
            let ss = Linearizer::new(&m)
                .at(&[("v", v)])
                .method(method)
                .run()
                .unwrap_or_else(|e| panic!("{method:?} at v = {v}: {e}"))
                .state_space;
            assert_eq!(ss.inputs(), 2, "{method:?}: inputs {:?}", ss.names.inputs);
            let (t_phi, t_delta) = (
                index(&ss.names.inputs, "T_phi"),
                index(&ss.names.inputs, "T_delta"),
            );
            let (phi, delta) = (
                index(&ss.names.outputs, "phi"),
                index(&ss.names.outputs, "delta"),
            );
            let cb: DMatrix<f64> = &ss.c * &ss.b;
            let cab: DMatrix<f64> = &ss.c * &ss.a * &ss.b;
            // [phi, delta] × [T_phi, T_delta], as M⁻¹ is ordered.
            let rows = [phi, delta];
            let cols = [t_phi, t_delta];
            for (i, &r) in rows.iter().enumerate() {
                for (j, &c) in cols.iter().enumerate() {
                    assert!(
                        cb[(r, c)].abs() < 1e-14,
                        "{method:?} v = {v}: C B[{i},{j}] = {:e}",
                        cb[(r, c)]
                    );
                    // The published M has 15 digits: M⁻¹ follows to ~1e-13.
                    let err = (cab[(r, c)] - minv[(i, j)]).abs();
                    assert!(
                        err < 1e-12,
                        "{method:?} v = {v}: C A B[{i},{j}] = {} vs M⁻¹ {} ({err:e})",
                        cab[(r, c)],
                        minv[(i, j)]
                    );
                }
            }
        }
    }
}
