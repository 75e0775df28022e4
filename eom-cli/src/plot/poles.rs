//! The pole map (`eom analyze … --plot-poles FILE.svg`): the eigenvalues in the complex
//! plane with the stable half-plane shaded; the modes the inputs and outputs see (the poles
//! of the minimal realization) are told apart from the hidden ones (uncontrollable,
//! unobservable), and the transmission zeros are drawn as rings.

use super::{
    Chart, Mark, Plot, STABLE_FILL, axis_range, bounds, draw_legend, draw_mesh, drawing, plottable,
    render, union, with_title,
};
use crate::analyze::Analysis;
use crate::error::CliError;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// Size of the pole map in pixels.
const SIZE: (u32, u32) = (1000, 720);

/// Colour of the poles seen from the inputs and outputs.
const SEEN: RGBColor = RGBColor(31, 100, 180);
/// Colour of uncontrollable (hidden) modes.
const UNCONTROLLABLE: RGBColor = RGBColor(230, 110, 0);
/// Colour of unobservable (hidden) modes.
const UNOBSERVABLE: RGBColor = RGBColor(130, 60, 170);
/// Colour of modes that could not be classified.
const UNCLASSIFIED: RGBColor = RGBColor(90, 90, 90);
/// Colour of transmission zeros.
const ZERO: RGBColor = RGBColor(30, 130, 50);

/// The points of the map, `(Re, Im)` in 1/s, by kind.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PoleSets {
    /// Poles of the minimal realization: the modes the inputs and outputs see.
    pub seen: Vec<(f64, f64)>,
    /// Modes the inputs cannot excite.
    pub uncontrollable: Vec<(f64, f64)>,
    /// Modes the outputs cannot see.
    pub unobservable: Vec<(f64, f64)>,
    /// Every mode, when the minimal realization could not be computed.
    pub unclassified: Vec<(f64, f64)>,
    /// Transmission zeros.
    pub zeros: Vec<(f64, f64)>,
}

impl PoleSets {
    /// The sets of an analysis. Without a minimal realization every mode is unclassified.
    pub fn of(a: &Analysis) -> PoleSets {
        let pts = |v: &[crate::format::ReIm]| v.iter().map(|z| (z.re, z.im)).collect();
        let removed = |reason: &str| -> Vec<(f64, f64)> {
            a.minimal
                .iter()
                .flat_map(|m| &m.removed)
                .filter(|r| r.reason == reason)
                .map(|r| (r.eigenvalue.re, r.eigenvalue.im))
                .collect()
        };
        PoleSets {
            seen: a
                .minimal
                .as_ref()
                .map_or_else(Vec::new, |m| pts(&m.eigenvalues)),
            uncontrollable: removed("uncontrollable"),
            unobservable: removed("unobservable"),
            unclassified: if a.minimal.is_none() {
                pts(&a.eigenvalues)
            } else {
                Vec::new()
            },
            zeros: a.zeros.as_deref().map_or_else(Vec::new, pts),
        }
    }

    /// Every point, of every kind.
    fn all(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.seen
            .iter()
            .chain(&self.uncontrollable)
            .chain(&self.unobservable)
            .chain(&self.unclassified)
            .chain(&self.zeros)
            .copied()
    }
}

/// The axis ranges: the real axis always includes 0 (the stability border), the imaginary
/// axis is symmetric (eigenvalues of a real matrix come in conjugate pairs). Neither axis is
/// narrower than a tenth of the largest coordinate on each side: rounding-level imaginary
/// parts (1e-10 next to poles at ±4) would otherwise fill the whole height and look like
/// oscillations.
fn ranges(sets: &PoleSets) -> ((f64, f64), (f64, f64)) {
    let drawn: Vec<(f64, f64)> = sets
        .all()
        .filter(|(re, im)| plottable(*re) && plottable(*im))
        .collect();
    let scale = drawn
        .iter()
        .fold(0.0_f64, |m, p| m.max(p.0.abs()).max(p.1.abs()));
    let (lo, hi) = union(bounds(drawn.iter().map(|p| p.0)), Some((0.0, 0.0))).unwrap_or((0.0, 0.0));
    let (lo, hi) = (lo.min(-0.1 * scale), hi.max(0.1 * scale));
    let m = drawn.iter().fold(0.1 * scale, |m, p| m.max(p.1.abs()));
    (
        axis_range(Some((lo, hi)), 0.08),
        axis_range(Some((-m, m)), 0.08),
    )
}

