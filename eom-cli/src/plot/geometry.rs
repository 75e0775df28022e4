//! The drawing of a model from its own geometry: each body a dot at its mass centre joined
//! by sticks to the points of the items on it, each line item (spring, damper, link, beam) a
//! line between its ends, each joint a dot, and the ground points a ground mark. Items that
//! do not support anything (loads, sensors, actuators, wings) are not drawn.
//!
//! A mode moves every point rigidly with its body: `d = t + θ × (p − c)` from the body's six
//! rows of the mode shape (translations `t`, small rotations `θ`, centre `c`).

use eom_model::Model;
use eom_model::items::{Field, GROUND, Index, Item};
use nalgebra::{DVector, Vector3};
use num_complex::Complex64;

/// A point of the drawing, fixed to a body (or to the ground: `body = None`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Node {
    /// Nominal position.
    pub at: [f64; 3],
    /// Index of the body it moves with (into [`Sketch::bodies`]).
    pub body: Option<usize>,
}

/// What a line of the drawing is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeKind {
    /// Part of a body: from its mass centre to a point of one of its items.
    Body,
    /// A line item between two bodies (spring, damper, link, beam).
    Item,
}

/// A line of the drawing.
#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    /// Start.
    pub a: Node,
    /// End.
    pub b: Node,
    /// Body stick or item.
    pub kind: EdgeKind,
}

/// A body: name and mass centre.
#[derive(Clone, Debug, PartialEq)]
pub struct SketchBody {
    /// Name.
    pub name: String,
    /// Mass centre.
    pub centre: [f64; 3],
}

/// The drawing of a model at its nominal geometry.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sketch {
    /// The bodies (the ground excluded).
    pub bodies: Vec<SketchBody>,
    /// Lines.
    pub edges: Vec<Edge>,
    /// Joints and other point items, each fixed to its first body that is not the ground.
    pub joints: Vec<Node>,
    /// Points at which an item holds a body to the ground.
    pub grounds: Vec<[f64; 3]>,
    /// The z component of the sum of the loads fixed in ground axes (the weights): negative
    /// when gravity points along −z (z up), positive in z-down axes, 0 without such loads.
    pub load_z: f64,
}

/// The points of an item: its `location` (point items) and its `ends` (line items).
fn item_points(item: &dyn Item<f64>) -> (Option<[f64; 3]>, [Option<[f64; 3]>; 2]) {
    let mut location: Option<[f64; 3]> = None;
    let mut ends: [Option<[f64; 3]>; 2] = [None, None];
    item.fields(
        &mut |field: Field, x: &f64| match (field.name, field.index) {
            ("location", [Index::Axis(k), _]) => {
                location.get_or_insert([0.0; 3])[k as usize] = *x;
            }
            ("ends", [Index::Nth(i), Index::Axis(k)]) if i < 2 => {
                ends[i as usize].get_or_insert([0.0; 3])[k as usize] = *x;
            }
            _ => {}
        },
    );
    (location, ends)
}

impl Sketch {
    /// The drawing of `model` (numbers: a model evaluated at a point).
    pub fn of(model: &Model<f64>) -> Sketch {
        let bodies: Vec<SketchBody> = model
            .bodies
            .iter()
            .map(|b| SketchBody {
                name: b.name.to_string(),
                centre: b.location,
            })
            .collect();
        let index = |name: &str| {
            if name == GROUND {
                None
            } else {
                bodies.iter().position(|b| b.name == name)
            }
        };
        let load_z = model
            .items()
            .iter()
            .filter_map(|i| match i {
                eom_model::items::AnyItem::Load(l) => Some(l),
                _ => None,
            })
            .filter(|l| &*l.frame == eom_model::GROUND)
            .map(|l| l.force[2])
            .sum();
        let mut s = Sketch {
            bodies: bodies.clone(),
            load_z,
            ..Sketch::default()
        };
        for item in model.items() {
            if !item.supports() {
                continue;
            }
            let on: Vec<Option<usize>> = item.bodies().iter().map(|n| index(n)).collect();
            let (location, ends) = item_points(item);
            if let Some(p) = location {
                s.attach(p, &on);
                let body = on.iter().copied().flatten().next();
                s.joints.push(Node { at: p, body });
            }
            if let [Some(e0), Some(e1)] = ends {
                let (b0, b1) = (on.first().copied().flatten(), on.get(1).copied().flatten());
                s.attach(e0, &on[..1.min(on.len())]);
                s.attach(e1, &on[1.min(on.len())..]);
                s.edges.push(Edge {
                    a: Node { at: e0, body: b0 },
                    b: Node { at: e1, body: b1 },
                    kind: EdgeKind::Item,
                });
            }
        }
        s
    }

