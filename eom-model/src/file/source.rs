//! The TOML document with positions: tables whose keys are checked against the known ones,
//! typed getters, and errors that name the file, line and column.

use super::error::FileError;
use std::ops::Range;
use toml::Spanned;
use toml::de::{DeTable, DeValue};

/// A TOML value with its span.
pub(crate) type Value<'a> = Spanned<DeValue<'a>>;

/// Where in a file: 1-based line and column (0 for the whole file).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FilePosition {
    /// The file as named by the caller.
    pub file: String,
    /// 1-based line (0: the file as a whole).
    pub line: usize,
    /// 1-based column in characters (0: the file as a whole).
    pub column: usize,
}

impl FilePosition {
    /// The file as a whole.
    pub fn whole(file: &str) -> Self {
        FilePosition {
            file: file.to_string(),
            line: 0,
            column: 0,
        }
    }
}

impl std::fmt::Display for FilePosition {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.line == 0 {
            write!(f, "{}", self.file)
        } else {
            write!(f, "{}:{}:{}", self.file, self.line, self.column)
        }
    }
}

/// The text being loaded and its name.
pub(crate) struct Ctx<'t> {
    pub text: &'t str,
    pub origin: &'t str,
    /// The directory that relative paths in the file (AVL files) are relative to; `None`:
    /// the current directory.
    pub base: Option<&'t std::path::Path>,
}

impl<'t> Ctx<'t> {
    pub fn new(text: &'t str, origin: &'t str, base: Option<&'t std::path::Path>) -> Self {
        Ctx { text, origin, base }
    }

    /// The position of byte offset `at`.
    pub fn position(&self, at: usize) -> FilePosition {
        let at = at.min(self.text.len());
        let before = &self.text[..self.text.floor_char_boundary(at)];
        let line = before.matches('\n').count() + 1;
        let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
        FilePosition {
            file: self.origin.to_string(),
            line,
            column,
        }
    }

    /// An error at `span`, about `context` (e.g. ``spring `front`, field `stiffness` ``).
    pub fn error(
        &self,
        span: &Range<usize>,
        context: &str,
        problem: impl Into<String>,
    ) -> FileError {
        FileError::Invalid {
            position: self.position(span.start),
            context: context.to_string(),
            problem: problem.into(),
        }
    }

    /// The document (a TOML syntax error is reported at its position).
    pub fn parse(&self) -> Result<Spanned<DeTable<'t>>, FileError> {
        DeTable::parse(self.text).map_err(|e| {
            let span = e.span().unwrap_or(0..0);
            self.error(&span, "", format!("not valid TOML: {}", e.message().trim()))
        })
    }
}

/// A table of the document with the context its errors name.
pub(crate) struct Table<'a> {
    pub ctx: &'a Ctx<'a>,
    pub table: &'a DeTable<'a>,
    pub span: Range<usize>,
    pub context: String,
}

impl<'a> Table<'a> {
    pub fn new(ctx: &'a Ctx<'a>, doc: &'a Spanned<DeTable<'a>>, context: &str) -> Self {
        Table {
            ctx,
            table: doc.get_ref(),
            span: doc.span(),
            context: context.to_string(),
        }
    }

    /// A sub-table value as a [`Table`] with its own context.
    pub fn sub(ctx: &'a Ctx<'a>, v: &'a Value<'a>, context: String) -> Result<Self, FileError> {
        match v.get_ref() {
            DeValue::Table(t) => Ok(Table {
                ctx,
                table: t,
                span: v.span(),
                context,
            }),
            other => Err(ctx.error(
                &v.span(),
                &context,
                format!("expected a table, found {}", other.type_str()),
            )),
        }
    }

    /// An error about the whole table.
    pub fn error(&self, problem: impl Into<String>) -> FileError {
        self.ctx.error(&self.span, &self.context, problem)
    }

    /// An error about field `key` at `span`.
    pub fn field_error(
        &self,
        key: &str,
        span: &Range<usize>,
        problem: impl Into<String>,
    ) -> FileError {
        self.ctx.error(span, &self.field_context(key), problem)
    }

    /// `context, field `key``.
    pub fn field_context(&self, key: &str) -> String {
        if self.context.is_empty() {
            format!("field `{key}`")
        } else {
            format!("{}, field `{key}`", self.context)
        }
    }

