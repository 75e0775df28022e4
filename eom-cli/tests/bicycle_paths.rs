//! What `eom analyze bicycle` prints, on every reduction path, against the published
//! eigenvalues of the Whipple bicycle benchmark (Meijaard et al. 2007, Table 2; the digits are
//! good to about 1e-13, docs/references.md §A), with the heading and lateral position reported
//! as exact structural zeros.

// Published digits, quoted as printed.
#![allow(clippy::excessive_precision, clippy::unreadable_literal)]

mod common;
use common::{complex, eom_json};

/// (v, [weave re, weave im, capsize, castor]) for v = 1…10; v = 0 has four real roots.
const TABLE: [(f64, [f64; 4]); 10] = [
    (
        1.0,
        [
            3.52696170990070,
            0.80774027519930,
            -3.13423125066578,
            -7.11008014637442,
        ],
    ),
    (
        2.0,
        [
            2.68234517512745,
            1.68066296590675,
            -3.07158645641514,
            -8.67387984831735,
        ],
    ),
    (
        3.0,
        [
            1.70675605663975,
            2.31582447384325,
            -2.63366137253667,
            -10.35101467245920,
        ],
    ),
    (
        4.0,
        [
            0.41325331521125,
            3.07910818603206,
            -1.42944427361326,
            -12.15861426576447,
        ],
    ),
    (
        5.0,
        [
            -0.77534188219585,
            4.46486771378823,
            -0.32286642900409,
            -14.07838969279822,
        ],
    ),
    (
        6.0,
        [
            -1.52644486584142,
            5.87673060598709,
            -0.00406690076970,
            -16.08537123098030,
        ],
    ),
    (
        7.0,
        [
            -2.13875644258362,
            7.19525913329805,
            0.10268170574766,
            -18.15788466125262,
        ],
    ),
    (
        8.0,
        [
            -2.69348683581097,
            8.46037971396931,
            0.14327879765713,
            -20.27940894394569,
        ],
    ),
    (
        9.0,
        [
            -3.21675402252485,
            9.69377351531791,
            0.15790184030917,
            -22.43788559040858,
        ],
    ),
    (
        10.0,
        [
            -3.72016840437287,
            10.90681139476287,
            0.16105338653172,
            -24.62459635017404,
        ],
    ),
];

fn printed(v: f64, method: &str) -> (Vec<(f64, f64)>, usize) {
    let j = eom_json(&[
        "analyze",
        "bicycle",
        "--set",
        &format!("v={v}"),
        "--method",
        method,
        "--format",
        "json",
    ]);
    let e: Vec<(f64, f64)> = j["eigenvalues"]
        .as_array()
        .expect("eigenvalues")
        .iter()
        .map(complex)
        .collect();
    let zeros = j["structural_zeros"]
        .as_array()
        .expect("structural_zeros")
        .len();
    (e, zeros)
}

#[test]
fn printed_eigenvalues_equal_the_published_table_on_every_path() {
    for method in ["numeric", "symbolic", "robust"] {
        for &(v, [wr, wi, capsize, castor]) in &TABLE {
            let (e, zeros) = printed(v, method);
            assert_eq!(zeros, 2, "{method} v = {v}: heading and lateral position");
            let exact_zeros = e.iter().filter(|z| **z == (0.0, 0.0)).count();
            assert_eq!(exact_zeros, 2, "{method} v = {v}: {e:?}");
            let rest: Vec<(f64, f64)> = e.into_iter().filter(|z| *z != (0.0, 0.0)).collect();
            let want = [(castor, 0.0), (capsize, 0.0), (wr, -wi), (wr, wi)];
            for w in &want {
                let d = rest
                    .iter()
                    .map(|g| ((g.0 - w.0).powi(2) + (g.1 - w.1).powi(2)).sqrt())
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    d < 1e-12,
                    "{method} v = {v}: {w:?} missing (nearest {d:e}) in {rest:?}"
                );
            }
        }
        // v = 0: ±3.13164324790656, ±5.53094371765393.
        let (e, _) = printed(0.0, method);
        for w in [
            -5.53094371765393,
            -3.13164324790656,
            3.13164324790656,
            5.53094371765393,
        ] {
            assert!(
                e.iter().any(|g| (g.0 - w).abs() < 1e-12 && g.1 == 0.0),
                "{method} v = 0: {w} in {e:?}"
            );
        }
    }
}

#[test]
fn stability_is_decided_alike_by_analyze_and_sweep() {
    // Self-stable between the weave and capsize speeds (4.292…, 6.024…).
    for (v, stable) in [(4.0, false), (5.0, true), (6.0, true), (6.1, false)] {
        for method in ["numeric", "symbolic", "robust"] {
            let j = eom_json(&[
                "analyze",
                "bicycle",
                "--set",
                &format!("v={v}"),
                "--method",
                method,
                "--format",
                "json",
            ]);
            assert_eq!(j["stable"].as_bool(), Some(stable), "{method} v = {v}");
        }
    }
}
