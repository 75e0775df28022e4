//! The generated module of a model whose texts try to inject code (`tests/build.rs`,
//! `hostile_model`): that it compiled is the first check (it is part of this test crate); here,
//! that no injected line became code, and that the names came through exactly or escaped.

use super::hostile_gen::hostile;

const SOURCE: &str = include_str!(concat!(env!("OUT_DIR"), "/hostile.rs"));

#[test]
fn injected_text_stays_in_comments_and_literals() {
    let mut seen = 0;
    for line in SOURCE.lines() {
        if line.contains("fn injected") {
            seen += 1;
            let t = line.trim_start();
            assert!(
                t.starts_with("//") || t.starts_with('"') || t.starts_with("pub const CHECKS"),
                "injected text outside a comment: {line:?}"
            );
        }
    }
    // The model name, the descriptions and a unit each reach the comments.
    assert!(seen >= 3, "{seen} lines");
    assert!(
        !SOURCE.contains('\r'),
        "a carriage return in the generated code"
    );
    for c in ['\u{2028}', '\u{202e}', '\u{1b}', '\0'] {
        assert!(!SOURCE.contains(c), "{c:?} raw in the generated code");
    }
    assert!(
        SOURCE
            .lines()
            .next()
            .unwrap()
            .contains("smd\\npub fn injected()")
    );
}

#[test]
fn names_come_through_exactly_and_units_escaped() {
    assert_eq!(
        hostile::BODY_NAMES,
        ["block \" \\ */ /* // /// #[cfg(any())] } { r#\"x\"# ü 漢"]
    );
    assert_eq!(hostile::PARAM_NAMES, ["m", "k", "c"]);
    assert!(hostile::PARAM_UNITS[0].starts_with("kg\\0\\u{1}"));
    assert!(hostile::INPUT_UNITS[0].contains("\\n") && !hostile::INPUT_UNITS[0].contains('\n'));
    assert_eq!(hostile::INPUT_NAMES, ["force \"\\n"]);
    // And the code computes: A of a mass on a spring, [[0, 1], [−k/m, −c/m]].
    let mut a = [0.0; hostile::N_STATES * hostile::N_STATES];
    let mut b = [0.0; hostile::N_STATES * hostile::N_INPUTS];
    let mut c = [0.0; hostile::N_OUTPUTS * hostile::N_STATES];
    let mut d = [0.0; hostile::N_OUTPUTS * hostile::N_INPUTS];
    let mut work = [0.0; hostile::WORK_LEN];
    hostile::eval_abcd(&hostile::NOMINAL, &mut a, &mut b, &mut c, &mut d, &mut work).unwrap();
    let mut entries: Vec<f64> = a.to_vec();
    entries.sort_by(f64::total_cmp);
    assert_eq!(entries, [-10.0, -0.1, 0.0, 1.0]);
}
