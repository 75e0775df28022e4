//! From surfaces to horseshoe vortices: panel corners, bound segments, control points,
//! force points and normals.

use crate::error::{AeroError, Result};
use crate::geometry::{Configuration, Surface};
use crate::kernel::{Vec3, add, cross, norm, scale, sub};
use crate::spacing::{Spacing, chord_stations, span_stations};

/// One horseshoe vortex of the lattice (geometry axes: x aft, y right, z up).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Panel {
    /// Start of the bound segment (its trailing leg comes in from x = +∞).
    pub a: Vec3,
    /// End of the bound segment (its trailing leg goes out to x = +∞).
    pub b: Vec3,
    /// Control point, where flow tangency is imposed.
    pub control: Vec3,
    /// Point of the bound segment at the control point's spanwise station, where the
    /// Kutta–Joukowski force acts.
    pub force_point: Vec3,
    /// Unit normal of flow tangency, tilted by the local incidence.
    pub normal: Vec3,
    /// x of the trailing edge behind `a` and behind `b` (end of the legs' on-surface part).
    pub te_a: f64,
    /// See `te_a`.
    pub te_b: f64,
    /// The panel's loads count (not `NOLOAD`).
    pub loaded: bool,
    /// The panel sees α, β and the rates (not `NOALBE`).
    pub sees_flow_angles: bool,
}

/// The whole lattice.
#[derive(Debug, Clone)]
pub(crate) struct Lattice {
    pub panels: Vec<Panel>,
    /// Surfaces including mirrored copies.
    pub surfaces: usize,
    /// Strips including mirrored copies.
    pub strips: usize,
}

/// A strip between two spanwise stations of one section interval: the local fractions
/// t₀, t₁ of its edges and t_c of its control points.
struct Strip {
    interval: usize,
    t0: f64,
    t1: f64,
    tc: f64,
}

/// Section data after SCALE, TRANSLATE and ANGLE.
struct Placed {
    le: Vec3,
    chord: f64,
    incidence: f64,
}

fn place(s: &Surface) -> Vec<Placed> {
    s.sections
        .iter()
        .map(|sec| Placed {
            le: std::array::from_fn(|i| sec.leading_edge[i] * s.scale[i] + s.translate[i]),
            chord: sec.chord * s.scale[0],
            incidence: (sec.incidence_deg + s.angle_deg).to_radians(),
        })
        .collect()
}

pub(crate) fn build(config: &Configuration) -> Result<Lattice> {
    let mut lattice = Lattice {
        panels: Vec::new(),
        surfaces: 0,
        strips: 0,
    };
    for surface in &config.surfaces {
        let placed = place(surface);
        let strips = strips(surface, &placed)?;
        let copies = if surface.y_duplicate.is_some() { 2 } else { 1 };
        let adding = strips
            .len()
            .saturating_mul(surface.chordwise.count)
            .saturating_mul(copies);
        let total = lattice.panels.len().saturating_add(adding);
        if total > crate::MAX_PANELS {
            return Err(AeroError::OutOfRange {
                what: format!("the lattice of `{}`", eom_text::shown(&config.title)),
                reason: format!(
                    "surface `{}` brings it to {total} panels, more than the limit of {} \
                     (fewer chordwise or spanwise vortices: Nchord, Nspan)",
                    eom_text::shown(&surface.name),
                    crate::MAX_PANELS
                ),
            });
        }
        let first = lattice.panels.len();
        for strip in &strips {
            add_strip(&mut lattice.panels, surface, &placed, strip);
        }
        lattice.surfaces += 1;
        lattice.strips += strips.len();
        if let Some(y0) = surface.y_duplicate {
            let mirrored: Vec<Panel> = lattice.panels[first..]
                .iter()
                .map(|p| mirror(p, y0))
                .collect();
            lattice.panels.extend(mirrored);
            lattice.surfaces += 1;
            lattice.strips += strips.len();
        }
    }
    Ok(lattice)
}

/// Cumulative y–z length of the leading-edge polyline at each section.
fn span_positions(placed: &[Placed]) -> Vec<f64> {
    let mut s = vec![0.0];
    for w in placed.windows(2) {
        let d = (w[1].le[1] - w[0].le[1]).hypot(w[1].le[2] - w[0].le[2]);
        s.push(s.last().unwrap() + d);
    }
    s
}

fn strips(surface: &Surface, placed: &[Placed]) -> Result<Vec<Strip>> {
    let intervals = placed.len() - 1;
    let mut out = Vec::new();
    match surface.spanwise {
        None => {
            for (k, sec) in surface.sections[..intervals].iter().enumerate() {
                if out.len() > crate::MAX_PANELS {
                    break; // already beyond the limit: `build` refuses the surface
                }
                // validated: every section but the last has its own spacing here
                let sp = sec.spanwise.unwrap_or(Spacing::cosine(1));
                let (nodes, cps) = span_stations(sp);
                for i in 0..sp.count {
                    out.push(Strip {
                        interval: k,
                        t0: nodes[i],
                        t1: nodes[i + 1],
                        tc: cps[i],
                    });
                }
            }
        }
        Some(sp) => surface_strips(surface, placed, sp, &mut out)?,
    }
    Ok(out)
}

