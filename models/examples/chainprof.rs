use eom_sym::model::*;
fn main() {
    let n: usize = std::env::args().nth(1).and_then(|x| x.parse().ok()).unwrap_or(200);
    let model = models::build(&format!("chain{n}"), &[]).unwrap();
    let a = assemble(&model).unwrap();
    let r = reduce(&a, None).unwrap();
    eprintln!("{}", r.state_space.a.nrows());
}
