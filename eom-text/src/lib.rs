//! Text that comes from outside — a model file, an AVL file, the command line — on its way
//! into a message, a terminal, a comment of generated code or a name. One home for the rules:
//!
//! * [`shown`]: a user string quoted in a message, with every character that could act on a
//!   terminal or mislead a reader escaped ([`is_unsafe`]: control characters, bidirectional
//!   overrides, line and paragraph separators) and a long string cut in the middle with its
//!   length, so that a 10 MB key in a file is not echoed whole;
//! * [`escaped`]: the same escapes without the cut (a comment of generated code must keep the
//!   whole name, on one line);
//! * [`for_terminal`]: a whole message or report before it is printed: the same escapes, but
//!   line feeds and tabs kept;
//! * [`name_problem`]: why a name (of a model, body, item, unit, …) cannot be used, if it
//!   contains a character that [`is_unsafe`] — names reach terminals, generated code and
//!   exported files, where such a character would break or forge a line;
//! * [`closest`]: the known name a misspelt one most likely meant, for "did you mean".
//!
//! ```
//! use eom_text::{name_problem, shown};
//! assert_eq!(shown("a\u{1b}[2Jb"), "a\\u{1b}[2Jb");
//! assert!(shown(&"k".repeat(10_000_000)).ends_with("(10000000 characters)"));
//! assert!(name_problem("front wheel").is_none());
//! assert_eq!(
//!     name_problem("smd\npub fn x() {}").unwrap(),
//!     "contains a line feed (U+000A) at character 4: names cannot contain control \
//!      characters, bidirectional-text overrides or line separators"
//! );
//! ```

#![warn(missing_docs)]
#![forbid(unsafe_code)]

use std::borrow::Cow;
use std::fmt::Write;

/// Longest user text repeated in a message, in characters; longer text is cut in the middle.
pub const SHOWN_CHARS: usize = 60;

/// Whether `c` must not appear raw in a name, a message, a terminal or a line comment: a
/// control character (C0, DEL, C1 — line feed and carriage return among them), an explicit
/// bidirectional-text mark, embedding, override or isolate (the "Trojan Source" characters,
/// which reorder what a reader sees and which rustc refuses in comments and literals), or a
/// line or paragraph separator.
pub fn is_unsafe(c: char) -> bool {
    c.is_control()
        || matches!(
            c,
            '\u{061C}'
                | '\u{200E}'
                | '\u{200F}'
                | '\u{202A}'..='\u{202E}'
                | '\u{2066}'..='\u{2069}'
                | '\u{2028}'
                | '\u{2029}'
        )
}

/// The escape of one unsafe character: `\n`, `\r`, `\t`, `\0`, else `\u{…}` in hexadecimal.
fn push_escape(out: &mut String, c: char) {
    match c {
        '\n' => out.push_str("\\n"),
        '\r' => out.push_str("\\r"),
        '\t' => out.push_str("\\t"),
        '\0' => out.push_str("\\0"),
        c => {
            let _ = write!(out, "\\u{{{:x}}}", u32::from(c));
        }
    }
}

/// `s` with every character that [`is_unsafe`] escaped (`\n`, `\u{1b}`, …), whole.
pub fn escaped(s: &str) -> Cow<'_, str> {
    escape_where(s, is_unsafe)
}

/// `s` ready for a terminal: like [`escaped`], but line feeds and tabs are kept (a message
/// or a report has lines).
pub fn for_terminal(s: &str) -> Cow<'_, str> {
    escape_where(s, |c| c != '\n' && c != '\t' && is_unsafe(c))
}

