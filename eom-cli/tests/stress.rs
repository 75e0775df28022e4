//! `eom bench stress --quick -o DIR`, the reduced failure map CI runs: every file is written,
//! and no method is silently wrong anywhere on the grid (read back from the CSVs the user
//! gets).

mod common;
use common::eom;

#[test]
fn the_quick_stress_map_has_no_silently_wrong_cell() {
    let dir = std::env::temp_dir().join(format!("eom-stress-{}", std::process::id()));
    let d = dir.to_str().expect("UTF-8 path");
    let r = eom(&["--quiet", "bench", "stress", "--quick", "-o", d]);
    assert_eq!(r.code, 0, "{}", r.stderr);
    assert!(r.stdout.contains("| region | points |"), "{}", r.stdout);
    for f in ["stress.csv", "stress_counts.csv", "stress.md", "stress.svg"] {
        assert!(dir.join(f).exists(), "{f} not written: {}", r.stderr);
    }
    let counts = std::fs::read_to_string(dir.join("stress_counts.csv")).expect("counts");
    let mut lines = counts.lines();
    assert_eq!(
        lines.next(),
        Some("region,method,accurate,reported,silently_wrong,unchecked")
    );
    let (mut regions, mut accurate) = (std::collections::BTreeSet::new(), 0);
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let n: Vec<usize> = f[2..].iter().map(|x| x.parse().expect("count")).collect();
        regions.insert(f[0].to_string());
        accurate += n[0];
        assert_eq!(n[2], 0, "silently wrong: {line}");
    }
    // The grid is really there: every region, and most cells accurate.
    assert!(regions.len() >= 13, "{regions:?}");
    assert!(accurate >= 120, "{counts}");
    // The per-cell CSV agrees with the counts.
    let cells = std::fs::read_to_string(dir.join("stress.csv")).expect("cells");
    let wrong = cells
        .lines()
        .skip(1)
        .filter(|l| l.split(',').nth(4) == Some("silently wrong"))
        .count();
    assert_eq!(wrong, 0, "{cells}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A chain of four unit masses on sliders, the third spring `k3`.
fn stiff_chain() -> String {
    let mut s = String::from(
        "[model]\nname = \"chain\"\n[parameters]\nk3 = { value = 1, range = \"> 0\" }\n",
    );
    for i in 1..=4 {
        let prev = if i == 1 {
            "ground".to_string()
        } else {
            format!("b{}", i - 1)
        };
        let k = if i == 3 { "k3" } else { "1" };
        s.push_str(&format!(
            "[[body]]\nname = \"b{i}\"\nat = [{i}, 0, 0]\nmass = 1\nmoments = [1, 1, 1]\n\
             [[rigid_point]]\nname = \"s{i}\"\nbetween = [\"b{i}\", \"ground\"]\nat = [{i}, 0, 0]\n\
             forces = 2\nmoments = 3\naxis = [1, 0, 0]\n\
             [[spring]]\nname = \"l{i}\"\nbetween = [\"b{i}\", \"{prev}\"]\n\
             ends = [[{i}, 0, 0], [{}, 0, 0]]\nstiffness = \"{k}\"\n",
            i - 1
        ));
    }
    s
}

#[test]
fn analyze_warns_about_eigenvalues_the_rounding_makes_uncertain() {
    // The stress map's chain_stiffness region as the user meets it: at a stiffness ratio of
    // 1e10 the slow modes are accurate to a few 1e-6 only, and `eom analyze` says so; at equal
    // stiffnesses it says nothing.
    let dir = std::env::temp_dir().join(format!("eom-stiff-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let file = dir.join("chain.toml");
    std::fs::write(&file, stiff_chain()).expect("model file");
    let f = file.to_str().expect("UTF-8 path");
    let stiff = eom(&["analyze", f, "--set", "k3=1e10"]);
    assert_eq!(stiff.code, 0, "{}", stiff.stderr);
    assert!(
        stiff.stdout.contains("accurate to only about"),
        "{}",
        stiff.stdout
    );
    let even = eom(&["analyze", f]);
    assert_eq!(even.code, 0, "{}", even.stderr);
    assert!(!even.stdout.contains("accurate to only"), "{}", even.stdout);
    // The JSON carries the estimate of every mode: the slow modes beyond 1e-6 with the stiff
    // spring, every mode within 1e-12 with equal ones.
    let worst = |args: &[&str]| -> f64 {
        let out = eom(args);
        assert_eq!(out.code, 0, "{}", out.stderr);
        let j: serde_json::Value = serde_json::from_str(&out.stdout).expect("JSON");
        j["modes"]
            .as_array()
            .expect("modes")
            .iter()
            .map(|m| m["accuracy"].as_f64().expect("accuracy"))
            .fold(0.0, f64::max)
    };
    let stiff_json = worst(&["analyze", f, "--set", "k3=1e10", "--format", "json"]);
    assert!(stiff_json > 1e-6, "{stiff_json:e}");
    let even_json = worst(&["analyze", f, "--format", "json"]);
    assert!(even_json < 1e-12, "{even_json:e}");
    let _ = std::fs::remove_dir_all(&dir);
}
