//! Lattice spacing: how panel edges, bound vortices and control points are placed along the
//! chord and along the span.
//!
//! The spacing parameter follows the AVL input convention (−3 … 3): 0 and ±3 are equal
//! spacing, ±1 cosine, +2 sine (dense at the start), −2 "minus sine" (dense at the end);
//! values in between blend the two neighbouring distributions linearly.

use serde::Serialize;
use std::f64::consts::PI;

/// A number of lattice intervals and the AVL spacing parameter that distributes them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Spacing {
    /// Number of intervals (panels chordwise, strips spanwise); at least 1.
    pub count: usize,
    /// AVL spacing parameter in −3 … 3 (1 = cosine, the usual choice).
    pub parameter: f64,
}

impl Spacing {
    /// `count` intervals with spacing `parameter`.
    pub fn new(count: usize, parameter: f64) -> Self {
        Spacing { count, parameter }
    }

    /// `count` intervals with cosine spacing (parameter 1).
    pub fn cosine(count: usize) -> Self {
        Spacing::new(count, 1.0)
    }

    /// Whether the values are usable: a positive count and a finite parameter in −3 … 3.
    pub(crate) fn problem(&self) -> Option<String> {
        if self.count == 0 {
            Some("count must be at least 1".into())
        } else if !self.parameter.is_finite() || self.parameter.abs() > 3.0 {
            Some(format!(
                "spacing parameter {} must be a number in -3 ... 3",
                self.parameter
            ))
        } else {
            None
        }
    }
}

/// Weights of the equal, cosine and sine distributions for a spacing parameter.
struct Blend {
    equal: f64,
    cosine: f64,
    sine: f64,
    /// The sine distribution is dense at the end (parameter < 0) instead of the start.
    reversed: bool,
}

fn blend(parameter: f64) -> Blend {
    let p = parameter.abs();
    let (equal, cosine, sine) = if p <= 1.0 {
        (1.0 - p, p, 0.0)
    } else if p <= 2.0 {
        (0.0, 2.0 - p, p - 1.0)
    } else {
        (p - 2.0, 0.0, 3.0 - p)
    };
    Blend {
        equal,
        cosine,
        sine,
        reversed: parameter < 0.0,
    }
}

fn cosine_map(t: f64) -> f64 {
    0.5 * (1.0 - (PI * t).cos())
}

fn sine_map(t: f64, reversed: bool) -> f64 {
    if reversed {
        (0.5 * PI * t).sin()
    } else {
        1.0 - (0.5 * PI * t).cos()
    }
}

/// The blended image of a uniform parameter `t` in 0 … 1.
fn warp(b: &Blend, t: f64) -> f64 {
    b.equal * t + b.cosine * cosine_map(t) + b.sine * sine_map(t, b.reversed)
}

/// Spanwise stations of one run of strips: `count + 1` node fractions (0 … 1) and `count`
/// control-point fractions. The control point of a strip is the image of the strip's
/// middle parameter, not the arithmetic middle of its nodes: with cosine spacing this is the
/// cosine of the mid-angle, which keeps the lattice convergent from the first refinements
/// (the midpoint of the nodes converges only as 1/N).
pub(crate) fn span_stations(s: Spacing) -> (Vec<f64>, Vec<f64>) {
    let b = blend(s.parameter);
    let n = s.count as f64;
    let nodes = (0..=s.count).map(|i| warp(&b, i as f64 / n)).collect();
    let cps = (0..s.count)
        .map(|i| warp(&b, (i as f64 + 0.5) / n))
        .collect();
    (nodes, cps)
}

/// Chordwise stations of a strip, as fractions of the local chord from the leading edge.
#[derive(Debug, Clone)]
pub(crate) struct ChordStations {
    /// Bound-vortex fraction of each panel.
    pub vortex: Vec<f64>,
    /// Control-point fraction of each panel.
    pub control: Vec<f64>,
}

/// Chordwise vortex and control-point stations.
///
/// * Equal spacing: the classic ¼–¾ rule (vortex at the panel quarter chord, control point
///   at three quarters), exact for a 2-D flat plate.
/// * Cosine spacing: Lan's quasi-vortex-lattice stations, vortex at
///   ½(1 − cos((2j − 1)π/2N)) and control point at ½(1 − cos(jπ/N)), j = 1 … N, which give
///   the exact 2-D flat-plate lift and moment for every N and converge fastest in 3-D.
/// * Sine spacing: the ¼–¾ rule applied in the sine-stretched parameter.
///
/// Intermediate parameters blend the stations with the weights of the spacing blend. A
/// single panel has nothing to distribute: it is the ¼–¾ (Weissinger) panel whatever the
/// parameter, so that the load of a one-panel lattice acts at the quarter chord.
pub(crate) fn chord_stations(s: Spacing) -> ChordStations {
    let b = blend(if s.count == 1 { 0.0 } else { s.parameter });
    let n = s.count as f64;
    let mut vortex = Vec::with_capacity(s.count);
    let mut control = Vec::with_capacity(s.count);
    for j in 0..s.count {
        let j = j as f64;
        let (tv, tc) = ((j + 0.25) / n, (j + 0.75) / n);
        let lan_v = 0.5 * (1.0 - ((2.0 * j + 1.0) * PI / (2.0 * n)).cos());
        let lan_c = 0.5 * (1.0 - ((j + 1.0) * PI / n).cos());
        vortex.push(b.equal * tv + b.cosine * lan_v + b.sine * sine_map(tv, b.reversed));
        control.push(b.equal * tc + b.cosine * lan_c + b.sine * sine_map(tc, b.reversed));
    }
    ChordStations { vortex, control }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cosine_span_nodes_cluster_at_both_ends() {
        let (nodes, cps) = span_stations(Spacing::cosine(4));
        assert_eq!(nodes.len(), 5);
        assert!((nodes[0]).abs() < 1e-15 && (nodes[4] - 1.0).abs() < 1e-15);
        assert!((nodes[2] - 0.5).abs() < 1e-15);
        // control point of the first strip at the cosine image of the mid-angle π/8
        assert!((cps[0] - 0.5 * (1.0 - (PI / 8.0).cos())).abs() < 1e-15);
    }

    #[test]
    fn equal_chord_stations_are_quarter_three_quarter() {
        let c = chord_stations(Spacing::new(2, 0.0));
        assert_eq!(c.vortex, vec![0.125, 0.625]);
        assert_eq!(c.control, vec![0.375, 0.875]);
    }

    #[test]
    fn three_is_equal_and_minus_two_is_dense_at_the_end() {
        let (a, _) = span_stations(Spacing::new(4, 3.0));
        let (b, _) = span_stations(Spacing::new(4, 0.0));
        assert_eq!(a, b);
        let (m, _) = span_stations(Spacing::new(4, -2.0));
        assert!(m[4] - m[3] < m[1] - m[0]);
    }
}
