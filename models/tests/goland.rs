//! The Goland wing's convergence in the number of beam segments: the flutter speed and
//! frequency of `models::aeroelastic::goland_wing(N)` against the reference's N-segment lumped
//! model with the segments' rotary inertia (`tests/data/aero/goland.json`, computed by
//! `goland.py` from the same equations; docs/aero-references.md §3), with Jones' states and
//! quasi-steady. The 16-segment catalogue model is checked through `eom sweep` in
//! eom-cli/tests/aeroelastic.rs.

use eom_model::{Linearizer, Method, Unsteady};
use models::aeroelastic::goland_wing;

/// The largest real part of the eigenvalues at airspeed `v`, and that eigenvalue's |Im|.
fn least_stable(model: &eom_model::Model, v: f64) -> (f64, f64) {
    let ss = Linearizer::new(model)
        .at(&[("V", v)])
        .method(Method::Numeric)
        .run()
        .expect("linearized")
        .state_space;
    let e = eom_num::modes::eigenvalues(&ss.a).expect("eigenvalues");
    let top = e
        .iter()
        .max_by(|a, b| a.re.total_cmp(&b.re))
        .expect("an eigenvalue");
    (top.re, top.im.abs())
}

/// The flutter speed and frequency by bisection of the sign change in (lo, hi).
fn flutter(n: usize, unsteady: Unsteady, lo: f64, hi: f64) -> (f64, f64) {
    let m = goland_wing(n, unsteady, &[]).expect("built");
    let (mut lo, mut hi) = (lo, hi);
    assert!(least_stable(&m, lo).0 < 0.0 && least_stable(&m, hi).0 > 0.0);
    while hi - lo > 1e-9 * hi {
        let mid = 0.5 * (lo + hi);
        if least_stable(&m, mid).0 < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (lo, least_stable(&m, lo).1)
}

fn reference() -> serde_like::Rows {
    let p = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/data/aero/goland.json");
    serde_like::rows(&std::fs::read_to_string(p).expect("reference"))
}

/// The few numbers needed from the reference's JSON, read without a JSON crate: the rows of
/// `lumped_with_slope_inertia` as (segments, Jones U_F, ω_F, quasi-steady U_F, ω_F).
mod serde_like {
    pub type Rows = Vec<(usize, [f64; 4])>;

    fn number_after(s: &str, key: &str) -> f64 {
        let at = s.find(key).unwrap_or_else(|| panic!("no {key}")) + key.len();
        let t = s[at..].trim_start_matches([':', ' ', '"']);
        let end = t
            .find(|c: char| !(c.is_ascii_digit() || "+-.eE".contains(c)))
            .unwrap_or(t.len());
        t[..end].parse().expect("a number")
    }

    pub fn rows(text: &str) -> Rows {
        let block = &text[text.find("\"lumped_with_slope_inertia\"").expect("rows")..];
        block
            .split("\"theodorsen\"")
            .skip(1)
            .map(|row| {
                let jones = &row[row.find("\"jones\"").expect("jones")..];
                let qs = &row[row.find("\"quasi_steady\"").expect("qs")..];
                (
                    number_after(row, "\"segments\"") as usize,
                    [
                        number_after(jones, "\"U_F_m_s\""),
                        number_after(jones, "\"omega_F_rad_s\""),
                        number_after(qs, "\"U_F_m_s\""),
                        number_after(qs, "\"omega_F_rad_s\""),
                    ],
                )
            })
            .collect()
    }
}

#[test]
fn segments_converge_like_the_reference() {
    let rows = reference();
    for n in [4, 8] {
        let want = rows
            .iter()
            .find(|r| r.0 == n)
            .unwrap_or_else(|| panic!("no row for N = {n}"))
            .1;
        let (u, w) = flutter(n, Unsteady::Jones, 100.0, 180.0);
        assert!(
            (u / want[0] - 1.0).abs() < 1e-7,
            "N = {n}: U_F {u} vs {}",
            want[0]
        );
        assert!(
            (w / want[1] - 1.0).abs() < 1e-7,
            "N = {n}: ω_F {w} vs {}",
            want[1]
        );
        let (u, w) = flutter(n, Unsteady::QuasiSteady, 40.0, 100.0);
        assert!(
            (u / want[2] - 1.0).abs() < 1e-7,
            "N = {n}: quasi-steady U_F {u} vs {}",
            want[2]
        );
        assert!(
            (w / want[3] - 1.0).abs() < 1e-7,
            "N = {n}: quasi-steady ω_F {w} vs {}",
            want[3]
        );
    }
}
