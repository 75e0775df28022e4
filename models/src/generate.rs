//! Model files generated for size and stress tests: the text of a model file, as a user
//! would write it, for sizes no one writes by hand.

use std::fmt::Write;

/// A model file of `n` identical bodies, each on its own slider along z and its own spring
/// and damper (m = 1, k = 4, c = 0.1: every body the oscillator ω = 2 rad/s, ζ = 0.025), the
/// first `driven` bodies each driven by a force along z and seen by a displacement sensor
/// along z. No item couples two bodies: the model has `n` identical decoupled oscillators
/// (2n states), of which exactly the `driven` ones are controllable and observable, so its
/// minimal order is `2 · driven` (issue 27, item 7). With `derived`, each body's mass is
/// its own derived parameter (`m1 = "m"`, …), which exercises the derived parameters.
pub fn identical_bodies(n: usize, driven: usize, derived: bool) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "# {n} identical bodies, each on its own slider and spring; {driven} driven and seen\n\
         \n[model]\nname = \"identical{n}\"\n\n[parameters]\n\
         m = {{ value = 1, unit = \"kg\", range = \"> 0\" }}\n\
         k = {{ value = 4, unit = \"N/m\", range = \"> 0\" }}\n\
         c = {{ value = 0.1, unit = \"N s/m\", range = \">= 0\" }}"
    );
    if derived {
        for i in 1..=n {
            let _ = writeln!(t, "m{i} = \"m\"");
        }
    }
    for i in 1..=n {
        let mass = if derived {
            format!("m{i}")
        } else {
            "m".to_string()
        };
        let _ = writeln!(
            t,
            "\n[[body]]\nname = \"b{i}\"\nat = [{i}, 0, 0]\nmass = \"{mass}\"\n\
             \n[[rigid_point]]\nname = \"slider{i}\"\nbetween = [\"b{i}\", \"ground\"]\n\
             at = [{i}, 0, 0]\nforces = 2\nmoments = 3\naxis = [0, 0, 1]\n\
             \n[[flex_point]]\nname = \"spring{i}\"\nbetween = [\"b{i}\", \"ground\"]\n\
             at = [{i}, 0, 0]\nforces = 1\naxis = [0, 0, 1]\nstiffness = [\"k\", 0]\n\
             damping = [\"c\", 0]"
        );
    }
    for i in 1..=driven.min(n) {
        let _ = writeln!(
            t,
            "\n[[actuator]]\nname = \"f{i}\"\nbetween = [\"b{i}\", \"ground\"]\n\
             ends = [[{i}, 0, 0], [{i}, 0, -1]]\n\
             \n[[sensor]]\nname = \"z{i}\"\nbetween = [\"b{i}\", \"ground\"]\n\
             ends = [[{i}, 0, 0], [{i}, 0, -1]]"
        );
    }
    t
}
