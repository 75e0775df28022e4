//! `eom check`: validate a model (file or built-in) and summarise it; `eom new`: a commented
//! starter file.

use crate::error::CliError;
use crate::params::ModelChoice;
use eom_model::{assemble, reduce_report};
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
    /// Warnings of the loading and of the linearization.
    pub warnings: Vec<String>,
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
            (loaded.model, loaded.warnings)
        }
        crate::params::Source::Builtin => (choice.build(&[])?, Vec::new()),
    };
    let numeric = model.nominal()?;
    let assembled = assemble(&numeric)?;
    let reduction = reduce_report(&assembled)?;
    warnings.extend(reduction.warnings.iter().cloned());
    let mut items: Vec<(String, usize)> = Vec::new();
    for kind in eom_model::KINDS {
        let n = model.items_of(kind).count();
        if n > 0 {
            items.push((kind.to_string(), n));
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
        states: reduction.position_states + reduction.velocity_states,
        inputs: assembled.inputs.iter().map(|(n, _)| n.clone()).collect(),
        outputs: assembled.outputs.iter().map(|(n, _)| n.clone()).collect(),
        warnings,
    })
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
/// displacement output, ready to analyse.
pub fn starter(name: &str) -> String {
    format!(
        r#"# {name}: an eom model file (format: docs/model-files.md).
# Try: eom check {name}.toml; eom analyze {name}.toml; eom analyze {name}.toml --set k=20

[model]
name = "{name}"
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
    )
}
