//! Mirror images of items: the coordinate normal to the mirror plane changes sign in positions
//! and directions, the two others in rotations and moments (pseudo-vectors), and the products
//! of inertia that involve it change sign.

use super::items::VecKind;
use eom_sym::Expr;

/// A mirror plane, by the axis normal to it (`mirror = "y"`: the x–z plane, left ↔ right).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Mirror {
    axis: usize,
}

impl Mirror {
    pub fn parse(text: &str) -> Result<Mirror, String> {
        match text {
            "x" => Ok(Mirror { axis: 0 }),
            "y" => Ok(Mirror { axis: 1 }),
            "z" => Ok(Mirror { axis: 2 }),
            _ => Err(format!(
                "`{text}` is not a mirror axis; use \"y\" (left ↔ right), \"x\" or \"z\""
            )),
        }
    }

    /// The image of a vector.
    pub fn apply(self, v: [Expr; 3], kind: VecKind) -> [Expr; 3] {
        let mut out = v;
        for (k, x) in out.iter_mut().enumerate() {
            let flip = match kind {
                VecKind::Polar => k == self.axis,
                VecKind::Axial => k != self.axis,
                VecKind::Products => return self.products(v),
                VecKind::Plain => return v,
            };
            if flip && !x.is_zero() {
                *x = -*x;
            }
        }
        out
    }

    /// The image of the products of inertia `[xy, yz, zx]`: those involving the mirror axis
    /// change sign.
    pub fn products(self, p: [Expr; 3]) -> [Expr; 3] {
        let involves = |k: usize| match k {
            0 => self.axis == 0 || self.axis == 1,
            1 => self.axis == 1 || self.axis == 2,
            _ => self.axis == 2 || self.axis == 0,
        };
        let mut out = p;
        for (k, x) in out.iter_mut().enumerate() {
            if involves(k) && !x.is_zero() {
                *x = -*x;
            }
        }
        out
    }
}

/// The name of the mirror image: `left` ↔ `right` (any case), and the words `L`/`R`,
/// `LF`/`RF`, `LR`/`RR` (separated by `_`, `-`, `.` or a space). `None` when nothing changes.
pub(crate) fn mirror_name(name: &str) -> Option<String> {
    let swapped = swap_words(name);
    let out = swap_sides(&swapped);
    (out != name).then_some(out)
}

fn swap_sides(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let lower = s.to_lowercase();
    let mut i = 0;
    while i < s.len() {
        let rest = &lower[i..];
        let (from, to) = if rest.starts_with("left") {
            (4, "right")
        } else if rest.starts_with("right") {
            (5, "left")
        } else {
            let c = s[i..].chars().next().expect("a char");
            out.push(c);
            i += c.len_utf8();
            continue;
        };
        let orig = &s[i..i + from];
        out.push_str(&match_case(orig, to));
        i += from;
    }
    out
}

fn match_case(orig: &str, to: &str) -> String {
    if orig.chars().all(|c| c.is_uppercase()) {
        to.to_uppercase()
    } else if orig.chars().next().is_some_and(char::is_uppercase) {
        let mut c = to.chars();
        c.next().map_or(String::new(), |f| {
            f.to_uppercase().collect::<String>() + c.as_str()
        })
    } else {
        to.to_string()
    }
}

fn swap_words(s: &str) -> String {
    let mut out = String::new();
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        let w = match word.as_str() {
            "L" => "R",
            "R" => "L",
            "LF" => "RF",
            "RF" => "LF",
            "LR" => "RR",
            "RR" => "LR",
            "l" => "r",
            "r" => "l",
            w => w,
        };
        out.push_str(w);
        word.clear();
    };
    for c in s.chars() {
        if matches!(c, '_' | '-' | '.' | ' ') {
            flush(&mut word, &mut out);
            out.push(c);
        } else {
            word.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_swap_sides() {
        assert_eq!(
            mirror_name("front_left_wheel").as_deref(),
            Some("front_right_wheel")
        );
        assert_eq!(mirror_name("Left spring").as_deref(), Some("Right spring"));
        assert_eq!(mirror_name("wheel_LF").as_deref(), Some("wheel_RF"));
        assert_eq!(mirror_name("tyre_R").as_deref(), Some("tyre_L"));
        assert_eq!(mirror_name("chassis"), None);
    }
}