/// Strips distributed over the whole surface: the nodes nearest the interior sections are
/// moved onto them, so that every strip lies within one section interval, and the stations
/// in between are stretched linearly.
fn surface_strips(
    surface: &Surface,
    placed: &[Placed],
    sp: Spacing,
    out: &mut Vec<Strip>,
) -> Result<()> {
    let intervals = placed.len() - 1;
    if sp.count < intervals {
        return Err(AeroError::Geometry {
            surface: surface.name.clone(),
            section: None,
            field: "Nspan",
            reason: format!(
                "{} strips cannot cover {} section intervals",
                sp.count, intervals
            ),
        });
    }
    let pos = span_positions(placed);
    let total = *pos.last().unwrap();
    let (nodes, cps) = span_stations(sp);
    let mut snapped = vec![0usize; placed.len()];
    snapped[intervals] = sp.count;
    for k in 1..intervals {
        let target = pos[k] / total;
        let nearest = (0..=sp.count)
            .min_by(|&i, &j| {
                (nodes[i] - target)
                    .abs()
                    .total_cmp(&(nodes[j] - target).abs())
            })
            .unwrap_or(0);
        snapped[k] = nearest.clamp(snapped[k - 1] + 1, sp.count - (intervals - k));
    }
    for k in 0..intervals {
        let (i0, i1) = (snapped[k], snapped[k + 1]);
        let (n0, n1) = (nodes[i0], nodes[i1]);
        let local = |x: f64| (x - n0) / (n1 - n0);
        for i in i0..i1 {
            out.push(Strip {
                interval: k,
                t0: local(nodes[i]),
                t1: local(nodes[i + 1]),
                tc: local(cps[i]),
            });
        }
    }
    Ok(())
}

fn add_strip(panels: &mut Vec<Panel>, surface: &Surface, placed: &[Placed], strip: &Strip) {
    let (s0, s1) = (&placed[strip.interval], &placed[strip.interval + 1]);
    let le = |t: f64| add(s0.le, scale(sub(s1.le, s0.le), t));
    let chord = |t: f64| s0.chord + (s1.chord - s0.chord) * t;
    let (l0, l1, lc) = (le(strip.t0), le(strip.t1), le(strip.tc));
    let (c0, c1, cc) = (chord(strip.t0), chord(strip.t1), chord(strip.tc));
    // The section chord lines are tilted nose up by their incidence about the strip's
    // spanwise direction in the y-z plane, and interpolated linearly between sections
    // (leading and trailing edges alike, so the incidence is chord-weighted). The normal of
    // flow tangency of a panel is perpendicular to that chord line and to the panel's bound
    // vortex: on a swept panel with incidence it gains a spanwise component (sideslip then
    // changes the flow through the panel), and on a tapered strip each chordwise row has
    // its own sweep.
    let x_hat = [1.0, 0.0, 0.0];
    let span = sub(l1, l0);
    let span_yz = [0.0, span[1], span[2]];
    let nose_down = cross(scale(span_yz, 1.0 / norm(span_yz)), x_hat);
    let tilted = |a: f64| add(scale(x_hat, a.cos()), scale(nose_down, a.sin()));
    let t = strip.tc;
    let chord_line = add(
        scale(tilted(s0.incidence), (1.0 - t) * s0.chord),
        scale(tilted(s1.incidence), t * s1.chord),
    );
    let along = |p: Vec3, c: f64, f: f64| [p[0] + c * f, p[1], p[2]];
    let stations = chord_stations(surface.chordwise);
    for (&xv, &xc) in stations.vortex.iter().zip(&stations.control) {
        let (a, b) = (along(l0, c0, xv), along(l1, c1, xv));
        let n = cross(chord_line, sub(b, a));
        panels.push(Panel {
            a,
            b,
            control: along(lc, cc, xc),
            force_point: along(lc, cc, xv),
            normal: scale(n, 1.0 / norm(n)),
            te_a: l0[0] + c0,
            te_b: l1[0] + c1,
            loaded: !surface.no_load,
            sees_flow_angles: !surface.no_alpha_beta,
        });
    }
}

/// The mirror image about y = y0: points and normal reflected, and the bound segment
/// reversed so that a symmetric flow gives equal circulations on both halves.
fn mirror(p: &Panel, y0: f64) -> Panel {
    let m = |v: Vec3| [v[0], 2.0 * y0 - v[1], v[2]];
    Panel {
        a: m(p.b),
        b: m(p.a),
        control: m(p.control),
        force_point: m(p.force_point),
        normal: [p.normal[0], -p.normal[1], p.normal[2]],
        te_a: p.te_b,
        te_b: p.te_a,
        ..*p
    }
}
