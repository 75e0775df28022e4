use eom_sym::simplify::Simplifier;
use eom_sym::testing::{params, random_dag, SplitMix};
use eom_sym::{Expr, SparseMatrix};
use std::time::Duration;

fn atba(seed: u64) -> Vec<Expr> {
    let p = params(16, seed, true);
    let mut rng = SplitMix(seed);
    let n = 6;
    let mut a = SparseMatrix::zeros(n, n);
    let mut b = SparseMatrix::zeros(n, n);
    for i in 0..n {
        for j in 0..n {
            if rng.uniform(0.0, 1.0) < 0.55 {
                let x = p[rng.below(16)];
                let y = p[rng.below(16)];
                let v = match rng.below(4) { 0 => x, 1 => x * y, 2 => x + y, _ => -Expr::int(2) * x };
                a.set(i, j, v);
            }
            if j >= i && rng.uniform(0.0, 1.0) < 0.5 {
                let v = p[rng.below(16)];
                b.set(i, j, v);
                b.set(j, i, v);
            }
        }
    }
    let c = a.transpose().mul(&b).unwrap().mul(&a).unwrap();
    c.iter().map(|e| e.2).collect()
}

#[test]
fn scratch() {
    for seed in 1..6 {
        let r = atba(seed);
        let joint = Simplifier::default().run(&r).unwrap();
        let sep: Vec<Expr> = r.iter().map(|&e| Simplifier::default().run(&[e]).unwrap().roots[0]).collect();
        println!("atba seed {seed}: before {} joint {} separate {} | stop {:?} iters {}", joint.cost_before, joint.cost_after, eom_sym::CostModel::default().of(&sep), joint.stop, joint.iterations);
        for k in [1usize, 2] {
            let o = Simplifier::default().with_stall_iterations(k).run(&r).unwrap();
            println!("   k={k}: {} stop {:?} iters {}", o.cost_after, o.stop, o.iterations);
        }
    }
    for seed in 1..3 {
        let p = params(10, seed, true);
        let roots = random_dag(&p, 4000, 36, seed);
        for k in [0usize, 4] {
            let out = Simplifier::default().with_stall_iterations(k).run(&roots).unwrap();
            println!("random4000 seed {seed} k {k}: dag {} kept {} cost {} -> {} nodes {} iters {} stop {:?} rewrite {:?} total {:?}",
                Expr::dag_size(&roots), out.kept, out.cost_before, out.cost_after, out.egraph_nodes, out.iterations, out.stop, out.rewrite_time, out.time);
        }
    }
}
