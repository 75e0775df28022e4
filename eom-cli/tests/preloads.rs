//! Static preloads in `eom analyze` (text and JSON `preloads`) and `eom report`, against
//! hand computations of statically determinate models — the half car on its springs (the
//! lever rule), the hanging double pendulum's pins (the weight below each) — and a model with
//! redundant constraints, whose preloads are reported as not unique (minimum norm: the two
//! identical supports share the load equally).

mod common;
use common::{eom, eom_json};
use serde_json::Value;

fn model(name: &str) -> String {
    format!("{}/../models/{name}.toml", env!("CARGO_MANIFEST_DIR"))
}

/// The preload entry of `item`.
fn entry<'a>(j: &'a Value, item: &str) -> &'a Value {
    j["preloads"]["items"]
        .as_array()
        .expect("items")
        .iter()
        .find(|p| p["item"] == item)
        .unwrap_or_else(|| panic!("no preload of {item}: {}", j["preloads"]))
}

fn vector(v: &Value) -> [f64; 3] {
    let a = v.as_array().expect("three numbers");
    [0, 1, 2].map(|k| a[k].as_f64().expect("a number"))
}

fn close(got: [f64; 3], want: [f64; 3], what: &str) {
    for k in 0..3 {
        assert!(
            (got[k] - want[k]).abs() <= 1e-9 * want.iter().fold(1.0f64, |m, x| m.max(x.abs())),
            "{what}: {got:?} vs {want:?}"
        );
    }
}

#[test]
fn the_half_car_springs_carry_the_weight_by_the_lever_rule() {
    // m g b/(a + b) at the front, m g a/(a + b) at the rear: the springs are compressed
    // (negative tension) and push the body up.
    let (m, g, a, b) = (1500.0, 9.81, 1.1, 1.5);
    let sets = ["--set", "m=1500", "--set", "a=1.1", "--set", "b=1.5"];
    let mut args = vec![
        "analyze".to_string(),
        model("half_car"),
        "--format".into(),
        "json".into(),
    ];
    args.extend(sets.iter().map(|s| s.to_string()));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let j = eom_json(&args);
    assert_eq!(j["preloads"]["statics"], "determinate");
    let front = entry(&j, "spring `front suspension`");
    let rear = entry(&j, "spring `rear suspension`");
    let (wf, wr) = (m * g * b / (a + b), m * g * a / (a + b));
    close(vector(&front["force"]), [0.0, 0.0, wf], "front");
    close(vector(&rear["force"]), [0.0, 0.0, wr], "rear");
    assert!((front["tension"].as_f64().unwrap() + wf).abs() < 1e-9 * wf);
    assert!((rear["tension"].as_f64().unwrap() + wr).abs() < 1e-9 * wr);
    assert_eq!(front["body"], "body");
    assert_eq!(front["unique"], true);
    // The sliders carry nothing: the springs are vertical and the weight acts at the mass
    // centre.
    close(
        vector(&entry(&j, "rigid point `no surge or sway`")["force"]),
        [0.0; 3],
        "slider",
    );

    // The text output shows the same table.
    let mut text_args = vec!["analyze", args[1]];
    text_args.extend_from_slice(&sets);
    let text = eom(&text_args).stdout;
    let line = text
        .lines()
        .find(|l| l.contains("spring `front suspension`"))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(line.contains(&format!("{:.2}", wf)), "{line}");
}

#[test]
fn each_pin_of_the_hanging_double_pendulum_carries_the_weight_below_it() {
    let j = eom_json(&["analyze", &model("double_pendulum"), "--format", "json"]);
    let (m1, m2, g) = (1.0, 1.0, 9.81);
    // The pins' forces on the rods below them (their first bodies), up.
    close(
        vector(&entry(&j, "rigid point `pin1`")["force"]),
        [0.0, 0.0, (m1 + m2) * g],
        "pin1",
    );
    close(
        vector(&entry(&j, "rigid point `pin2`")["force"]),
        [0.0, 0.0, m2 * g],
        "pin2",
    );
}

#[test]
fn redundant_supports_are_reported_as_not_unique_and_minimum_norm() {
    // A block held at one point by two identical ball joints: any split of its weight
    // between them balances it; the minimum-norm split is half each.
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("preloads");
    std::fs::create_dir_all(&dir).expect("a directory");
    let file = dir.join("twice.toml");
    std::fs::write(
        &file,
        r#"[model]
gravity = [0, 0, -10]

[[body]]
name = "block"
mass = 3
moments = [1, 1, 1]

[[rigid_point]]
name = "left"
between = ["block", "ground"]
forces = 3
moments = 3

[[rigid_point]]
name = "right"
between = ["block", "ground"]
forces = 3
moments = 3
"#,
    )
    .expect("the model file");
    let f = file.to_str().expect("UTF-8");
    let j = eom_json(&["analyze", f, "--format", "json"]);
    for item in ["rigid point `left`", "rigid point `right`"] {
        let p = entry(&j, item);
        assert_eq!(p["unique"], false, "{p}");
        close(vector(&p["force"]), [0.0, 0.0, 15.0], item);
    }
    let text = eom(&["analyze", f]).stdout;
    assert!(text.contains("not unique (minimum norm)"), "{text}");

    // The report has the section, with the same note.
    let out = dir.join("report");
    std::fs::create_dir_all(&out).expect("a directory");
    let r = eom(&["report", f, "-o", out.to_str().expect("UTF-8"), "--quiet"]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    let html = std::fs::read_to_string(out.join("twice.html")).expect("the page");
    assert!(html.contains("<h2 id=\"preloads\">") && html.contains("not unique (minimum norm)"));
}
