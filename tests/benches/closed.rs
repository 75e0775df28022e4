//! Closed forms of the bicycle with all 27 parameters symbolic: the characteristic polynomial
//! (from the descriptor pencil) and the Liénard–Chipart conditions. The sizes are printed, for
//! the comparison with sympy (docs/method.md, "Closed forms").

use criterion::{Criterion, criterion_group, criterion_main};
use eom_model::Linearizer;
use eom_sym::Expr;
use eom_sym::closed::ClosedForms;
use std::hint::black_box;

fn closed(c: &mut Criterion) {
    let m = models::build("bicycle", &[]).expect("bicycle");
    let sym = Linearizer::new(&m).symbolic().expect("symbolic");
    let (e, f) = sym.pencil();
    let cf = ClosedForms::default();
    let p = cf.pencil_polynomial(Some(&e), &f).expect("polynomial");
    let conds = cf.stability_conditions(&p).expect("conditions");
    let ce: Vec<Expr> = conds.iter().map(|c| c.expression).collect();
    eprintln!(
        "bicycle: s^{} × degree-{} polynomial, {} unique nodes, {} operations; {} conditions, {} \
         operations (normal form: {})",
        p.zero_roots,
        p.polynomial.degree(),
        Expr::dag_size(&p.polynomial.coefficients),
        Expr::op_count(&p.polynomial.coefficients).total(),
        conds.len(),
        Expr::op_count(&ce).total(),
        p.normalized
    );
    let mut g = c.benchmark_group("closed forms");
    g.sample_size(20);
    g.bench_function(
        "bicycle (27 symbols): characteristic polynomial + Hurwitz",
        |b| {
            b.iter(|| {
                let p = cf
                    .pencil_polynomial(Some(black_box(&e)), &f)
                    .expect("polynomial");
                cf.stability_conditions(&p).expect("conditions")
            })
        },
    );
    g.finish();
}

criterion_group!(benches, closed);
criterion_main!(benches);
