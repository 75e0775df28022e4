//! Generates the bicycle's A..D in `f32` for the controller, the bicycle reduced to 5 states
//! with its zero-order-hold discretisation (`eval_discrete`) for the 1 kHz predictor, and every
//! built-in model in `f64` and `f32` for the `no_std` compile check (`src/nostd_check.rs`).

use eom_codegen::build::Generate;
use std::fmt::Write;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    builtin("bicycle")
        .f32()
        .write_to_out_dir("bicycle.rs")
        .expect("bicycle");
    // The bicycle reduced by balanced truncation at the nominal point (the two structural
    // zeros kept whole, the fast castor mode removed), discretised at run time.
    let model = models::build("bicycle", &[]).expect("bicycle");
    let sym = eom_model::Linearizer::new(&model)
        .symbolic()
        .expect("bicycle");
    let opts = eom_codegen::EmitOptions::default()
        .f32()
        .module("bicycle_reduced")
        .model_name("bicycle")
        .discrete(true);
    let (e, _) = eom_codegen::reduced::emit_reduced(
        &sym,
        5,
        eom_num::model_reduction::ReductionMethod::Balanced,
        &opts,
    )
    .expect("reduced bicycle");
    let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("OUT_DIR"));
    eom_codegen::build::write_if_changed(&out.join("bicycle_reduced.rs"), &e.source)
        .expect("write");
    let mut index = String::new();
    for info in models::catalogue() {
        // A family (`chainN`, `chainpN`) at size 10.
        let name = info.name_at(10);
        let name = name.as_str();
        for (ty, g) in [("f64", builtin(name)), ("f32", builtin(name).f32())] {
            let file = format!("check_{name}_{ty}.rs");
            g.module(&format!("{name}_{ty}"))
                .write_to_out_dir(&file)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            writeln!(index, "include!(concat!(env!(\"OUT_DIR\"), \"/{file}\"));").expect("write");
        }
    }
    eom_codegen::build::write_if_changed(&out.join("check_all.rs"), &index).expect("write");
}

/// The code generator for a built-in model at its defaults.
fn builtin(name: &str) -> Generate {
    Generate::new(models::build(name, &[]).unwrap_or_else(|e| panic!("{name}: {e}")))
}
