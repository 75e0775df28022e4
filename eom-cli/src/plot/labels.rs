//! Text that stays inside its picture and out of the way of other text: a width estimate
//! from the font size and the characters (the SVG is drawn without a font at hand), titles
//! shrunk to fit their width, and labels placed beside their points where they overlap no
//! label placed before them.

/// Estimated width of `text` in pixels at a font size of `px` pixels (sans-serif): narrow
/// characters 0.35 em, capitals and wide ones 0.8 em, others 0.62 em — at or above the
/// advance widths of the common sans-serif fonts (DejaVu Sans, Liberation Sans, Helvetica),
/// so that a box of this width holds the drawn text.
pub fn text_width(text: &str, px: f64) -> f64 {
    text.chars()
        .map(|c| {
            if "iljtfr.,:;|!'()[] ".contains(c) {
                0.35
            } else if c.is_uppercase() || "mwMW@%—…".contains(c) {
                0.8
            } else {
                0.62
            }
        })
        .sum::<f64>()
        * px
}

/// The font size (pixels, at most `px`, at least `min`) at which `text` fits in `width`
/// pixels by [`text_width`].
pub fn fitting_size(text: &str, px: f64, min: f64, width: f64) -> f64 {
    let w = text_width(text, px);
    if w <= width || w == 0.0 {
        px
    } else {
        (px * width / w).max(min)
    }
}

/// A box in pixels: `[left, top, right, bottom]`.
pub type Box2 = [f64; 4];

/// Space kept between two labels, in pixels (so that "10" and "5" side by side do not read
/// as "105").
const PAD: f64 = 4.0;

fn overlap(a: &Box2, b: &Box2) -> bool {
    a[0] < b[2] + PAD && b[0] < a[2] + PAD && a[1] < b[3] + PAD && b[1] < a[3] + PAD
}

/// Places labels one after another: each at the first of eight positions around its point
/// whose box lies inside the bounds and overlaps no box placed before.
#[derive(Clone, Debug)]
pub struct Placer {
    bounds: Box2,
    placed: Vec<Box2>,
}

impl Placer {
    /// A placer for labels inside `bounds`, with boxes already taken (e.g. other text).
    pub fn new(bounds: Box2) -> Self {
        Placer {
            bounds,
            placed: Vec::new(),
        }
    }

    /// Marks a box as taken.
    pub fn take(&mut self, b: Box2) {
        self.placed.push(b);
    }

    /// The top-left corner of a free box for `text` at `px` pixels beside the point
    /// `(x, y)` (`gap` pixels away), or `None` when every position is taken or outside.
    pub fn place(
        &mut self,
        text: &str,
        px: f64,
        (x, y): (f64, f64),
        gap: f64,
    ) -> Option<(f64, f64)> {
        let (w, h) = (text_width(text, px), 1.2 * px);
        let candidates = [
            (x + gap, y - gap - h),
            (x + gap, y + gap),
            (x - gap - w, y - gap - h),
            (x - gap - w, y + gap),
            (x + gap, y - h / 2.0),
            (x - gap - w, y - h / 2.0),
            (x - w / 2.0, y - gap - h),
            (x - w / 2.0, y + gap),
        ];
        let b = &self.bounds;
        for (left, top) in candidates {
            let bx = [left, top, left + w, top + h];
            let inside = bx[0] >= b[0] && bx[1] >= b[1] && bx[2] <= b[2] && bx[3] <= b[3];
            if inside && !self.placed.iter().any(|p| overlap(p, &bx)) {
                self.placed.push(bx);
                return Some((left, top));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn titles_shrink_and_labels_do_not_overlap() {
        let t = "a title that is far too long for the narrow width it is given here";
        let s = fitting_size(t, 20.0, 5.0, 200.0);
        assert!(s < 20.0 && text_width(t, s) <= 200.0 + 1e-9);
        assert_eq!(fitting_size("short", 20.0, 5.0, 200.0), 20.0);
        let mut p = Placer::new([0.0, 0.0, 300.0, 300.0]);
        let w = text_width("10.5", 13.0);
        let boxes: Vec<Box2> = (0..12)
            .filter_map(|_| p.place("10.5", 13.0, (150.0, 150.0), 4.0))
            .map(|(l, t)| [l, t, l + w, t + 1.2 * 13.0])
            .collect();
        // The four corners at least, never two overlapping, and not twelve around one point.
        assert!((4..12).contains(&boxes.len()), "{boxes:?}");
        for (i, a) in boxes.iter().enumerate() {
            assert!(boxes[i + 1..].iter().all(|b| !overlap(a, b)), "{boxes:?}");
        }
        // Nothing outside the bounds.
        let mut q = Placer::new([0.0, 0.0, 100.0, 100.0]);
        let (l, t) = q.place("label", 13.0, (99.0, 1.0), 4.0).unwrap();
        assert!(l >= 0.0 && t >= 0.0 && l + text_width("label", 13.0) <= 100.0);
    }
}
