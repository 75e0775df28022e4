fn main() {
    let name = std::env::args().nth(1).unwrap_or("smd".into());
    let m = models::build(&name, &[]).unwrap();
    let e = eom_codegen::emit_model(&m, &eom_codegen::EmitOptions::default()).unwrap();
    println!("{}", e.source);
    eprintln!("{:#?}", e.stats);
}