/// The legend rows: one per kind present, with counts, then the notes.
fn legend_rows(sets: &PoleSets, notes: &[String]) -> Vec<(Mark, String)> {
    let kinds = [
        (
            Mark::Cross(SEEN),
            "pole seen from the inputs/outputs",
            &sets.seen,
        ),
        (
            Mark::Triangle(UNCONTROLLABLE),
            "hidden: uncontrollable (the inputs cannot excite it)",
            &sets.uncontrollable,
        ),
        (
            Mark::Square(UNOBSERVABLE),
            "hidden: unobservable (the outputs cannot see it)",
            &sets.unobservable,
        ),
        (
            Mark::Cross(UNCLASSIFIED),
            "mode (not classified)",
            &sets.unclassified,
        ),
        (Mark::Ring(ZERO), "transmission zero", &sets.zeros),
    ];
    let mut rows: Vec<(Mark, String)> = kinds
        .into_iter()
        .filter(|(_, _, v)| !v.is_empty())
        .map(|(m, what, v)| (m, format!("{what} ({})", v.len())))
        .collect();
    rows.push((
        Mark::Swatch(STABLE_FILL),
        "stable half-plane Re λ < 0".into(),
    ));
    rows.extend(notes.iter().map(|n| (Mark::Note, n.clone())));
    rows
}

/// Notes: points left out, no points at all, modes not classified.
fn notes(sets: &PoleSets) -> Vec<String> {
    let mut notes = Vec::new();
    let left_out = super::left_out(sets.all());
    if left_out > 0 {
        notes.push(format!(
            "{left_out} pole(s)/zero(s) are NaN or infinite and are not drawn"
        ));
    }
    if sets.all().next().is_none() {
        notes.push("no poles or zeros to draw (a model without states)".into());
    }
    if !sets.unclassified.is_empty() {
        notes.push(
            "the minimal realization was not computed: seen and hidden modes are not told \
             apart"
                .into(),
        );
    }
    notes
}

/// The chart type of the pole map.
type Plane<'a, 'b> = Chart<'a, 'b, RangedCoordf64, RangedCoordf64>;

/// Whether both coordinates of a point can be drawn.
fn drawable(p: &&(f64, f64)) -> bool {
    plottable(p.0) && plottable(p.1)
}

/// The stable half-plane (shaded first, under the grid), the grid, and the axes through the
/// origin — the imaginary axis is the stability border.
fn draw_plane(chart: &mut Plane<'_, '_>, x: (f64, f64), y: (f64, f64)) -> Result<(), CliError> {
    if x.0 < 0.0 {
        let stable = Rectangle::new([(x.0, y.0), (x.1.min(0.0), y.1)], STABLE_FILL.filled());
        chart
            .draw_series(std::iter::once(stable))
            .map_err(drawing)?;
    }
    draw_mesh(chart, "Re λ [1/s]", "Im λ [1/s]")?;
    let axes = [vec![(0.0, y.0), (0.0, y.1)], vec![(x.0, 0.0), (x.1, 0.0)]];
    let grey = RGBColor(120, 120, 120).stroke_width(1);
    chart
        .draw_series(axes.map(|a| PathElement::new(a, grey)))
        .map_err(drawing)?;
    Ok(())
}

