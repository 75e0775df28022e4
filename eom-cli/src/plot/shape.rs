//! Mode shapes drawn from the model's geometry ([`super::geometry`]), as SVG written by hand
//! (plotters has no animation): the nominal drawing in grey, the two extremes of the motion
//! (solid and dashed, in the mode's colour), an animated copy that a browser plays through
//! one cycle (SMIL `<animate>`, no script), and the centre of rotation of each body that
//! rotates in the view, as a red ring with a cross.
//!
//! Planar models (geometry and motion in two axes) get one view; 3-D models three: side
//! (x–z), front (y–z) and top (x–y). The vertical axis is z, drawn so that the model's
//! weights point down the page (a model in the z-down axes of vehicle dynamics, like the
//! bicycle, has +z down); without weights, upward unless the bodies lie below z = 0.

use super::geometry::{EdgeKind, Node, Sketch, displacement};
use super::labels::{Placer, text_width};
use nalgebra::Vector3;
use num_complex::Complex64;
use std::f64::consts::TAU;
use std::fmt::Write;

/// Motion amplitude drawn, as a fraction of the model's size.
const AMPLITUDE: f64 = 0.12;

/// Frames of the animation per cycle.
const FRAMES: usize = 24;

/// Duration of one animated cycle, in seconds.
const CYCLE_S: f64 = 2.0;

/// Colour of the mode's motion.
const MODE_COLOUR: &str = "#1f64b4";

/// A view: name, the horizontal and vertical axes (0 = x, 1 = y, 2 = z), and whether the
/// vertical axis grows downward on the page.
#[derive(Clone, Copy, Debug, PartialEq)]
struct View {
    name: &'static str,
    h: usize,
    v: usize,
    down: bool,
}

/// What to draw: the sketch, and the motion of each body (`None`: the model at rest).
pub struct ShapeDrawing<'a> {
    /// Heading (model, mode, eigenvalue).
    pub title: String,
    /// The model's drawing.
    pub sketch: &'a Sketch,
    /// `(t, θ)` per body of the sketch, or `None` for a picture of the model alone.
    pub motions: Option<Vec<[Vector3<Complex64>; 2]>>,
}

const AXES: [&str; 3] = ["x", "y", "z"];

/// Whether z grows downward on the page: the model's weights point along +z (z-down axes,
/// like the bicycle's), so that gravity points down in the picture; without weights, when
/// the bodies' mass centres lie below z = 0 on average.
fn z_down(s: &Sketch) -> bool {
    if s.load_z != 0.0 {
        return s.load_z > 0.0;
    }
    let n = s.bodies.len().max(1) as f64;
    s.bodies.iter().map(|b| b.centre[2]).sum::<f64>() / n < 0.0
}

/// The views for this drawing: one for a planar model, three otherwise.
fn views(s: &Sketch, disp: &[Vector3<Complex64>]) -> Vec<View> {
    let size = s.size();
    let pts = s.points();
    let big = disp.iter().map(|d| d.norm()).fold(0.0f64, f64::max);
    let used: Vec<bool> = (0..3)
        .map(|k| {
            let lo = pts.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
            let hi = pts.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
            let moves = disp.iter().any(|d| d[k].norm() > 1e-6 * big);
            hi - lo > 1e-9 * size || (big > 0.0 && moves)
        })
        .collect();
    let down = z_down(s);
    let side = View {
        name: "side view",
        h: 0,
        v: 2,
        down,
    };
    let front = View {
        name: "front view",
        h: 1,
        v: 2,
        down,
    };
    let top = View {
        name: "top view",
        h: 0,
        v: 1,
        down: !down,
    };
    match (used[0], used[1], used[2]) {
        (true, true, true) => vec![side, front, top],
        (_, true, false) => vec![top],
        (false, true, true) => vec![front],
        _ => vec![side],
    }
}

/// Font size of the body names, in pixels.
const LABEL_PX: f64 = 12.0;

