//! Print the generated module of a built-in model on stdout, statistics on stderr.
//!
//! `cargo run -p eom-codegen --example emit --release -- bicycle [--f32] [--std] [--simplify]
//! [--simplify-always] [--module NAME] [--chunk N]`

use eom_codegen::{EmitOptions, emit_model};

fn main() {
    let mut args = std::env::args().skip(1);
    let name = args.next().unwrap_or_else(|| "smd".to_string());
    let mut opts = EmitOptions::default();
    while let Some(a) = args.next() {
        opts = match a.as_str() {
            "--f32" => opts.f32(),
            "--std" => opts.std_math(),
            "--simplify" => opts.simplify(true),
            "--simplify-always" => opts.simplify_always(true),
            "--module" => opts.module(&args.next().expect("--module NAME")),
            "--chunk" => {
                opts.max_temporaries(args.next().and_then(|n| n.parse().ok()).expect("--chunk N"))
            }
            other => panic!("unknown option {other}"),
        };
    }
    let model = models::build(&name, &[]).unwrap_or_else(|e| panic!("{e}"));
    let t = std::time::Instant::now();
    let e = emit_model(&model, &opts).unwrap_or_else(|e| panic!("{e}"));
    let dt = t.elapsed();
    print!("{}", e.source);
    eprintln!("{name}: {} bytes in {dt:?}", e.source.len());
    for f in &e.stats.functions {
        eprintln!(
            "  {}: {} ops ({} add, {} mul, {} div, {} sqrt, {} calls), critical path {}, cost estimate {}, {} distinct checks ({} comparisons), {} stores, {} chunk(s)",
            f.name,
            f.ops.total(),
            f.ops.add,
            f.ops.mul,
            f.ops.div,
            f.ops.sqrt,
            f.ops.func,
            f.critical_path,
            f.cost_estimate(),
            f.distinct_checks,
            f.check_comparisons,
            f.stores,
            f.chunks
        );
    }
    eprintln!("  simplification: {:?}", e.stats.simplification);
    eprintln!(
        "  DAG of A..D: {} nodes, {} operations {:?}",
        e.stats.dag_nodes_abcd,
        e.stats.dag_ops_abcd.total(),
        e.stats.dag_ops_abcd
    );
}
