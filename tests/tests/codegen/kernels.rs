//! The kernels of a module: structural non-zeros, the varying kernels and the constants,
//! the parameters struct and `StateSpace`.

use super::*;

#[test]
fn only_structural_nonzeros_are_written() {
    for g in all_f64() {
        let r = reference(g.model);
        let nominal = r.model.scope.nominal_values();
        let ss = r.sym.state_space();
        let mats = [&ss.a, &ss.b, &ss.c, &ss.d, &ss.phys];
        // The pattern constants are the structural non-zeros of the expressions.
        for (k, m) in mats.iter().enumerate() {
            let want: Vec<(usize, usize)> = (0..m.ncols())
                .flat_map(|j| (0..m.nrows()).map(move |i| (i, j)))
                .filter(|&(i, j)| !m[(i, j)].is_zero())
                .collect();
            assert_eq!(
                g.nonzeros[k],
                want.as_slice(),
                "{}: pattern of matrix {k}",
                g.model
            );
        }
        // A kernel writing into arrays full of a sentinel leaves the other entries alone.
        let got = (g.abcd)(&nominal).expect("nominal is valid");
        let want = r.sym.evaluate(&nominal).expect("nominal");
        for (k, m) in [&want.a, &want.b, &want.c, &want.d].iter().enumerate() {
            assert!(rel_diff(&got[k], m.as_slice()) <= 1e-12, "{}", g.model);
        }
    }
    use gen64::shimmy as s;
    let (mut a, mut b, mut c, mut d, mut w) = (
        [-3.5; s::A_LEN],
        [-3.5; s::B_LEN],
        [-3.5; s::C_LEN],
        [-3.5; s::D_LEN],
        [0.0; s::WORK_LEN],
    );
    s::eval_abcd(&s::NOMINAL, &mut a, &mut b, &mut c, &mut d, &mut w).expect("nominal");
    for (arr, nz, rows) in [
        (&a[..], &s::A_NONZEROS[..], s::N_STATES),
        (&b[..], &s::B_NONZEROS[..], s::N_STATES),
        (&c[..], &s::C_NONZEROS[..], s::N_OUTPUTS),
        (&d[..], &s::D_NONZEROS[..], s::N_OUTPUTS),
    ] {
        for (idx, x) in arr.iter().enumerate() {
            let structural = nz.contains(&(idx % rows, idx / rows));
            assert_eq!(*x == -3.5, !structural, "entry {idx}");
        }
    }
}

/// The kernels and the matrices each writes (0–3: A, B, C, D; 4: the physical coordinates).
const KERNELS: [(&str, &[usize]); 4] = [
    ("eval_abcd", &[0, 1, 2, 3]),
    ("eval_ab", &[0, 1]),
    ("eval_cd", &[2, 3]),
    ("eval_phys", &[4]),
];

/// Each `eval_X_varying` writes exactly the structural non-zeros that `write_X_constants`
/// does not, and together they give `eval_X`'s values, bit for bit; so does `StateSpace`,
/// which is built on `eval_abcd_varying`. At nominal and at random points, on every module.
#[test]
fn varying_kernels_and_constants_make_up_the_kernels() {
    let mut with_constants = [0; 4];
    for g in all_f64().into_iter().chain(all_f32()).chain(variants()) {
        let r = reference(g.model);
        let sym = r.sym.state_space();
        let rows = [&sym.a, &sym.b, &sym.c, &sym.d, &sym.phys].map(|m| m.nrows());
        let wholes = [g.abcd, g.ab, g.cd, g.phys];
        for (kernel, (name, mats)) in KERNELS.iter().enumerate() {
            let constants = (g.constants[kernel])();
            let check = |values: &[f64]| -> Result<(), TestCaseError> {
                let whole = (wholes[kernel])(values);
                let part = (g.varying[kernel])(values);
                let ss = if kernel == 0 {
                    Some((g.state_space)(values))
                } else {
                    None
                };
                let (whole, part) = match (whole, part) {
                    (Ok(w), Ok(p)) => (w, p),
                    (Err(a), Err(b)) => {
                        prop_assert_eq!(&a, &b, "{}: {}: different errors", g.model, name);
                        if let Some(s) = ss {
                            prop_assert_eq!(Err(a), s.map(|_| ()), "{}: StateSpace", g.model);
                        }
                        return Ok(());
                    }
                    (w, p) => {
                        return Err(TestCaseError::fail(format!(
                            "{}: {name} {:?}, {name}_varying {:?}",
                            g.model,
                            w.is_ok(),
                            p.is_ok(),
                        )));
                    }
                };
                let ss = match ss {
                    Some(Ok(s)) => Some(s),
                    Some(Err(e)) => {
                        return Err(TestCaseError::fail(format!(
                            "{}: StateSpace fails where eval_abcd does not: {e:?}",
                            g.model
                        )));
                    }
                    None => None,
                };
                for (n, &k) in mats.iter().enumerate() {
                    for idx in 0..whole[n].len() {
                        let structural = g.nonzeros[k].contains(&(idx % rows[k], idx / rows[k]));
                        let (c, p) = (constants[n][idx], part[n][idx]);
                        // Exactly one of the two writes each structural non-zero, neither the
                        // rest.
                        prop_assert!(
                            structural == ((c == SENTINEL) != (p == SENTINEL)),
                            "{}: {name}: matrix {k} entry {idx}: constants {c}, varying {p}",
                            g.model
                        );
                        let joined = if c == SENTINEL { p } else { c };
                        let want = if structural { whole[n][idx] } else { SENTINEL };
                        prop_assert_eq!(
                            joined.to_bits(),
                            want.to_bits(),
                            "{}: {}: matrix {} entry {}",
                            g.model,
                            name,
                            k,
                            idx
                        );
                        if let Some(ss) = &ss {
                            prop_assert_eq!(
                                ss[n][idx].to_bits(),
                                whole[n][idx].to_bits(),
                                "{}: StateSpace matrix {} entry {}",
                                g.model,
                                k,
                                idx
                            );
                        }
                    }
                }
                Ok(())
            };
            let nominal = r.model.scope.nominal_values();
            check(&nominal).expect("nominal point");
            proptest!(config(8), |(values in near_nominal(nominal.clone()))| {
                check(&values)?;
            });
            if constants.iter().flatten().any(|&x| x != SENTINEL) {
                with_constants[kernel] += 1;
            }
        }
    }
    // Every kernel of some module has constant entries, or its half of the test tests nothing.
    for (kernel, (name, _)) in KERNELS.iter().enumerate() {
        assert!(
            with_constants[kernel] > 0,
            "no module's {name} has constant entries: the test tests nothing for it"
        );
    }
}

#[test]
fn params_struct_and_state_space_value() {
    use gen64::bicycle as b;
    let p = b::Params::NOMINAL;
    assert_eq!(p.to_array(), b::NOMINAL);
    assert_eq!(b::Params::from_array(&b::NOMINAL), p);
    assert_eq!(b::Params::default(), p);
    let mut ss = b::StateSpace::new();
    let mut q = p;
    q.v = 5.0;
    ss.evaluate(&q).expect("valid");
    let r = reference("bicycle");
    let want = r.sym.evaluate(&q.to_array()).expect("valid");
    assert!(rel_diff(ss.a(), want.a.as_slice()) <= 1e-12);
    assert!(rel_diff(ss.b(), want.b.as_slice()) <= 1e-12);
    assert_eq!(
        b::PARAM_UNITS[b::PARAM_NAMES.iter().position(|n| *n == "v").expect("v")],
        "m/s"
    );
}