/// The markers: zeros first and poles last, so that a pole on top of a zero stays visible.
fn draw_points(chart: &mut Plane<'_, '_>, sets: &PoleSets) -> Result<(), CliError> {
    let zeros = sets.zeros.iter().filter(drawable);
    chart
        .draw_series(zeros.map(|&p| Circle::new(p, 6, ZERO.stroke_width(2))))
        .map_err(drawing)?;
    // An open square of a fixed size in pixels, wherever the point is.
    let square =
        |&p| EmptyElement::at(p) + Rectangle::new([(-5, -5), (5, 5)], UNOBSERVABLE.stroke_width(2));
    chart
        .draw_series(sets.unobservable.iter().filter(drawable).map(square))
        .map_err(drawing)?;
    let triangles = sets.uncontrollable.iter().filter(drawable);
    chart
        .draw_series(triangles.map(|&p| TriangleMarker::new(p, 7, UNCONTROLLABLE.filled())))
        .map_err(drawing)?;
    for (v, c) in [(&sets.seen, SEEN), (&sets.unclassified, UNCLASSIFIED)] {
        let crosses = v.iter().filter(drawable);
        chart
            .draw_series(crosses.map(|&p| Cross::new(p, 5, c.stroke_width(2))))
            .map_err(drawing)?;
    }
    Ok(())
}

/// Draws the pole map. Points that cannot be drawn are left out with a note.
pub fn pole_map(title: &str, sets: &PoleSets) -> Result<Plot, CliError> {
    let (x, y) = ranges(sets);
    let notes = notes(sets);
    let rows = legend_rows(sets, &notes);
    let svg = render(SIZE, |root| {
        let (area, legend) = with_title(root, title)?;
        let mut chart = ChartBuilder::on(&area)
            .margin(10)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(x.0..x.1, y.0..y.1)
            .map_err(drawing)?;
        draw_plane(&mut chart, x, y)?;
        draw_points(&mut chart, sets)?;
        draw_legend(&legend, &rows)
    })?;
    Ok(Plot { svg, notes })
}

/// The pole map of an analysis.
pub fn pole_map_of(a: &Analysis) -> Result<Plot, CliError> {
    let title = format!("{}: poles and zeros ({})", a.model, a.stability);
    pole_map(&title, &PoleSets::of(a))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_get_their_own_markers_and_bad_points_a_note() {
        let sets = PoleSets {
            seen: vec![(-1.0, 2.0), (-1.0, -2.0)],
            uncontrollable: vec![(0.5, 0.0)],
            unobservable: vec![(f64::NAN, 0.0)],
            unclassified: Vec::new(),
            zeros: vec![(-3.0, 0.0)],
        };
        let p = pole_map("t", &sets).unwrap();
        assert!(p.svg.starts_with("<svg"));
        assert_eq!(p.notes.len(), 1, "{:?}", p.notes);
        assert!(p.notes[0].starts_with("1 pole(s)/zero(s)"), "{:?}", p.notes);
        // One triangle in the map, one in the legend.
        assert_eq!(p.svg.matches("<polygon").count(), 2);
        // Two crosses of two lines each, and the legend's (grid lines are grey).
        let cross = format!(
            "<line opacity=\"1\" stroke=\"#{:02X}{:02X}{:02X}\"",
            SEEN.0, SEEN.1, SEEN.2
        );
        assert_eq!(p.svg.matches(&cross).count(), 6, "{cross}");
        assert!(p.svg.contains("hidden: uncontrollable"));
        assert!(p.svg.contains("transmission zero (1)"));
    }

    #[test]
    fn no_points_and_a_single_point_do_not_panic() {
        let p = pole_map("t", &PoleSets::default()).unwrap();
        assert!(p.notes[0].contains("no poles or zeros"), "{:?}", p.notes);
        let sets = PoleSets {
            unclassified: vec![(0.0, 0.0)],
            ..PoleSets::default()
        };
        let p = pole_map("t", &sets).unwrap();
        assert!(p.notes[0].contains("not classified") || p.notes[0].contains("not computed"));
        assert!(p.svg.contains("mode (not classified) (1)"));
    }
}
