//! Conventions a user should not have to guess: a sensor measures end 1 relative to end 2 (the
//! quarter car's outputs as rows of C), states driven by input rates are named for what they
//! are (x − Γu), the states are the coordinates users expect where the model allows (a
//! double pendulum's two angles), reserved names are listed once.

mod common;
use common::{eom, eom_json};
use serde_json::Value;

fn row(m: &Value, i: usize) -> Vec<f64> {
    m[i].as_array()
        .expect("a row")
        .iter()
        .map(|x| x.as_f64().expect("a number"))
        .collect()
}

#[test]
fn a_sensor_measures_end_1_relative_to_end_2() {
    // z_s: end 1 on the sprung mass above end 2 on the ground → the sprung mass's height;
    // z_s-z_u: end 1 on the unsprung mass, end 2 on the sprung mass above it → the line
    // points down, so the reading is z_s − z_u.
    let j = eom_json(&["analyze", "quarter_car", "--format", "json"]);
    let m = &j["matrices"];
    assert_eq!(
        m["states"].as_array().unwrap()[..2],
        [Value::from("unsprung.z"), Value::from("sprung.z")]
    );
    assert_eq!(row(&m["C"], 0), [0.0, 1.0, 0.0, 0.0]);
    assert_eq!(row(&m["C"], 1), [-1.0, 1.0, 0.0, 0.0]);
    let check = eom(&["check", "quarter_car"]).stdout;
    assert!(
        check.contains(
            "output `z_s-z_u`: gain × displacement of end 1 relative to end 2 along (0, 0, -1)"
        ),
        "{check}"
    );
}

#[test]
fn states_shifted_by_input_rates_say_so() {
    // The quarter car's road input acts through the tyre's damper ct on the unsprung mass mu:
    // its velocity state is x − (ct/mu)·z_g, 500/50 = 10 at the defaults.
    let j = eom_json(&["analyze", "quarter_car", "--format", "json"]);
    assert_eq!(j["state_names"][2], "unsprung.vz − 10·z_g");
    assert_eq!(j["state_names"][3], "sprung.vz");
    // The half car's, symbolic: (cf·zr_f + cr·zr_r)/m off the body's vertical velocity.
    let file = format!("{}/../models/half_car.toml", env!("CARGO_MANIFEST_DIR"));
    let j = eom_json(&["analyze", &file, "--method", "symbolic", "--format", "json"]);
    assert_eq!(j["state_names"][2], "body.vz − (cf/m)·zr_f − (cr/m)·zr_r");
}

#[test]
fn double_pendulums_keep_their_angles_as_states() {
    // The double pendulum of rods, and of point masses at lengths that differ (the choice
    // once depended on them: `bob1.y, bob2.rx`).
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("conventions");
    std::fs::create_dir_all(&dir).expect("a directory");
    let rods = format!(
        "{}/../models/double_pendulum.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&rods).expect("the model");
    let points = text
        .replace(
            "moments = [\"m1*l1^2/12\", \"m1*l1^2/12\", 0]",
            "moments = [0, 0, 0]",
        )
        .replace(
            "moments = [\"m2*l2^2/12\", \"m2*l2^2/12\", 0]",
            "moments = [0, 0, 0]",
        )
        .replace("at = [0, 0, \"-l1/2\"]", "at = [0, 0, \"-l1\"]")
        .replace("at = [0, 0, \"-l1 - l2/2\"]", "at = [0, 0, \"-l1 - l2\"]");
    assert_ne!(points, text);
    let file = dir.join("point_masses.toml");
    std::fs::write(&file, points).expect("the model file");
    let f = file.to_str().expect("UTF-8");
    for (model, sets) in [
        (rods.as_str(), vec![]),
        (f, vec![]),
        (f, vec!["--set", "l1=1", "--set", "l2=0.5"]),
        (f, vec!["--set", "l1=2.5", "--set", "l2=0.3"]),
    ] {
        let mut args = vec!["analyze", model, "--format", "json"];
        args.extend(sets);
        let j = eom_json(&args);
        assert_eq!(
            j["state_names"],
            serde_json::json!(["rod1.rx", "rod2.rx", "rod1.wx", "rod2.wx"]),
            "{args:?}"
        );
    }
}

#[test]
fn reserved_names_are_listed_once() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("conventions");
    std::fs::create_dir_all(&dir).expect("a directory");
    let file = dir.join("reserved.toml");
    std::fs::write(
        &file,
        "[parameters]\ne = 1\n\n[[body]]\nname = \"b\"\nmass = \"e\"\n",
    )
    .expect("the model file");
    let r = eom(&["check", file.to_str().expect("UTF-8")]);
    assert_eq!(r.code, 2, "{}", r.stderr);
    assert_eq!(r.stderr.matches("parameter `e`").count(), 1, "{}", r.stderr);
    for name in ["pi", "sin", "atan2"] {
        assert!(r.stderr.contains(name), "{}", r.stderr);
    }
}
