use eom_model::*;
use eom_sym::{Dd, dd::refine_eigenvalue, scalar::Scalar};
fn exact(model: &Model, v: f64) -> Vec<(f64, f64)> {
    let values: Vec<Dd> = model
        .scope
        .names()
        .iter()
        .zip(model.scope.nominal_values())
        .map(|(n, x)| match n.as_str() {
            "lambda" => Dd::PI / Dd::from_f64(10.0),
            "v" => Dd::from_f64(v),
            _ => Dd::from_rational(&eom_sym::Rational::from_decimal(&format!("{x}")).unwrap()),
        })
        .collect();
    let m = model.evaluate_in::<Dd>(&values).unwrap();
    let red = reduce(&assemble(&m).unwrap(), None).unwrap();
    let a = &red.state_space.a;
    let rows: Vec<Vec<Dd>> = (0..a.nrows())
        .map(|i| (0..a.ncols()).map(|j| a[(i, j)]).collect())
        .collect();
    let e = eom_num::modes::eigenvalues(&a.map(|x| x.nominal())).unwrap();
    e.iter()
        .filter(|z| z.norm() > 1e-5)
        .map(|z| {
            let (r, i) = refine_eigenvalue(&rows, (z.re, z.im)).unwrap();
            (r.to_f64(), i.to_f64())
        })
        .collect()
}
fn main() {
    let model = models::build("bicycle", &[]).unwrap();
    let sym = Linearizer::new(&model).symbolic().unwrap();
    for v in [5.0, 5.76, 6.0, 7.0] {
        let ex: Vec<num_complex::Complex64> = exact(&model, v)
            .iter()
            .map(|&(r, i)| num_complex::Complex64::new(r, i))
            .collect();
        let vals = model.scope.values_with(&[("v", v)]).unwrap();
        let paths = [
            ("sym", sym.evaluate(&vals).unwrap()),
            (
                "num",
                Linearizer::new(&model)
                    .at(&[("v", v)])
                    .run()
                    .unwrap()
                    .state_space,
            ),
            (
                "rob",
                Linearizer::new(&model)
                    .at(&[("v", v)])
                    .method(Method::Robust)
                    .run()
                    .unwrap()
                    .state_space,
            ),
        ];
        for (n, ss) in paths {
            let e = eom_num::modes::eigenvalues(&ss.a).unwrap();
            let k = tests::nonzero(&e, 1e-5);
            let pairs = tests::match_eigenvalues(&k, &ex);
            let zc: Vec<usize> = (0..ss.a.ncols())
                .filter(|&j| ss.a.column(j).iter().all(|&x| x == 0.0))
                .collect();
            let keep: Vec<usize> = (0..ss.a.ncols()).filter(|j| !zc.contains(j)).collect();
            let sub = ss.a.select_rows(&keep).select_columns(&keep);
            let e2 = eom_num::modes::eigenvalues(&sub).unwrap();
            let k2 = tests::nonzero(&e2, 1e-5);
            if k2.len() == 4 {
                let p2 = tests::match_eigenvalues(&k2, &ex);
                println!(
                    "   deflated {zc:?}: errs {:?}",
                    p2.iter()
                        .map(|(g, e)| format!("{:.1e}", (g - e).norm()))
                        .collect::<Vec<_>>()
                );
            }
            let (mr, _) = eom_num::minreal::minimal_realization(&ss, &Default::default()).unwrap();
            let em = eom_num::modes::eigenvalues(&mr.a).unwrap();
            if em.len() == 4 {
                let p3 = tests::match_eigenvalues(&em, &ex);
                println!(
                    "   minreal: errs {:?}",
                    p3.iter()
                        .map(|(g, e)| format!("{:.1e}", (g - e).norm()))
                        .collect::<Vec<_>>()
                );
            } else {
                println!("   minreal states {}", em.len());
            }
            println!(
                "v={v} {n}: errs {:?}  zeros {:?}",
                pairs
                    .iter()
                    .map(|(g, e)| format!("{:.1e}", (g - e).norm()))
                    .collect::<Vec<_>>(),
                e.iter()
                    .filter(|z| z.norm() <= 1e-5)
                    .map(|z| format!("{:.1e}", z.norm()))
                    .collect::<Vec<_>>()
            );
        }
    }
}
