//! `eom check`: validate a model (file or built-in) and summarise it; `eom new`: a commented
//! starter file.

use crate::error::CliError;
use crate::params::ModelChoice;
use crate::shown_warning::ShownWarning;
use eom_model::{Linearizer, Method, ModelError, assemble, reduce_report};
use serde::Serialize;

/// The summary `eom check` prints.
#[derive(Clone, Debug, Serialize)]
pub struct CheckReport {
    /// The model as given.
    pub model: String,
    /// Parameters with their defaults.
    pub parameters: Vec<(String, f64)>,
    /// The bodies.
    pub bodies: Vec<String>,
    /// Item counts by kind.
    pub items: Vec<(String, usize)>,
    /// Six per body.
    pub degrees_of_freedom: usize,
    /// Holonomic constraint rows (links, joints).
    pub holonomic_constraints: usize,
    /// Nonholonomic constraint rows (rolling contacts).
    pub nonholonomic_constraints: usize,
    /// States of the reduced model.
    pub states: usize,
    /// Inputs.
    pub inputs: Vec<String>,
    /// Outputs.
    pub outputs: Vec<String>,
    /// What each input and output is, in words: the sign conventions of the actuators (a
    /// force extending the line from end 2 to end 1) and sensors (end 1 relative to end 2).
    pub signals: Vec<String>,
    /// Warnings of the loading and of the linearization (JSON: objects with `kind`, `item` and
    /// `message`).
    pub warnings: Vec<ShownWarning>,
}

/// Builds, assembles and reduces the model at its defaults (the numeric elimination with all
/// its checks, without forming the dense state space: a model of many bodies is validated in
/// time and memory linear in its size where its matrices would not fit).
pub fn check(choice: &ModelChoice) -> Result<CheckReport, CliError> {
    // A file is loaded once, its own warnings kept (e.g. derivatives an AVL stability-axis
    // file cannot give).
    let (model, mut warnings) = match &choice.source {
        crate::params::Source::File(path) => {
            let loaded = eom_model::file::load(path, &[])?;
            (loaded.model, shown(&loaded.warnings))
        }
        crate::params::Source::Builtin => (choice.build(&[])?, Vec::new()),
    };
    let numeric = model.nominal()?;
    let assembled = assemble(&numeric)?;
    // The numeric elimination first; where it cannot reduce the model (a massless motion,
    // which its messages suggest the robust path for), the robust path, and the command that
    // works.
    let states = match reduce_report(&assembled) {
        Ok(reduction) => {
            warnings.extend(shown(&reduction.warnings));
            reduction.position_states + reduction.velocity_states + reduction.lag_states
        }
        Err(numeric) => {
            // A massless motion's advice names the library's path, not a command: said here
            // without it (the warning below names the command).
            let numeric = match &numeric {
                ModelError::MasslessMotion { coordinates } => format!(
                    "the reduced mass matrix is singular at the nominal point (massless motion \
                     of {})",
                    coordinates.join(", ")
                ),
                e => e.to_string(),
            };
            match Linearizer::new(&model).method(Method::Robust).run() {
                Ok(lin) => {
                    warnings.push(ShownWarning::new(
                        "robust_reduction_needed",
                        format!(
                            "the default reduction fails ({}); the robust one reduces the \
                             model: analyse it with `eom analyze {} --method robust`",
                            numeric,
                            eom_text::shown(&choice.name)
                        ),
                    ));
                    warnings.extend(shown(&lin.warnings));
                    lin.state_space.states()
                }
                Err(robust) => {
                    return Err(CliError::BadArgument {
                        argument: eom_text::shown(&choice.name),
                        problem: format!(
                            "no reduction handles this model: the numeric one fails ({numeric}), \
                             and so does the robust one ({robust})"
                        ),
                    });
                }
            }
        }
    };
    let mut items: Vec<(String, usize)> = Vec::new();
    for kind in eom_model::items::KINDS {
        let n = model.items_of(kind.name).count();
        if n > 0 {
            items.push((kind.name.to_string(), n));
        }
    }
    Ok(CheckReport {
        model: choice.name.clone(),
        parameters: choice.values(&[]),
        bodies: assembled.bodies.clone(),
        items,
        degrees_of_freedom: 6 * assembled.bodies.len(),
        holonomic_constraints: assembled.holonomic_rows.len(),
        nonholonomic_constraints: assembled.nonholonomic_rows.len(),
        states,
        inputs: assembled.inputs.iter().map(|(n, _)| n.clone()).collect(),
        outputs: assembled.outputs.iter().map(|(n, _)| n.clone()).collect(),
        signals: signal_descriptions(&numeric),
        warnings,
    })
}

