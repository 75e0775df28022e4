//! Runs the failure map and prints the table: `cargo run --release -p eom-bench --example
//! stress [-- --quick]`.
fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let t = std::time::Instant::now();
    let map = eom_bench::stress::run(quick, &mut |r| eprintln!("{r} ({:.1?})", t.elapsed()))
        .expect("stress map");
    println!("{}", eom_bench::stress::output::markdown(&map));
    eprintln!("total {:.1?}", t.elapsed());
    for r in &map.regions {
        for m in eom_bench::stress::METHODS {
            let worst = map
                .cells
                .iter()
                .filter(|c| c.region == r.name && c.method == m)
                .filter_map(|c| c.error)
                .fold(None, |a: Option<f64>, e| Some(a.map_or(e, |a| a.max(e))));
            if let Some(w) = worst {
                eprintln!("{:<24} {:<14} worst error {w:.2e}", r.name, m);
            }
        }
    }
    for c in &map.cells {
        if c.outcome != eom_bench::stress::classify::Outcome::Accurate {
            eprintln!(
                "{} {:e} {}: {} {:?} [{}] {}",
                c.region,
                c.value,
                c.method,
                c.outcome.label(),
                c.error,
                c.reference,
                c.note
            );
        }
    }
}
