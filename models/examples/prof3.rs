use eom_model::*;
use std::time::Instant;
fn main() {
    let arg = std::env::args().nth(1).unwrap_or_default();
    let n: usize = std::env::var("N")
        .ok()
        .and_then(|x| x.parse().ok())
        .unwrap_or(2000);
    let nm = models::build("bicycle", &[]).unwrap().nominal().unwrap();
    let t = Instant::now();
    let mut count = 0usize;
    match arg.as_str() {
        "assemble" => {
            for _ in 0..n {
                let a = assemble(&nm).unwrap();
                count += a.mass.nnz();
            }
        }
        "both" => {
            for _ in 0..n {
                let a = assemble(&nm).unwrap();
                let r = reduce(&a, None).unwrap();
                count += r.state_space.a.nrows();
            }
        }
        "replay" => {
            let plan = reduce(&assemble(&nm).unwrap(), None).unwrap().plan;
            for _ in 0..n {
                let a = assemble(&nm).unwrap();
                let r = reduce(&a, Some(&plan)).unwrap();
                count += r.state_space.a.nrows();
            }
        }
        _ => {}
    }
    eprintln!(
        "{arg}: {n} calls, {:?} per call ({count})",
        t.elapsed() / n.max(1) as u32
    );
}
