//! Sums and products combined by the estimated ready times of their operands.

use proc_macro2::TokenStream;
use quote::quote;

/// Estimated latencies (cycles) of the operations, for ordering the operands of sums and
/// products. Only their relative sizes matter: a division or a call is much slower than an
/// addition, and everything waiting on it should be combined last.
pub(super) mod latency {
    /// Addition, subtraction, multiplication.
    pub const ARITH: u32 = 3;
    /// Sign flip or absolute value (a bit operation).
    pub const SIGN: u32 = 1;
    /// Division (and reciprocal).
    pub const DIV: u32 = 13;
    /// Square root.
    pub const SQRT: u32 = 15;
    /// A call of an elementary function (`sin`, `sincos`, `exp`, `pow`, …).
    pub const CALL: u32 = 45;
}

/// A subtree of a sum or product being built: its code, when its value is ready, whether it
/// is compound (needs parentheses as a right operand) and, in sums, whether it enters
/// subtracted.
#[derive(Clone)]
pub(super) struct Part {
    pub(super) code: TokenStream,
    pub(super) ready: u32,
    pub(super) compound: bool,
    pub(super) neg: bool,
}

impl Part {
    pub(super) fn leaf(code: TokenStream, ready: u32) -> Part {
        Part {
            code,
            ready,
            compound: false,
            neg: false,
        }
    }
}

/// Combine `parts` with `op` (`+` for sums, `*` for products) by ready time: the two values
/// that are ready first are combined first (as Huffman's code combines the two rarest), so
/// a late value (after a division or a call) meets a sum of everything else in one last
/// operation, instead of sitting at the bottom of a balanced tree. Equal ready times give a
/// balanced tree. Rust keeps the written association of floating-point operations, so the
/// tree is spelt out with parentheses.
///
/// In sums, subtracted parts combine as `a − b`, `b − a` or `−(a + b)`; a sum with one added
/// term (the lowering's canonical sign guarantees one) is never negative at the root, since
/// a part containing an added term stays added. Ties keep the given order (deterministic).
pub(super) fn by_ready(mut parts: Vec<Part>, sum: bool) -> Part {
    if parts.is_empty() {
        let code = if sum { quote!(0.0) } else { quote!(1.0) };
        return Part::leaf(code, 0);
    }
    // Kept sorted by ready time (stable: ties in the given order); a merged part goes after
    // the parts that are ready as early, so equal ready times give a balanced tree.
    parts.sort_by_key(|p| p.ready);
    while parts.len() > 1 {
        let (mut a, mut b) = (parts.remove(0), parts.remove(0));
        let ready = a.ready.max(b.ready) + latency::ARITH;
        // `x + (y + z)` reads better as `y + z + x`; commuting is exact in floating point.
        if b.compound && !a.compound && a.neg == b.neg {
            std::mem::swap(&mut a, &mut b);
        }
        let paren = |p: &Part| {
            let c = &p.code;
            if p.compound { quote!((#c)) } else { c.clone() }
        };
        let (code, neg) = match (sum, a.neg, b.neg) {
            (false, _, _) => {
                let (l, r) = (&a.code, paren(&b));
                (quote!(#l * #r), false)
            }
            (true, false, false) | (true, true, true) => {
                let (l, r) = (&a.code, paren(&b));
                (quote!(#l + #r), a.neg)
            }
            (true, false, true) => {
                let (l, r) = (&a.code, paren(&b));
                (quote!(#l - #r), false)
            }
            (true, true, false) => {
                let (l, r) = (&b.code, paren(&a));
                (quote!(#l - #r), false)
            }
        };
        let at = parts.partition_point(|p| p.ready <= ready);
        parts.insert(
            at,
            Part {
                code,
                ready,
                compound: true,
                neg,
            },
        );
    }
    let root = parts.pop().expect("one part");
    if root.neg {
        let c = &root.code;
        let code = if root.compound {
            quote!(-(#c))
        } else {
            quote!(-#c)
        };
        Part {
            code,
            ready: root.ready + latency::SIGN,
            compound: false,
            neg: false,
        }
    } else {
        root
    }
}

/// `c0 op c1 op …` for boolean conditions with a non-short-circuit `&` or `|`, parenthesising
/// the comparisons (which bind less tightly than `&` and `|`).
pub(super) fn join(conds: &[TokenStream], op: TokenStream) -> TokenStream {
    if conds.len() == 1 {
        return conds[0].clone();
    }
    let wrapped = conds.iter().map(|c| {
        let text = c.to_string();
        if text.starts_with('!') || !text.contains(['<', '>', '=', '&', '|']) {
            c.clone()
        } else {
            quote!((#c))
        }
    });
    let mut out = TokenStream::new();
    for (k, c) in wrapped.enumerate() {
        if k > 0 {
            out.extend(op.clone());
        }
        out.extend(c);
    }
    out
}