/// The SVG document of a mode shape (or of the model at rest).
pub fn shape_svg(d: &ShapeDrawing<'_>) -> String {
    let s = d.sketch;
    // Every node's complex displacement, scaled to the drawn amplitude.
    let nodes = all_nodes(s);
    let mut disp: Vec<Vector3<Complex64>> = match &d.motions {
        Some(m) => nodes.iter().map(|n| displacement(s, m, n)).collect(),
        None => vec![Vector3::zeros(); nodes.len()],
    };
    let big = disp.iter().map(|v| v.norm()).fold(0.0f64, f64::max);
    if big > 0.0 && big.is_finite() {
        let k = Complex64::new(AMPLITUDE * s.size() / big, 0.0);
        disp.iter_mut().for_each(|v| *v *= k);
    }
    let views = views(s, &disp);
    let (pw, ph) = if views.len() == 1 {
        (760.0, 420.0)
    } else {
        (420.0, 340.0)
    };
    let width = pw * views.len() as f64;
    let height = ph + 40.0;
    let mut out = String::new();
    let _ = write!(
        out,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="sans-serif"><rect width="100%" height="100%" fill="white"/><text x="10" y="24" font-size="{:.1}">{}</text>"##,
        super::labels::fitting_size(&d.title, 17.0, 8.0, width - 20.0),
        escape(&d.title)
    );
    for (k, v) in views.iter().enumerate() {
        let _ = write!(
            out,
            r#"<g transform="translate({},{})">"#,
            k as f64 * pw,
            40.0
        );
        view_svg(
            &mut out,
            s,
            &nodes,
            &disp,
            *v,
            (pw, ph),
            d.motions.as_deref(),
        );
        out.push_str("</g>");
    }
    out.push_str("</svg>\n");
    out
}

/// The nodes in a fixed order: edge ends, joints, body centres (each centre on its body).
fn all_nodes(s: &Sketch) -> Vec<Node> {
    let mut n: Vec<Node> = s.edges.iter().flat_map(|e| [e.a, e.b]).collect();
    n.extend(s.joints.iter().copied());
    n.extend(s.bodies.iter().enumerate().map(|(b, body)| Node {
        at: body.centre,
        body: Some(b),
    }));
    n
}

/// Maps model coordinates of one view into the panel: uniform scale, centred.
struct Frame {
    view: View,
    scale: f64,
    offset: (f64, f64),
    panel: (f64, f64),
}

impl Frame {
    fn fit(view: View, pts: &[[f64; 3]], (pw, ph): (f64, f64)) -> Frame {
        let (mut hl, mut hh, mut vl, mut vh) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in pts {
            let (h, v) = (p[view.h], p[view.v] * if view.down { -1.0 } else { 1.0 });
            (hl, hh, vl, vh) = (hl.min(h), hh.max(h), vl.min(v), vh.max(v));
        }
        let margin = 40.0;
        let span = (hh - hl).max(vh - vl).max(1e-12);
        let scale = ((pw - 2.0 * margin) / (hh - hl).max(span * 0.05))
            .min((ph - 2.0 * margin - 30.0) / (vh - vl).max(span * 0.05));
        let offset = (
            pw / 2.0 - scale * (hl + hh) / 2.0,
            30.0 + (ph - 30.0) / 2.0 + scale * (vl + vh) / 2.0,
        );
        Frame {
            view,
            scale,
            offset,
            panel: (pw, ph),
        }
    }

    fn map(&self, p: [f64; 3]) -> (f64, f64) {
        let v = p[self.view.v] * if self.view.down { -1.0 } else { 1.0 };
        (
            self.offset.0 + self.scale * p[self.view.h],
            self.offset.1 - self.scale * v,
        )
    }
}

/// The position of node `k` at phase `phi` of the cycle.
fn moved(node: &Node, d: &Vector3<Complex64>, phi: f64) -> [f64; 3] {
    let e = Complex64::from_polar(1.0, phi);
    [
        node.at[0] + (d[0] * e).re,
        node.at[1] + (d[1] * e).re,
        node.at[2] + (d[2] * e).re,
    ]
}

