use eom_model::*;
use std::time::Instant;
fn main() {
    let model = models::build("bicycle", &[]).unwrap();
    let t = Instant::now();
    let a = assemble(&model).unwrap();
    let t1 = t.elapsed();
    let r = reduce(&a, None).unwrap();
    let t2 = t.elapsed();
    println!("bicycle symbolic: assemble {:?}, +reduce {:?}", t1, t2);
    let nm = model.nominal().unwrap();
    let t = Instant::now();
    for _ in 0..1000 {
        let a = assemble(&nm).unwrap();
        let _ = reduce(&a, None).unwrap();
    }
    println!("bicycle numeric: {:?} per call", t.elapsed() / 1000);
    let t = Instant::now();
    for _ in 0..1000 {
        let a = assemble(&nm).unwrap();
        let _ = reduce(&a, Some(&r.plan)).unwrap();
    }
    println!("bicycle numeric replay: {:?} per call", t.elapsed() / 1000);
    let t = Instant::now();
    for _ in 0..100 {
        let a = assemble(&nm).unwrap();
        let _ = reduce_robust(&a).unwrap();
    }
    println!("bicycle robust: {:?} per call", t.elapsed() / 100);
    for n in [10, 50, 200] {
        let model = models::build(&format!("chain{n}"), &[]).unwrap();
        let t = Instant::now();
        let a = assemble(&model).unwrap();
        let r = reduce(&a, None).unwrap();
        let ss = &r.state_space;
        let roots: Vec<eom_sym::Expr> =
            ss.a.iter()
                .chain(ss.b.iter())
                .chain(ss.c.iter())
                .chain(ss.d.iter())
                .copied()
                .filter(|e| !e.is_zero())
                .collect();
        println!(
            "chain{n}: {:?}, ops {}, nnz {}",
            t.elapsed(),
            eom_sym::Expr::op_count(&roots).total(),
            roots.len()
        );
    }
}
