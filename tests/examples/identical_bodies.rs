//! Writes a model file of N identical bodies, each on its own slider and spring, the first
//! `driven` of them with a force and a sensor (`models::generate::identical_bodies`), to
//! standard output: the models of the "many identical bodies" figures in docs/performance.md.
//!
//! ```text
//! cargo run --release -p tests --example identical_bodies -- N [DRIVEN] [--derived]
//! ```

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let number = |i: usize, default: usize| {
        args.get(i)
            .filter(|a| !a.starts_with("--"))
            .map_or(Ok(default), |a| a.parse::<usize>())
    };
    let (Ok(n), Ok(driven)) = (number(0, 100), number(1, 0)) else {
        eprintln!("usage: identical_bodies N [DRIVEN] [--derived]");
        std::process::exit(2);
    };
    let derived = args.iter().any(|a| a == "--derived");
    print!("{}", models::generate::identical_bodies(n, driven, derived));
}
