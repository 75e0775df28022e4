//! Any model as a model file: parameters with their metadata, then every body and item with
//! its settings and its fields (expressions in the parser's syntax).

use super::params::ParamRange;
use crate::Model;
use crate::items::{AnyItem, BODY, Body, Field, Index, Item, Setting};
use eom_sym::Expr;
use std::fmt::Write;

/// The model as the text of a model file that loads back into the same model.
pub fn to_toml(model: &Model) -> String {
    let mut t = String::new();
    // The comment holds the name escaped: a line break in it would end the comment.
    let _ = writeln!(
        t,
        "# {} — written by eom export",
        eom_text::escaped(&model.name)
    );
    let _ = writeln!(t, "\n[model]\nname = {}", quote(&model.name));
    let _ = writeln!(t, "\n[parameters]");
    for p in model.scope.params() {
        let Some(info) = p.param_info() else { continue };
        let mut fields = vec![format!("value = {}", number(info.nominal))];
        if let Some(u) = info.unit.filter(|u| !u.is_empty()) {
            fields.push(format!("unit = {}", quote(&u)));
        }
        if let Some(d) = info.description.filter(|d| !d.is_empty()) {
            fields.push(format!("description = {}", quote(&d)));
        }
        let range = ParamRange::of(info.assume);
        if range != ParamRange::Any {
            fields.push(format!("range = {}", quote(&range.text())));
        }
        let _ = writeln!(t, "{} = {{ {} }}", key(&info.name), fields.join(", "));
    }
    for b in &model.bodies {
        write_item(&mut t, BODY.key, b, &Body::new(&b.name));
    }
    for item in model.items() {
        let defaults = AnyItem::declared(item.kind_id(), item.name());
        write_item(&mut t, item.kind_id().kind().key, item, &defaults);
    }
    t
}

/// One `[[kind]]` table: its settings, then its fields, leaving out those that are zero where
/// the declared default (`defaults`) is zero too.
fn write_item(t: &mut String, kind: &str, item: &dyn Item<Expr>, defaults: &dyn Item<Expr>) {
    let mut nonzero_default: Vec<&'static str> = Vec::new();
    defaults.fields(&mut |f, e| {
        if !e.is_zero() && !nonzero_default.contains(&f.name) {
            nonzero_default.push(f.name);
        }
    });
    let _ = writeln!(t, "\n[[{kind}]]\nname = {}", quote(item.name()));
    let mut feedthrough: Option<String> = None;
    for (k, s) in item.settings() {
        let value = match s {
            Setting::Text(x) if k == "feedthrough" => {
                feedthrough = Some(x);
                continue;
            }
            Setting::Text(x) => quote(&x),
            Setting::Pair([a, b]) => format!("[{}, {}]", quote(&a), quote(&b)),
            Setting::Count(n) => n.to_string(),
            Setting::Flag(f) => f.to_string(),
        };
        let _ = writeln!(t, "{k} = {value}");
    }
    let mut groups: Vec<(&'static str, Vec<(Field, Expr)>)> = Vec::new();
    item.fields(
        &mut |f, e| match groups.iter_mut().find(|(n, _)| *n == f.name) {
            Some(g) => g.1.push((f, *e)),
            None => groups.push((f.name, vec![(f, *e)])),
        },
    );
    // A wing's derivatives go into one inline table, by their AVL names.
    let mut derivatives: Vec<String> = Vec::new();
    for (name, values) in groups {
        if crate::items::wing_derivative_index(name).is_some()
            || crate::items::WING_ACCELERATION_DERIVATIVES.contains(&name)
        {
            if !values[0].1.is_zero() {
                derivatives.push(format!("{name} = {}", value(&values[0].1)));
            }
            continue;
        }
        if name == "actuator_gain" {
            if let Some(a) = &feedthrough {
                let _ = writeln!(
                    t,
                    "feedthrough = {{ actuator = {}, gain = {} }}",
                    quote(a),
                    value(&values[0].1)
                );
            }
            continue;
        }
        if values.iter().all(|(_, e)| e.is_zero()) && !nonzero_default.contains(&name) {
            continue;
        }
        let _ = writeln!(t, "{} = {}", file_key(name), group(&values));
    }
    if !derivatives.is_empty() {
        let _ = writeln!(t, "derivatives = {{ {} }}", derivatives.join(", "));
    }
}

/// The file's key for a field (the builders' `at` for a location).
fn file_key(field: &str) -> &str {
    match field {
        "location" => "at",
        f => f,
    }
}

/// A scalar, vector, array, array of vectors or matrix, from its indexed values.
fn group(values: &[(Field, Expr)]) -> String {
    match values[0].0.index {
        [Index::None, _] => value(&values[0].1),
        [Index::Axis(_), _] | [Index::Nth(_), Index::None] => {
            list(values.iter().map(|v| value(&v.1)))
        }
        [Index::Nth(_), _] => {
            let mut rows: Vec<Vec<String>> = Vec::new();
            for (f, e) in values {
                let Index::Nth(i) = f.index[0] else { continue };
                let i = usize::from(i);
                if rows.len() <= i {
                    rows.resize(i + 1, Vec::new());
                }
                rows[i].push(value(e));
            }
            list(rows.into_iter().map(|r| list(r.into_iter())))
        }
    }
}

fn list(items: impl Iterator<Item = String>) -> String {
    format!("[{}]", items.collect::<Vec<_>>().join(", "))
}

/// An integer as a TOML integer, anything else as an expression string.
fn value(e: &Expr) -> String {
    // An inexact constant stays in the parser's `float(…)` spelling: a bare decimal would read
    // back as the exact decimal fraction, a different number.
    match e.as_rational().and_then(|r| r.as_small()) {
        Some((n, 1)) => n.to_string(),
        _ => quote(&e.to_string()),
    }
}

/// A nominal value: the shortest text that reads back as the same `f64`.
fn number(x: f64) -> String {
    if x == x.trunc() && x.abs() < 1e15 {
        format!("{}", x as i64)
    } else {
        format!("{x:?}")
    }
}

/// `s` as a TOML basic string (quoted, with `"`, `\\` and every control character escaped):
/// the one way eom writes text into a model file.
pub fn toml_string(s: &str) -> String {
    quote(s)
}

/// A TOML basic string.
fn quote(s: &str) -> String {
    let mut q = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => q.push_str("\\\""),
            '\\' => q.push_str("\\\\"),
            '\n' => q.push_str("\\n"),
            c if c.is_control() => {
                let _ = write!(q, "\\u{:04X}", c as u32);
            }
            c => q.push(c),
        }
    }
    q.push('"');
    q
}

/// A TOML key: bare when it can be, quoted otherwise.
fn key(s: &str) -> String {
    if !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        s.to_string()
    } else {
        quote(s)
    }
}
