use eom_model::*;
use eom_num::minreal::{MinrealOptions, minimal_realization};
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let methods: Vec<String> = std::env::args().skip(2).collect();
    let text = std::fs::read_to_string(&path).unwrap();
    let model = eom_model::file::from_str(&text, &path, &[]).unwrap();
    for ms in methods {
        let method = match ms.as_str() {
            "numeric" => Method::Numeric,
            "robust" => Method::Robust,
            _ => Method::Symbolic,
        };
        let lin = Linearizer::new(&model).method(method).run().unwrap();
        let ss = &lin.state_space;
        let (min, rep) = minimal_realization(ss, &MinrealOptions::default()).unwrap();
        println!(
            "{ms}: {} -> {} (unc {}, unobs {})",
            ss.states(),
            min.states(),
            rep.uncontrollable,
            rep.unobservable
        );
        for d in &rep.decisions {
            println!(
                "  {:?} step {} {}x{} rank {} tol {:.2e} sv {:?}",
                d.stage,
                d.step,
                d.rows,
                d.cols,
                d.rank,
                d.tolerance,
                d.singular_values
                    .iter()
                    .take(8)
                    .map(|s| format!("{s:.2e}"))
                    .collect::<Vec<_>>()
            );
        }
        if std::env::var_os("DUMP").is_some() {
            println!("names {:?}", ss.names.states);
            println!(
                "B {:?}",
                ss.b.column(0)
                    .iter()
                    .map(|v| format!("{v:.3}"))
                    .collect::<Vec<_>>()
            );
            println!(
                "C {:?}",
                ss.c.row(0)
                    .iter()
                    .map(|v| format!("{v:.3}"))
                    .collect::<Vec<_>>()
            );
            let n = ss.states();
            for i in 0..n {
                for j in 0..n {
                    let v = ss.a[(i, j)];
                    if v != 0.0 {
                        let (si, sj) = (&ss.names.states[i], &ss.names.states[j]);
                        let ip = |s: &str| s.ends_with(".x") || s.ends_with(".vx");
                        if ip(si) != ip(sj) {
                            println!("couple {si} <- {sj}: {v:.3e}");
                        }
                    }
                }
            }
            let ip: Vec<usize> = (0..n)
                .filter(|&i| {
                    let s = &ss.names.states[i];
                    s.ends_with(".x") || s.ends_with(".vx")
                })
                .collect();
            let sub = nalgebra::DMatrix::from_fn(ip.len(), ip.len(), |i, j| ss.a[(ip[i], ip[j])]);
            let sb = nalgebra::DMatrix::from_fn(ip.len(), 1, |i, _| ss.b[(ip[i], 0)]);
            let sc = nalgebra::DMatrix::from_fn(1, ip.len(), |_, j| ss.c[(0, ip[j])]);
            let st = eom_num::minreal::controllability_staircase(&sub, &sb, &sc, 1e-9).unwrap();
            println!("sub kept {} of {}", st.kept, ip.len());
            let stf =
                eom_num::minreal::controllability_staircase(&ss.a, &ss.b, &ss.c, 1e-9).unwrap();
            println!("full staircase kept {} of {n}", stf.kept);
            let q = &stf.q;
            println!(
                "similarity residual {:.2e}",
                (q * &stf.a * q.transpose() - &ss.a).norm()
            );
            println!(
                "orth residual {:.2e}",
                (q.transpose() * q - nalgebra::DMatrix::<f64>::identity(n, n)).norm()
            );
            for j in 0..35 {
                let out: f64 = (0..n)
                    .filter(|i| !ip.contains(i))
                    .map(|i| q[(i, j)].powi(2))
                    .sum::<f64>()
                    .sqrt();
                print!("{j}:{out:.1e} ");
            }
            println!();
            for j in 0..35 {
                print!("{:.2e} ", stf.a[(j + 1, j)]);
            }
            println!();
            let (m2, _) = minimal_realization(
                ss,
                &MinrealOptions {
                    balance: false,
                    ..Default::default()
                },
            )
            .unwrap();
            println!("minreal unbalanced {}", m2.states());
            let ev = eom_num::modes::eigenvalues(&ss.a).unwrap();
            let evs = eom_num::modes::eigenvalues(&sub).unwrap();
            println!(
                "sub ev {:?}",
                evs.iter()
                    .filter(|z| z.im > 0.0)
                    .map(|z| format!("{:.6}", z.im))
                    .collect::<Vec<_>>()
            );
            println!(
                "all ev {:?}",
                ev.iter()
                    .filter(|z| z.im > 0.0)
                    .map(|z| format!("{:.6}", z.im))
                    .collect::<Vec<_>>()
            );
            for i in 0..0 {
                println!(
                    "A{i} {:?}",
                    (0..n.min(20))
                        .map(|j| format!("{:.2}", ss.a[(i, j)]))
                        .collect::<Vec<_>>()
                );
            }
        }
    }
}
#[allow(dead_code)]
fn _x() {}