#[allow(clippy::too_many_arguments)]
fn view_svg(
    out: &mut String,
    s: &Sketch,
    nodes: &[Node],
    disp: &[Vector3<Complex64>],
    view: View,
    panel: (f64, f64),
    motions: Option<&[[Vector3<Complex64>; 2]]>,
) {
    let animated = motions.is_some();
    let mut pts: Vec<[f64; 3]> = Vec::new();
    for (n, d) in nodes.iter().zip(disp) {
        pts.extend([moved(n, d, 0.0), moved(n, d, TAU / 2.0), n.at]);
    }
    pts.extend(s.grounds.iter().copied());
    let f = Frame::fit(view, &pts, panel);
    let vdir = if view.down { "↓" } else { "↑" };
    let _ = write!(
        out,
        r##"<rect x="2" y="2" width="{}" height="{}" fill="#fbfbfb" stroke="#ccc"/><text x="12" y="22" font-size="14">{} ({} →, {} {vdir})</text>"##,
        panel.0 - 4.0,
        panel.1 - 4.0,
        view.name,
        AXES[view.h],
        AXES[view.v]
    );
    for g in &s.grounds {
        let (x, y) = f.map(*g);
        let _ = write!(
            out,
            r##"<path d="M{x:.1},{y:.1} l-7,11 h14 z" fill="#999" stroke="none"/>"##
        );
    }
    let edges = s.edges.len();
    // Nominal geometry, then the two extremes, then the animated copy.
    let layers: Vec<(Option<f64>, &str)> = if animated {
        vec![
            (None, r##"stroke="#bbb" stroke-width="2""##),
            (Some(0.0), r##"stroke="MODE" stroke-width="2.5""##),
            (
                Some(TAU / 2.0),
                r##"stroke="MODE" stroke-width="2" stroke-dasharray="6 4" opacity="0.7""##,
            ),
        ]
    } else {
        vec![(None, r##"stroke="#333" stroke-width="2.5""##)]
    };
    for (phase, style) in &layers {
        let style = style.replace("MODE", MODE_COLOUR);
        for k in 0..edges {
            let (a, b) = position_pair(nodes, disp, k, *phase);
            let width = match s.edges[k].kind {
                EdgeKind::Body => "",
                EdgeKind::Item => r#" stroke-opacity="0.6""#,
            };
            let (p, q) = (f.map(a), f.map(b));
            let _ = write!(
                out,
                r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" {style}{width}/>"#,
                p.0, p.1, q.0, q.1
            );
        }
    }
    if let Some(m) = motions {
        animated_edges(out, nodes, disp, &f, edges);
        centres_of_rotation(out, s, m, &f);
    }
    // The view's caption is taken; body names go where they fit inside the panel.
    let caption = format!(
        "{} ({} →, {} {vdir})",
        view.name, AXES[view.h], AXES[view.v]
    );
    let mut placer = Placer::new([2.0, 2.0, panel.0 - 2.0, panel.1 - 2.0]);
    placer.take([12.0, 8.0, 12.0 + text_width(&caption, 14.0), 26.0]);
    body_dots(out, s, nodes, disp, &f, animated, &mut placer);
}

/// The positions of the two ends of edge `k` (nominal when `phase` is `None`).
fn position_pair(
    nodes: &[Node],
    disp: &[Vector3<Complex64>],
    k: usize,
    phase: Option<f64>,
) -> ([f64; 3], [f64; 3]) {
    let at = |i: usize| match phase {
        None => nodes[i].at,
        Some(phi) => moved(&nodes[i], &disp[i], phi),
    };
    (at(2 * k), at(2 * k + 1))
}

/// `values` of an SMIL animation of one coordinate over a cycle.
fn frames(mut coordinate: impl FnMut(f64) -> f64) -> String {
    (0..=FRAMES)
        .map(|i| format!("{:.1}", coordinate(TAU * i as f64 / FRAMES as f64)))
        .collect::<Vec<_>>()
        .join(";")
}

fn animate(attr: &str, values: &str) -> String {
    format!(
        r#"<animate attributeName="{attr}" dur="{CYCLE_S}s" repeatCount="indefinite" values="{values}"/>"#
    )
}

fn animated_edges(
    out: &mut String,
    nodes: &[Node],
    disp: &[Vector3<Complex64>],
    f: &Frame,
    edges: usize,
) {
    out.push_str(r#"<g class="animated">"#);
    for k in 0..edges {
        let (a, b) = (2 * k, 2 * k + 1);
        let coord = |i: usize, which: usize| {
            frames(|phi| {
                let p = f.map(moved(&nodes[i], &disp[i], phi));
                if which == 0 { p.0 } else { p.1 }
            })
        };
        let (p, q) = (f.map(nodes[a].at), f.map(nodes[b].at));
        let _ = write!(
            out,
            r##"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#d0401a" stroke-width="3">{}{}{}{}</line>"##,
            p.0,
            p.1,
            q.0,
            q.1,
            animate("x1", &coord(a, 0)),
            animate("y1", &coord(a, 1)),
            animate("x2", &coord(b, 0)),
            animate("y2", &coord(b, 1)),
        );
    }
    out.push_str("</g>");
}

/// The mass centres (labelled) and joints, animated in a drawing of a mode.
fn body_dots(
    out: &mut String,
    s: &Sketch,
    nodes: &[Node],
    disp: &[Vector3<Complex64>],
    f: &Frame,
    animated: bool,
    placer: &mut Placer,
) {
    let first_centre = nodes.len() - s.bodies.len();
    for (i, (n, d)) in nodes.iter().zip(disp).enumerate() {
        if i < 2 * s.edges.len() {
            continue;
        }
        let is_body = i >= first_centre;
        let (x, y) = f.map(n.at);
        let (r, fill) = if is_body { (5, "#222") } else { (3, "white") };
        let anim = if animated {
            animate("cx", &frames(|phi| f.map(moved(n, d, phi)).0))
                + &animate("cy", &frames(|phi| f.map(moved(n, d, phi)).1))
        } else {
            String::new()
        };
        let _ = write!(
            out,
            r##"<circle cx="{x:.1}" cy="{y:.1}" r="{r}" fill="{fill}" stroke="#222">{anim}</circle>"##
        );
        if is_body {
            // Beside the dot where it overlaps no other name and stays in the panel; a name
            // with no such place is left out (the names are in the model's tables).
            let name = &s.bodies[i - first_centre].name;
            if let Some((left, top)) = placer.place(name, LABEL_PX, (x, y), 6.0) {
                let _ = write!(
                    out,
                    r##"<text x="{left:.1}" y="{:.1}" font-size="{LABEL_PX}" fill="#444">{}</text>"##,
                    top + 0.95 * LABEL_PX,
                    escape(name)
                );
            }
        }
    }
}

/// The centre of rotation of each body in the view's plane: where the in-plane displacement
/// `t + θ × r` of the body's points vanishes, `r_h = −σ t_v/θ_n`, `r_v = σ t_h/θ_n` (σ = +1
/// when (h, v, n) is a cyclic order of the axes, −1 otherwise); the real part is drawn (the
/// centre at the extremes of the motion). Bodies that do not rotate in the plane, or whose
/// centre lies farther than three model sizes away (nearly a translation), get none.
fn centres_of_rotation(
    out: &mut String,
    s: &Sketch,
    motions: &[[Vector3<Complex64>; 2]],
    f: &Frame,
) {
    let (h, v) = (f.view.h, f.view.v);
    let n = 3 - h - v;
    let sigma = if (h + 1) % 3 == v { 1.0 } else { -1.0 };
    let big = motions
        .iter()
        .map(|[t, th]| t.norm().max(th.norm() * s.size()))
        .fold(0.0f64, f64::max);
    for (body, [t, th]) in s.bodies.iter().zip(motions) {
        let w = th[n];
        if big == 0.0 || w.norm() * s.size() <= 1e-3 * big {
            continue;
        }
        let rh = -t[v] / w * sigma;
        let rv = t[h] / w * sigma;
        if rh.norm().hypot(rv.norm()) > 3.0 * s.size() {
            continue;
        }
        let mut p = body.centre;
        p[h] += rh.re;
        p[v] += rv.re;
        let (x, y) = f.map(p);
        // Outside the panel (a centre far off the drawing, in this view's scale): not drawn.
        if !(6.0..=f.panel.0 - 6.0).contains(&x) || !(30.0..=f.panel.1 - 6.0).contains(&y) {
            continue;
        }
        let _ = write!(
            out,
            r##"<g class="centre" stroke="#c00" stroke-width="1.5" fill="none"><circle cx="{x:.1}" cy="{y:.1}" r="6"/><path d="M{:.1},{y:.1} h12 M{x:.1},{:.1} v12"/></g>"##,
            x - 6.0,
            y - 6.0
        );
    }
}

/// Escapes text for SVG/HTML.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
