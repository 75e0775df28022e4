//! Prints a model's descriptor pencil (E, F) and characteristic-polynomial coefficients as JSON
//! with expressions in eom's syntax, for the by-hand comparison with sympy in bench/sympy.
//!
//! cargo run --release -p tests --example pencil_json -- bicycle > bicycle_pencil.json

use eom_model::Linearizer;
use eom_sym::Expr;
use eom_sym::closed::ClosedForms;

fn main() {
    let name = std::env::args().nth(1).unwrap_or_else(|| "bicycle".into());
    let m = models::build(&name, &[]).expect("model");
    let sym = Linearizer::new(&m).symbolic().expect("symbolic");
    let (e, f) = sym.pencil();
    let rows = |x: &nalgebra::DMatrix<Expr>| -> Vec<Vec<String>> {
        (0..x.nrows())
            .map(|i| (0..x.ncols()).map(|j| x[(i, j)].to_string()).collect())
            .collect()
    };
    let p = ClosedForms::default()
        .pencil_polynomial(Some(&e), &f)
        .expect("polynomial");
    let out = serde_json::json!({
        "model": name,
        "parameters": m.scope.names(),
        "E": rows(&e),
        "F": rows(&f),
        "zero_roots": p.zero_roots,
        "coefficients": p.polynomial.coefficients.iter().map(|c| c.to_string()).collect::<Vec<_>>(),
        "scale": p.scale.to_string(),
        "operations": Expr::op_count(&p.polynomial.coefficients).total(),
        "unique_nodes": Expr::dag_size(&p.polynomial.coefficients),
    });
    println!("{}", serde_json::to_string_pretty(&out).expect("json"));
}