    /// Every key must be one of `known`.
    pub fn only(&self, known: &[&str]) -> Result<(), FileError> {
        for (k, _) in self.table.iter() {
            if !known.contains(&k.get_ref().as_ref()) {
                let hint = eom_text::did_you_mean(k.get_ref(), known);
                return Err(self.ctx.error(
                    &k.span(),
                    &self.context,
                    format!(
                        "unknown key `{}`{hint}; the keys here are: {}",
                        eom_text::shown(k.get_ref()),
                        known.join(", ")
                    ),
                ));
            }
        }
        Ok(())
    }

    pub fn get(&self, key: &str) -> Option<&'a Value<'a>> {
        self.table.get(key)
    }

    /// The keys in order, with their spans.
    pub fn entries(&self) -> impl Iterator<Item = (&'a str, Range<usize>, &'a Value<'a>)> {
        self.table
            .iter()
            .map(|(k, v)| (k.get_ref().as_ref(), k.span(), v))
    }

    pub fn table(&self, key: &str) -> Result<Option<Table<'a>>, FileError> {
        match self.get(key) {
            None => Ok(None),
            Some(v) => Table::sub(self.ctx, v, format!("[{key}]")).map(Some),
        }
    }

    pub fn string(&self, key: &str) -> Result<Option<String>, FileError> {
        match self.get(key) {
            None => Ok(None),
            Some(v) => match v.get_ref() {
                DeValue::String(s) => {
                    // Every string of a file reaches messages, terminals, exported files and
                    // generated code: no control characters (line breaks only in free text).
                    let problem = if key == "description" {
                        eom_text::description_problem(s)
                    } else {
                        eom_text::name_problem(s)
                    };
                    match problem {
                        Some(p) => Err(self.field_error(key, &v.span(), p)),
                        None => Ok(Some(s.to_string())),
                    }
                }
                other => Err(self.field_error(
                    key,
                    &v.span(),
                    format!("expected a string, found {}", other.type_str()),
                )),
            },
        }
    }

    pub fn bool(&self, key: &str) -> Result<Option<bool>, FileError> {
        match self.get(key) {
            None => Ok(None),
            Some(v) => match v.get_ref() {
                DeValue::Boolean(b) => Ok(Some(*b)),
                other => Err(self.field_error(
                    key,
                    &v.span(),
                    format!("expected true or false, found {}", other.type_str()),
                )),
            },
        }
    }

    /// A small non-negative integer (a count such as `forces`), at most `max`.
    pub fn count(&self, key: &str, max: u8) -> Result<Option<u8>, FileError> {
        match self.get(key) {
            None => Ok(None),
            Some(v) => match v.get_ref() {
                DeValue::Integer(i) => {
                    let n = parse_integer(i.as_str(), i.radix());
                    match n {
                        Some(n) if (0..=i64::from(max)).contains(&n) => Ok(Some(n as u8)),
                        _ => Err(self.field_error(
                            key,
                            &v.span(),
                            format!("expected an integer from 0 to {max}, found {}", i.as_str()),
                        )),
                    }
                }
                other => Err(self.field_error(
                    key,
                    &v.span(),
                    format!(
                        "expected an integer from 0 to {max}, found {}",
                        other.type_str()
                    ),
                )),
            },
        }
    }
}

/// `v` as an array of exactly `n` values.
pub(crate) fn array_of<'a>(
    t: &Table<'a>,
    key: &str,
    v: &'a Value<'a>,
    n: usize,
) -> Result<&'a [Value<'a>], FileError> {
    match v.get_ref() {
        DeValue::Array(a) if a.len() == n => Ok(a),
        DeValue::Array(a) => Err(t.field_error(
            key,
            &v.span(),
            format!("expected {n} values, found {}", a.len()),
        )),
        other => Err(t.field_error(
            key,
            &v.span(),
            format!(
                "expected an array of {n} values, found {}",
                other.type_str()
            ),
        )),
    }
}

/// A TOML integer's text (underscores allowed) in its radix.
pub(crate) fn parse_integer(text: &str, radix: u32) -> Option<i64> {
    let t: String = text.chars().filter(|&c| c != '_').collect();
    let t = t
        .trim_start_matches("0x")
        .trim_start_matches("0o")
        .trim_start_matches("0b");
    i64::from_str_radix(t, radix).ok()
}