    /// Sticks from the centres of the bodies `on` to `p`, or a ground mark for the ground.
    fn attach(&mut self, p: [f64; 3], on: &[Option<usize>]) {
        for b in on {
            match b {
                Some(b) => {
                    let c = self.bodies[*b].centre;
                    if c != p {
                        self.edges.push(Edge {
                            a: Node {
                                at: c,
                                body: Some(*b),
                            },
                            b: Node {
                                at: p,
                                body: Some(*b),
                            },
                            kind: EdgeKind::Body,
                        });
                    }
                }
                None => self.grounds.push(p),
            }
        }
    }

    /// Largest extent of the nominal geometry along any axis (1 for a single point).
    pub fn size(&self) -> f64 {
        let pts = self.points();
        let mut size = 0.0f64;
        for k in 0..3 {
            let lo = pts.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
            let hi = pts.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
            if hi > lo {
                size = size.max(hi - lo);
            }
        }
        if size > 0.0 { size } else { 1.0 }
    }

    /// Every nominal point of the drawing.
    pub fn points(&self) -> Vec<[f64; 3]> {
        let mut p: Vec<[f64; 3]> = self.bodies.iter().map(|b| b.centre).collect();
        p.extend(self.edges.iter().flat_map(|e| [e.a.at, e.b.at]));
        p.extend(self.joints.iter().map(|j| j.at));
        p.extend(self.grounds.iter().copied());
        p
    }
}

/// The motion of every body in one mode: `(t, θ)` per body of the sketch, complex, from the
/// mode shape (six rows per body of `body_names`, the order of the state-space model's
/// physical map). Bodies the shape does not name stay at rest.
pub fn body_motions(
    sketch: &Sketch,
    shape: &DVector<Complex64>,
    body_names: &[String],
) -> Vec<[Vector3<Complex64>; 2]> {
    sketch
        .bodies
        .iter()
        .map(|b| {
            let zero = Vector3::zeros();
            match body_names.iter().position(|n| n == &b.name) {
                Some(k) if shape.len() >= 6 * (k + 1) => {
                    let r = |i| shape[6 * k + i];
                    [
                        Vector3::new(r(0), r(1), r(2)),
                        Vector3::new(r(3), r(4), r(5)),
                    ]
                }
                _ => [zero, zero],
            }
        })
        .collect()
}

/// The complex displacement of a node: `t + θ × (p − c)` of its body (zero on the ground).
pub fn displacement(
    sketch: &Sketch,
    motions: &[[Vector3<Complex64>; 2]],
    node: &Node,
) -> Vector3<Complex64> {
    match node.body {
        None => Vector3::zeros(),
        Some(b) => {
            let c = sketch.bodies[b].centre;
            let arm = Vector3::new(
                Complex64::new(node.at[0] - c[0], 0.0),
                Complex64::new(node.at[1] - c[1], 0.0),
                Complex64::new(node.at[2] - c[2], 0.0),
            );
            let [t, th] = &motions[b];
            t + th.cross(&arm)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_moves_with_its_body_rigidly() {
        let s = Sketch {
            bodies: vec![SketchBody {
                name: "b".into(),
                centre: [1.0, 0.0, 0.0],
            }],
            ..Sketch::default()
        };
        let c = |x: f64| Complex64::new(x, 0.0);
        // A small rotation about z by 0.1 and a translation along y by 0.2.
        let shape = DVector::from_vec(vec![c(0.0), c(0.2), c(0.0), c(0.0), c(0.0), c(0.1)]);
        let m = body_motions(&s, &shape, &["b".to_string()]);
        let node = Node {
            at: [3.0, 0.0, 0.0],
            body: Some(0),
        };
        let d = displacement(&s, &m, &node);
        // θ × (p − c) = 0.1 ẑ × 2 x̂ = 0.2 ŷ.
        assert!((d[1].re - 0.4).abs() < 1e-15 && d[0].norm() == 0.0 && d[2].norm() == 0.0);
        let ground = Node {
            at: [3.0, 0.0, 0.0],
            body: None,
        };
        assert_eq!(displacement(&s, &m, &ground).norm(), 0.0);
    }
}