/// The inputs and outputs in words, with their sign conventions: an actuator's input pushes
/// end 1 (on body 1) away from end 2 (on body 2) along the line (or twists body 1 about it
/// relative to body 2); a sensor measures end 1 relative to end 2 along the line from end 2 to
/// end 1 (or body 1's rotation relative to body 2 about it).
pub fn signal_descriptions(model: &eom_model::Model<f64>) -> Vec<String> {
    use eom_model::items::AnyItem;
    use eom_model::{Line, SensorFrame, SensorOrder};
    let fmt = |v: &[f64; 3]| {
        format!(
            "({}, {}, {})",
            crate::format::g(v[0], 4),
            crate::format::g(v[1], 4),
            crate::format::g(v[2], 4)
        )
    };
    let direction = |l: &Line<f64>| {
        let d = [0, 1, 2].map(|k| l.ends[0][k] - l.ends[1][k]);
        let n = d.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n > 0.0 {
            fmt(&d.map(|x| x / n))
        } else {
            "its line".into()
        }
    };
    let ends = |l: &Line<f64>| {
        format!(
            "end 1 on `{}` at {}, end 2 on `{}` at {}",
            l.bodies[0],
            fmt(&l.ends[0]),
            l.bodies[1],
            fmt(&l.ends[1])
        )
    };
    let mut out = Vec::new();
    for item in model.items() {
        if let AnyItem::Actuator(a) = item {
            let l = &a.line;
            let what = if l.twist {
                format!(
                    "a moment (gain·u + rate_gain·u̇) turning `{}` relative to `{}` about {}",
                    l.bodies[0],
                    l.bodies[1],
                    direction(l)
                )
            } else {
                format!(
                    "a force (gain·u + rate_gain·u̇) pushing end 1 away from end 2 along {} \
                     (from end 2 to end 1)",
                    direction(l)
                )
            };
            out.push(format!("input `{}`: {what}; {}", a.name, ends(l)));
        } else if let AnyItem::Sensor(s) = item {
            let l = &s.line;
            let order = match s.order {
                SensorOrder::Displacement => "displacement",
                SensorOrder::Velocity => "velocity",
                SensorOrder::Acceleration => "acceleration",
            };
            let frame = match (s.order, s.frame) {
                (SensorOrder::Displacement, _) | (_, SensorFrame::Global) => "",
                (_, SensorFrame::Local) => " (in the moving bodies' axes)",
            };
            let what = if l.twist {
                format!(
                    "gain × rotation {order}{frame} of `{}` relative to `{}` about {}",
                    l.bodies[0],
                    l.bodies[1],
                    direction(l)
                )
            } else {
                format!(
                    "gain × {order}{frame} of end 1 relative to end 2 along {} (from end 2 to \
                     end 1)",
                    direction(l)
                )
            };
            out.push(format!("output `{}`: {what}; {}", s.name, ends(l)));
        }
    }
    out
}

impl CheckReport {
    /// Plain text.
    pub fn to_text(&self) -> String {
        let mut t = format!("{}: valid\n", self.model);
        let p: Vec<String> = self
            .parameters
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        t.push_str(&format!("  parameters ({}): {}\n", p.len(), p.join(", ")));
        t.push_str(&format!(
            "  bodies ({}): {}\n",
            self.bodies.len(),
            self.bodies.join(", ")
        ));
        let i: Vec<String> = self.items.iter().map(|(k, n)| format!("{n} {k}")).collect();
        t.push_str(&format!("  items: {}\n", i.join(", ")));
        t.push_str(&format!(
            "  {} degrees of freedom, {} holonomic and {} nonholonomic constraint rows → {} states\n",
            self.degrees_of_freedom,
            self.holonomic_constraints,
            self.nonholonomic_constraints,
            self.states
        ));
        t.push_str(&format!("  inputs: {}\n", list(&self.inputs)));
        t.push_str(&format!("  outputs: {}\n", list(&self.outputs)));
        for s in &self.signals {
            t.push_str(&format!("    {s}\n"));
        }
        for w in &self.warnings {
            t.push_str(&format!("  warning: {w}\n"));
        }
        t
    }
}

fn list(v: &[String]) -> String {
    if v.is_empty() {
        "none".into()
    } else {
        v.join(", ")
    }
}

/// A commented starter file: a mass on a spring and damper, with a force input and a
/// displacement output, ready to analyse. The name is refused when it holds a character no
/// name may hold (a line break would end the comment it appears in), and written as a TOML
/// string, so that the file loads whatever the name.
pub fn starter(name: &str) -> Result<String, CliError> {
    if let Some(problem) = eom_text::name_problem(name) {
        return Err(CliError::BadArgument {
            argument: format!("eom new {}", eom_text::shown(name)),
            problem: format!("the model name {problem}"),
        });
    }
    let quoted = eom_model::file::toml_string(name);
    Ok(format!(
        r#"# {name}: an eom model file (format: docs/model-files.md).
# Try: eom check {name}.toml; eom analyze {name}.toml; eom analyze {name}.toml --set k=20

[model]
name = {quoted}
description = "a mass on a vertical spring and damper"
gravity = [0, 0, "-g"]          # a weight on every body with mass

[parameters]
# name = value, or a table with value, unit, description and range ("> 0", ">= 0", "any",
# "[0, 1]"); a string is a derived parameter (an expression of the others).
m = {{ value = 1, unit = "kg", description = "mass", range = "> 0" }}
k = {{ value = 10, unit = "N/m", description = "stiffness", range = "> 0" }}
c = {{ value = 0.1, unit = "N s/m", description = "damping", range = ">= 0" }}
g = {{ value = 9.81, unit = "m/s^2", description = "gravity", range = "> 0" }}
h = {{ value = 0.5, unit = "m", description = "height of the mass", range = "> 0" }}

[[body]]
name = "block"
mass = "m"
at = [0, 0, "h"]

# A slider: the block moves along z only (two forces across the axis, all three moments).
[[rigid_point]]
name = "slider"
between = ["block", "ground"]
at = [0, 0, "h"]
forces = 2
moments = 3
axis = [0, 0, 1]

# The spring and damper between the block and the ground (its preload is solved from the
# weight).
[[spring]]
name = "spring"
between = ["block", "ground"]
ends = [[0, 0, "h"], [0, 0, 0]]
stiffness = "k"
damping = "c"

# A force on the block (the input) and its displacement (the output).
[[actuator]]
name = "force"
between = ["block", "ground"]
ends = [[0, 0, "h"], [0, 0, 0]]
units = "N"

[[sensor]]
name = "height"
between = ["block", "ground"]
ends = [[0, 0, "h"], [0, 0, 0]]
units = "m"
"#
    ))
}

/// The model's warnings, as the command shows them.
fn shown(warnings: &[eom_model::Warning]) -> Vec<ShownWarning> {
    ShownWarning::all_of_model(warnings, "")
}
