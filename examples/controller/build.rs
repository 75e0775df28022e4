//! Generates the bicycle's A..D in `f32` for the controller, and every built-in model in `f64`
//! and `f32` for the `no_std` compile check (`src/nostd_check.rs`).

use eom_codegen::build::Generate;
use std::fmt::Write;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    builtin("bicycle")
        .f32()
        .write_to_out_dir("bicycle.rs")
        .expect("bicycle");
    let mut index = String::new();
    for info in models::catalogue() {
        // A pattern (`chainN`, `chainpN`) at size 10.
        let name = match info.name.strip_suffix('N') {
            Some(stem) => format!("{stem}10"),
            None => info.name.to_string(),
        };
        let name = name.as_str();
        for (ty, g) in [("f64", builtin(name)), ("f32", builtin(name).f32())] {
            let file = format!("check_{name}_{ty}.rs");
            g.module(&format!("{name}_{ty}"))
                .write_to_out_dir(&file)
                .unwrap_or_else(|e| panic!("{name}: {e}"));
            writeln!(index, "include!(concat!(env!(\"OUT_DIR\"), \"/{file}\"));").expect("write");
        }
    }
    let out = std::path::PathBuf::from(std::env::var_os("OUT_DIR").expect("OUT_DIR"));
    eom_codegen::build::write_if_changed(&out.join("check_all.rs"), &index).expect("write");
}

/// The code generator for a built-in model at its defaults.
fn builtin(name: &str) -> Generate {
    Generate::new(models::build(name, &[]).unwrap_or_else(|e| panic!("{name}: {e}")))
}
