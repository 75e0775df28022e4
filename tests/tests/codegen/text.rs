//! The generated text: determinism, `no_std` code, typed errors for bad options, the
//! formatting snapshot and when simplification is used.

#[test]
fn generation_is_deterministic() {
    let dir = env!("OUT_DIR");
    let first = std::fs::read_to_string(format!("{dir}/smd_first.rs")).expect("file");
    let again = std::fs::read_to_string(format!("{dir}/smd_again.rs")).expect("file");
    assert_eq!(
        first, again,
        "smd generated in a fresh pool and after other models differ"
    );
    let m = models::build("bicycle", &[]).expect("bicycle");
    let opts = eom_codegen::EmitOptions::default();
    let x = eom_codegen::emit_model(&m, &opts).expect("emit").source;
    let _other = eom_codegen::emit_model(&models::build("chain3", &[]).expect("chain"), &opts)
        .expect("emit");
    let y = eom_codegen::emit_model(&models::build("bicycle", &[]).expect("bicycle"), &opts)
        .expect("emit")
        .source;
    assert_eq!(x, y);
}

#[test]
fn generated_libm_code_uses_core_only() {
    let dir = env!("OUT_DIR");
    for entry in std::fs::read_dir(dir).expect("OUT_DIR") {
        let path = entry.expect("entry").path();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default()
            .to_string();
        if !name.ends_with(".rs") || name.contains("_std") || name == "generated.rs" {
            continue;
        }
        let text = std::fs::read_to_string(&path).expect("read");
        assert!(
            !text.contains("std::") && !text.contains(".sin(") && !text.contains(".sqrt("),
            "{name} needs std"
        );
    }
}

#[test]
fn bad_options_are_typed_errors_naming_the_option() {
    use eom_codegen::{CodegenError, EmitOptions, emit_model};
    let m = models::build("smd", &[]).expect("smd");
    let e = emit_model(&m, &EmitOptions::default().module("Not A Module")).expect_err("bad module");
    assert!(
        matches!(
            e,
            CodegenError::BadOption {
                option: "module",
                ..
            }
        ),
        "{e}"
    );
    let e =
        emit_model(&m, &EmitOptions::default().fix("mass", 2.0)).expect_err("unknown parameter");
    assert!(
        e.to_string().contains("mass") && e.to_string().contains("m, k, c"),
        "{e}"
    );
    let e = emit_model(&m, &EmitOptions::default().fix("m", 0.0)).expect_err("division by zero");
    assert!(
        matches!(e, CodegenError::BadOption { option: "fix", .. }),
        "{e}"
    );
    let bike = models::build("bicycle", &[]).expect("bicycle");
    let e = emit_model(
        &bike,
        &EmitOptions::default().fix("lambda", std::f64::consts::FRAC_PI_2),
    )
    .expect_err("outside");
    assert!(
        matches!(e, CodegenError::BadOption { option: "fix", .. })
            && e.to_string().contains("steer hinge"),
        "{e}"
    );
    let e = emit_model(&m, &EmitOptions::default().max_temporaries(0)).expect_err("zero chunk");
    assert!(
        matches!(
            e,
            CodegenError::BadOption {
                option: "max_temporaries",
                ..
            }
        ),
        "{e}"
    );
}

/// Formatting snapshot of a tiny model (the only exact-text test).
#[test]
fn smd_eval_ab_formatting_snapshot() {
    let m = models::build("smd", &[]).expect("smd");
    let src = eom_codegen::emit_model(&m, &eom_codegen::EmitOptions::default())
        .expect("emit")
        .source;
    let start = src.find("    pub fn eval_ab(").expect("eval_ab");
    let end = start + src[start..].find("\n    }\n").expect("end") + 7;
    let expected = SMD_EVAL_AB;
    assert_eq!(
        &src[start..end],
        expected,
        "formatting of smd's eval_ab changed:\n{}",
        &src[start..end]
    );
}

const SMD_EVAL_AB: &str = r#"    pub fn eval_ab(
        p: &[f64; N_PARAMS],
        a: &mut [f64; A_LEN],
        b: &mut [f64; B_LEN],
        work: &mut [f64; WORK_LEN],
    ) -> Result<(), Error> {
        let _ = work;
        let p_m: f64 = p[0];
        let p_k: f64 = p[1];
        let p_c: f64 = p[2];
        let t0: f64 = 1.0 / p_m;
        let t1: f64 = p_k * t0;
        let t2: f64 = p_c * t0;
        let av0 = p_m.abs();
        let ok0: bool = av0 > 0.0;
        let size0: f64 = p_m.abs() + p_c.abs();
        let size1: f64 = p_k.abs();
        if !(ok0
            & (((size0 < 1.152921504606847e18) & (size1 < 1.152921504606847e18)
                & (p_m.abs() >= 8.673617379884035e-19))))
        {
            return eval_ab_checked(p, a, b, work);
        }
        a[1] = -t1;
        a[2] = 1.0;
        a[3] = -t2;
        b[1] = t0;
        Ok(())
    }
"#;

/// `simplify` keeps the simplified expressions only when they have fewer operations and a
/// lower cost estimate (chain × operations); otherwise the output is exactly the plain one.
/// `simplify_always` keeps them on fewer operations alone.
#[test]
fn simplification_is_used_only_when_estimated_faster() {
    use eom_codegen::{EmitOptions, Simplification, emit_model};
    let mut seen_slower = Vec::new();
    let mut seen_used = Vec::new();
    for name in ["smd", "shimmy", "bicycle", "chain3"] {
        let m = models::build(name, &[]).expect("model");
        let plain = emit_model(&m, &EmitOptions::default()).expect("emit");
        assert_eq!(plain.stats.simplification, Simplification::NotRun);
        let simp = emit_model(&m, &EmitOptions::default().simplify(true)).expect("emit");
        let always = emit_model(&m, &EmitOptions::default().simplify_always(true)).expect("emit");
        let (p0, s0, a0) = (
            &plain.stats.functions[0],
            &simp.stats.functions[0],
            &always.stats.functions[0],
        );
        match simp.stats.simplification {
            Simplification::Used => {
                seen_used.push(name);
                assert!(s0.cost_estimate() < p0.cost_estimate(), "{name}");
                assert!(s0.ops.total() < p0.ops.total(), "{name}");
                assert_eq!(simp.source, always.source, "{name}");
            }
            Simplification::NotFaster {
                simplified,
                original,
            } => {
                seen_slower.push(name);
                assert!(simplified >= original, "{name}");
                assert_eq!(
                    (original, simplified),
                    (p0.cost_estimate(), a0.cost_estimate())
                );
                assert!(a0.critical_path > p0.critical_path, "{name}");
                assert_eq!(simp.source, plain.source, "{name}: not the plain code");
                assert_eq!(always.stats.simplification, Simplification::Used, "{name}");
                assert_ne!(always.source, plain.source, "{name}");
            }
            Simplification::NotCheaper => {
                assert_eq!(simp.source, plain.source, "{name}");
                assert_eq!(always.source, plain.source, "{name}");
            }
            Simplification::NotRun => panic!("{name}: simplification not run"),
        }
    }
    // The two measured cases: the bicycle's factored form is slower (83 against 75 ns per
    // call), the shimmy's faster (4.78 against 4.94 ns).
    assert_eq!(seen_slower, ["bicycle"]);
    assert_eq!(seen_used, ["shimmy"]);
}