fn escape_where(s: &str, escape: impl Fn(char) -> bool) -> Cow<'_, str> {
    let Some(first) = s.find(&escape) else {
        return Cow::Borrowed(s);
    };
    let mut out = String::with_capacity(s.len() + 8);
    out.push_str(&s[..first]);
    for c in s[first..].chars() {
        if escape(c) {
            push_escape(&mut out, c);
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

/// A user string for a message: [`escaped`], and when longer than [`SHOWN_CHARS`] characters
/// cut to its beginning and end with its length (`abcdefghij…wxyz (1000 characters)`).
pub fn shown(s: &str) -> String {
    shown_within(s, SHOWN_CHARS)
}

/// [`shown`] with another length limit (at least 8 characters are shown).
pub fn shown_within(s: &str, max_chars: usize) -> String {
    let max = max_chars.max(8);
    // Short strings are common: count no further than needed.
    if s.chars().nth(max).is_none() {
        return escaped(s).into_owned();
    }
    let n = s.chars().count();
    let head_len = max * 2 / 3;
    let tail_len = max - head_len - 1;
    let head_end = s.char_indices().nth(head_len).map_or(s.len(), |(i, _)| i);
    let tail_start = s
        .char_indices()
        .nth_back(tail_len.saturating_sub(1))
        .map_or(0, |(i, _)| i);
    format!(
        "{}…{} ({n} characters)",
        escaped(&s[..head_end]),
        escaped(&s[tail_start..])
    )
}

/// The Unicode name of the common unsafe characters, else `U+XXXX`: `a line feed (U+000A)`.
pub fn describe(c: char) -> String {
    let what = match c {
        '\0' => "a NUL",
        '\u{7}' => "a bell",
        '\u{8}' => "a backspace",
        '\t' => "a tab",
        '\n' => "a line feed",
        '\u{b}' => "a vertical tab",
        '\u{c}' => "a form feed",
        '\r' => "a carriage return",
        '\u{1b}' => "an escape",
        '\u{7f}' => "a delete",
        '\u{85}' => "a next-line",
        '\u{2028}' => "a line separator",
        '\u{2029}' => "a paragraph separator",
        c if c.is_control() => "a control character",
        _ => "a bidirectional-text control",
    };
    format!("{what} (U+{:04X})", u32::from(c))
}

/// Why `name` cannot be a name, or `None` when it can: the first character that
/// [`is_unsafe`], with its position (1-based, in characters).
pub fn name_problem(name: &str) -> Option<String> {
    let (k, c) = name.chars().enumerate().find(|(_, c)| is_unsafe(*c))?;
    Some(format!(
        "contains {} at character {}: names cannot contain control characters, \
         bidirectional-text overrides or line separators",
        describe(c),
        k + 1
    ))
}

/// Why `text` cannot be a description (free text that may run over several lines), or
/// `None` when it can: like [`name_problem`], but line feeds and tabs are allowed.
pub fn description_problem(text: &str) -> Option<String> {
    let (k, c) = text
        .chars()
        .enumerate()
        .find(|&(_, c)| c != '\n' && c != '\t' && is_unsafe(c))?;
    Some(format!(
        "contains {} at character {}: text cannot contain control characters other than line \
         feeds and tabs, bidirectional-text overrides or line separators",
        describe(c),
        k + 1
    ))
}

/// The largest input file eom reads (a model file, an AVL file): 64 MiB. A model of 100 000
/// bodies takes about 20 MB; a larger file, or a device that never ends, is refused before
/// it fills the memory.
pub const MAX_FILE_BYTES: u64 = 64 << 20;

/// Reads the text file at `path`, refusing more than `max_bytes` (a size found before reading
/// where the file tells it, else after reading one byte more) and text that is not UTF-8.
/// The errors say which limit and which byte.
pub fn read_limited(path: &std::path::Path, max_bytes: u64) -> std::io::Result<String> {
    use std::io::{Error, ErrorKind, Read};
    let too_large = |size: String| {
        Error::new(
            ErrorKind::InvalidData,
            format!(
                "the file is {size}, more than the limit of {} MiB for an input file",
                max_bytes >> 20
            ),
        )
    };
    let file = std::fs::File::open(path)?;
    if let Ok(m) = file.metadata()
        && m.is_file()
        && m.len() > max_bytes
    {
        return Err(too_large(format!("{} bytes", m.len())));
    }
    let mut bytes = Vec::new();
    file.take(max_bytes + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(too_large("longer".into()));
    }
    String::from_utf8(bytes).map_err(|e| {
        Error::new(
            ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (an invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        )
    })
}

/// The known name closest to `name` in edit distance, if it is close enough to be a likely
/// typo: at most a third of its characters (at least 1, at most 3) edited. Ties go to the
/// first candidate. The one rule behind every "did you mean" (model files, expressions, the
/// command line).
pub fn closest<'k>(name: &str, known: impl IntoIterator<Item = &'k str>) -> Option<&'k str> {
    let n = name.chars().count();
    let limit = (n / 3).clamp(1, 3);
    known
        .into_iter()
        // The distance is at least the difference of the lengths: a long candidate costs
        // nothing.
        .filter(|k| n.abs_diff(k.chars().count()) <= limit)
        .map(|k| (edit_distance(name, k), k))
        .filter(|&(d, _)| d <= limit)
        .min_by_key(|&(d, _)| d)
        .map(|(_, k)| k)
}

/// ` (did you mean `x`?)` when one of `known` is a likely typo of `name` ([`closest`]), else
/// nothing: the suffix every "unknown name" message appends.
pub fn did_you_mean<S: AsRef<str>>(name: &str, known: &[S]) -> String {
    closest(name, known.iter().map(AsRef::as_ref))
        .map_or_else(String::new, |k| format!(" (did you mean `{}`?)", shown(k)))
}

/// Levenshtein distance over characters.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let up = row[j + 1];
            row[j + 1] = (up + 1).min(row[j] + 1).min(diag + usize::from(ca != cb));
            diag = up;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn every_control_character_is_escaped_and_named() {
        for c in (0u32..0x20).chain(0x7f..0xa0).filter_map(char::from_u32) {
            assert!(is_unsafe(c));
            let s = format!("a{c}b");
            let e = escaped(&s);
            assert!(!e.contains(c), "{c:?} left raw in {e:?}");
            assert!(e.starts_with('a') && e.ends_with('b'));
            assert!(name_problem(&s).unwrap().contains("at character 2"));
        }
        for c in ['\u{202E}', '\u{2066}', '\u{2028}', '\u{200F}'] {
            assert!(is_unsafe(c) && name_problem(&format!("x{c}")).is_some());
        }
        assert_eq!(escaped("é→ü 漢字 \\n"), "é→ü 漢字 \\n");
        assert!(name_problem("front wheel é (ü) \"quoted\" 'x' \\ `y`").is_none());
        assert_eq!(for_terminal("a\n\tb\u{1b}c\r"), "a\n\tb\\u{1b}c\\r");
    }

    #[test]
    fn long_text_is_cut_with_its_length() {
        let s = format!("{}\u{1b}{}", "é".repeat(5000), "z".repeat(5000));
        let c = shown(&s);
        assert!(c.chars().count() < 100, "{c}");
        assert!(c.starts_with("éé") && c.ends_with("zz (10001 characters)"));
        assert_eq!(shown("short"), "short");
        let exact: String = "x".repeat(SHOWN_CHARS);
        assert_eq!(shown(&exact), exact);
    }

    proptest! {
        #[test]
        fn shown_text_never_holds_an_unsafe_character(s in any::<String>()) {
            prop_assert!(!shown(&s).chars().any(is_unsafe));
            prop_assert!(!escaped(&s).chars().any(is_unsafe));
            prop_assert!(!for_terminal(&s).chars().any(|c| c != '\n' && c != '\t' && is_unsafe(c)));
            prop_assert_eq!(name_problem(&s).is_none(), !s.chars().any(is_unsafe));
        }
    }

    #[test]
    fn closest_names_a_likely_typo_only() {
        use super::{closest, edit_distance};
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        let keys = ["stiffness", "span", "sqrt", "sin", "at", "axis"];
        assert_eq!(closest("stifness", keys), Some("stiffness"));
        assert_eq!(closest("spn", keys), Some("span"));
        assert_eq!(closest("sinn", keys), Some("sin"));
        assert_eq!(closest("zzzzzz", keys), None);
        // Two characters: one edit at most (`ax` is not `at`'s typo and `axis`'s both).
        assert_eq!(closest("ax", ["axis"]), None);
    }
}
