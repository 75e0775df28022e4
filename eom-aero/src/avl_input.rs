//! Reader of AVL geometry files (`.avl`): the header and the lifting-surface keywords.
//!
//! Format (AVL's user guide): `#` and `!` start comments; the first five data lines are the
//! title, `Mach`, `iYsym iZsym Zsym`, `Sref Cref Bref`, `Xref Yref Zref`, optionally
//! followed by `CDp`; then keywords, of which only the first four letters count, each with
//! its data on the following line(s).
//!
//! Honoured: `SURFACE` (name; `Nchord Cspace [Nspan Sspace]`), `COMPONENT`/`INDEX`,
//! `YDUPLICATE`, `SCALE`, `TRANSLATE`, `ANGLE`, `NOALBE`, `NOLOAD`, `SECTION`
//! (`Xle Yle Zle Chord Ainc [Nspan Sspace]`), `NACA` with a zero-camber 4-digit section
//! (its camber line is the flat plate the lattice uses anyway) and `CLAF 1`.
//!
//! Refused with an error naming the file, line and keyword, because the flat-plate lattice
//! cannot honour them: `BODY`/`BFILE` (slender bodies), cambered `NACA`, `AIRFOIL`, `AFILE`
//! (camber lines), `CLAF` ≠ 1, `CDCL` (viscous polar), `CONTROL`, `DESIGN`, `NOWAKE` (a
//! surface without a Kutta condition), and a nonzero `iYsym` (the y image; `iZsym`, the z
//! image of ground effect, is supported).

use crate::derivatives::Reference;
use crate::error::{AeroError, Result};
use crate::geometry::{Configuration, Section, Surface, Symmetry};
use crate::spacing::Spacing;
use std::path::Path;

/// Reads an `.avl` geometry file.
pub fn read_avl(path: impl AsRef<Path>) -> Result<Configuration> {
    let path = path.as_ref();
    let file = path.display().to_string();
    let text =
        eom_text::read_limited(path, eom_text::MAX_FILE_BYTES).map_err(|source| AeroError::Io {
            file: file.clone(),
            source,
        })?;
    parse_avl(&text, &file)
}

/// Parses the text of an `.avl` geometry file; `file` names it in errors.
pub fn parse_avl(text: &str, file: &str) -> Result<Configuration> {
    let mut lines = Lines::new(text, file);
    let (_, title) = lines.next_raw("the title")?;
    let title = title.trim().to_string();
    let mach = lines.numbers("Mach", &["Mach"], 1)?[0];
    let (line, sym) = lines.numbers_at("iYsym iZsym Zsym", &["iYsym", "iZsym", "Zsym"], 3)?;
    let symmetry = Symmetry {
        iysym: lines.integer(line, "iYsym", sym[0])? as i32,
        izsym: lines.integer(line, "iZsym", sym[1])? as i32,
        zsym: sym[2],
    };
    if symmetry.iysym != 0 {
        return Err(unsupported(
            file,
            line,
            "iYsym",
            "the y image is not supported: model both halves with YDUPLICATE",
        ));
    }
    if !(-1..=1).contains(&symmetry.izsym) {
        return Err(lines.err(
            line,
            format!("iZsym must be -1, 0 or 1, found {}", symmetry.izsym),
        ));
    }
    let r = lines.numbers("Sref Cref Bref", &["Sref", "Cref", "Bref"], 3)?;
    let p = lines.numbers("Xref Yref Zref", &["Xref", "Yref", "Zref"], 3)?;
    let mut config =
        Configuration::new(title, Reference::new(r[0], r[1], r[2], [p[0], p[1], p[2]]));
    config.mach = mach;
    config.symmetry = symmetry;
    if lines.peek().is_some_and(|(_, t)| first_number(t).is_some()) {
        config.cdp = lines.numbers("CDp", &["CDp"], 1)?[0];
    }
    let mut reader = SurfaceReader::default();
    while let Some((line, text)) = lines.next_line() {
        reader.keyword(&mut lines, &mut config, line, text)?;
    }
    reader.finish(&mut config, file)?;
    Ok(config)
}

fn unsupported(file: &str, line: usize, keyword: &str, reason: &str) -> AeroError {
    AeroError::UnsupportedKeyword {
        file: file.to_string(),
        line,
        keyword: keyword.to_string(),
        reason: reason.to_string(),
    }
}

fn first_number(text: &str) -> Option<f64> {
    tokens(text).next().and_then(|t| t.parse::<f64>().ok())
}

fn tokens(text: &str) -> impl Iterator<Item = &str> {
    text.split(|c: char| c.is_whitespace() || c == ',')
        .filter(|t| !t.is_empty())
}

/// The data lines of the file with comments and blank lines removed.
struct Lines<'a> {
    file: &'a str,
    items: Vec<(usize, &'a str, &'a str)>,
    pos: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str, file: &'a str) -> Self {
        let items = text
            .lines()
            .enumerate()
            .filter_map(|(i, raw)| {
                let data = raw.split(['#', '!']).next().unwrap_or("").trim();
                (!data.is_empty()).then_some((i + 1, data, raw))
            })
            .collect();
        Lines {
            file,
            items,
            pos: 0,
        }
    }

    fn peek(&self) -> Option<(usize, &'a str)> {
        self.items.get(self.pos).map(|&(l, d, _)| (l, d))
    }

    fn next_line(&mut self) -> Option<(usize, &'a str)> {
        let item = self.peek();
        self.pos += item.is_some() as usize;
        item
    }

    fn last_line(&self) -> usize {
        self.items.last().map_or(0, |i| i.0)
    }

    fn err(&self, line: usize, message: String) -> AeroError {
        AeroError::Parse {
            file: self.file.to_string(),
            line,
            message,
        }
    }

    fn next_data(&mut self, what: &str) -> Result<(usize, &'a str)> {
        let end = self.last_line();
        self.next_line()
            .ok_or_else(|| self.err(end, format!("unexpected end of file: expected {what}")))
    }

    /// The next data line with its comment kept (titles and names may contain `#`).
    fn next_raw(&mut self, what: &str) -> Result<(usize, &'a str)> {
        let end = self.last_line();
        let item = self.items.get(self.pos).copied();
        self.pos += 1;
        item.map(|(l, _, raw)| (l, raw))
            .ok_or_else(|| self.err(end, format!("unexpected end of file: expected {what}")))
    }

    fn numbers(&mut self, what: &str, names: &[&str], required: usize) -> Result<Vec<f64>> {
        Ok(self.numbers_at(what, names, required)?.1)
    }

    /// The next line's numbers: the `required` first ones must be there; further ones up to
    /// `names.len()` are read while they are numbers (text after them is a remark).
    fn numbers_at(
        &mut self,
        what: &str,
        names: &[&str],
        required: usize,
    ) -> Result<(usize, Vec<f64>)> {
        let (line, text) = self.next_data(what)?;
        let mut out = Vec::new();
        let mut toks = tokens(text);
        for (k, name) in names.iter().enumerate() {
            let tok = toks.next();
            let value = tok
                .and_then(|t| t.parse::<f64>().ok())
                .filter(|v| v.is_finite());
            match (value, k < required) {
                (Some(v), _) => out.push(v),
                (None, false) => break,
                (None, true) => {
                    let found = tok.map_or("nothing".to_string(), |t| {
                        format!("`{}`", eom_text::shown(t))
                    });
                    return Err(self.err(
                        line,
                        format!("{what}: {name} must be a finite number, found {found}"),
                    ));
                }
            }
        }
        Ok((line, out))
    }

    fn integer(&self, line: usize, name: &str, v: f64) -> Result<i64> {
        if v.fract() == 0.0 && v.abs() < 1e9 {
            Ok(v as i64)
        } else {
            Err(self.err(line, format!("{name} must be an integer, found {v}")))
        }
    }

    fn count(&self, line: usize, name: &str, v: f64) -> Result<usize> {
        match self.integer(line, name, v)? {
            n if n as usize > crate::MAX_PANELS => Err(self.err(
                line,
                format!(
                    "{name} = {n} is more than the limit of {} panels of a lattice",
                    crate::MAX_PANELS
                ),
            )),
            n if n >= 1 => Ok(n as usize),
            n => Err(self.err(line, format!("{name} must be at least 1, found {n}"))),
        }
    }
}

/// Keyword state: the surface being read, and where its parts were declared.
#[derive(Default)]
struct SurfaceReader {
    current: Option<(Surface, usize, Vec<usize>)>,
}

impl SurfaceReader {
    fn surface(&mut self, lines: &Lines, line: usize, key: &str) -> Result<&mut Surface> {
        match self.current.as_mut() {
            Some((s, _, _)) => Ok(s),
            None => Err(lines.err(line, format!("{key} before any SURFACE"))),
        }
    }

    fn keyword(
        &mut self,
        lines: &mut Lines,
        config: &mut Configuration,
        line: usize,
        text: &str,
    ) -> Result<()> {
        let word = tokens(text).next().unwrap_or("");
        let key: String = word.to_ascii_uppercase().chars().take(4).collect();
        let file = lines.file;
        match key.as_str() {
            "SURF" => {
                self.finish(config, file)?;
                let (_, name) = lines.next_raw("the surface name")?;
                let (l, v) = lines.numbers_at(
                    "Nchord Cspace [Nspan Sspace]",
                    &["Nchord", "Cspace", "Nspan", "Sspace"],
                    2,
                )?;
                let mut s = Surface::new(name.trim()).strips_per_section();
                s.chordwise = Spacing::new(lines.count(l, "Nchord", v[0])?, v[1]);
                if v.len() >= 4 {
                    s.spanwise = Some(Spacing::new(lines.count(l, "Nspan", v[2])?, v[3]));
                } else if v.len() == 3 {
                    return Err(lines.err(l, "Nspan given without Sspace".into()));
                }
                self.current = Some((s, line, Vec::new()));
            }
            "COMP" | "INDE" => {
                let (l, v) = lines.numbers_at("component index", &["index"], 1)?;
                let n = lines.integer(l, "index", v[0])?;
                self.surface(lines, line, word)?.component = Some(n);
            }
            "YDUP" => {
                let v = lines.numbers("YDUPLICATE", &["Ydupl"], 1)?;
                self.surface(lines, line, word)?.y_duplicate = Some(v[0]);
            }
            "SCAL" => {
                let v = lines.numbers("SCALE", &["Xscale", "Yscale", "Zscale"], 3)?;
                self.surface(lines, line, word)?.scale = [v[0], v[1], v[2]];
            }
            "TRAN" => {
                let v = lines.numbers("TRANSLATE", &["dX", "dY", "dZ"], 3)?;
                self.surface(lines, line, word)?.translate = [v[0], v[1], v[2]];
            }
            "ANGL" => {
                let v = lines.numbers("ANGLE", &["dAinc"], 1)?;
                self.surface(lines, line, word)?.angle_deg = v[0];
            }
            "NOAL" => self.surface(lines, line, word)?.no_alpha_beta = true,
            "NOLO" => self.surface(lines, line, word)?.no_load = true,
            "SECT" => self.section(lines, line, word)?,
            _ => return self.special(lines, line, word, &key),
        }
        Ok(())
    }

    fn section(&mut self, lines: &mut Lines, line: usize, word: &str) -> Result<()> {
        self.surface(lines, line, word)?;
        let names = ["Xle", "Yle", "Zle", "Chord", "Ainc", "Nspan", "Sspace"];
        let (l, v) = lines.numbers_at("SECTION data", &names, 5)?;
        let mut sec = Section::new([v[0], v[1], v[2]], v[3]).incidence_deg(v[4]);
        if v.len() >= 7 {
            sec.spanwise = Some(Spacing::new(lines.count(l, "Nspan", v[5])?, v[6]));
        } else if v.len() == 6 {
            return Err(lines.err(l, "Nspan given without Sspace".into()));
        }
        if let Some((s, _, sec_lines)) = self.current.as_mut() {
            s.sections.push(sec);
            sec_lines.push(line);
        }
        Ok(())
    }

    /// Keywords that are accepted only where they change nothing, or refused.
    fn special(&mut self, lines: &mut Lines, line: usize, word: &str, key: &str) -> Result<()> {
        let file = lines.file;
        match key {
            "NACA" => {
                self.surface(lines, line, word)?;
                let (_, text) = lines.next_data("the NACA digits")?;
                let digits = tokens(text).next().unwrap_or("");
                if digits.len() == 4
                    && digits.starts_with('0')
                    && digits.chars().all(|c| c.is_ascii_digit())
                {
                    Ok(())
                } else {
                    Err(unsupported(
                        file,
                        line,
                        word,
                        &format!(
                            "NACA {digits} has camber; only symmetric sections (0xxx, a flat camber line) are supported"
                        ),
                    ))
                }
            }
            "CLAF" => {
                self.surface(lines, line, word)?;
                let v = lines.numbers("CLAF factor", &["CLaf"], 1)?;
                if v[0] == 1.0 {
                    Ok(())
                } else {
                    Err(unsupported(
                        file,
                        line,
                        word,
                        "a lift-slope factor other than 1 is not supported",
                    ))
                }
            }
            "AIRF" | "AFIL" => Err(unsupported(
                file,
                line,
                word,
                "camber lines are not supported (flat-plate lattice)",
            )),
            "BODY" | "BFIL" => Err(unsupported(
                file,
                line,
                word,
                "slender bodies are not supported",
            )),
            "CDCL" => Err(unsupported(
                file,
                line,
                word,
                "the lattice is inviscid: no profile-drag polar",
            )),
            "CONT" | "DESI" => Err(unsupported(
                file,
                line,
                word,
                "control and design variables are not supported",
            )),
            "NOWA" => Err(unsupported(
                file,
                line,
                word,
                "surfaces without a wake (no Kutta condition) are not supported",
            )),
            _ => Err(lines.err(line, format!("unknown keyword `{}`", eom_text::shown(word)))),
        }
    }

    /// Validates the surface being read and adds it to the configuration; errors point at
    /// the line of the surface or of the faulty section.
    fn finish(&mut self, config: &mut Configuration, file: &str) -> Result<()> {
        let Some((surface, line, sec_lines)) = self.current.take() else {
            return Ok(());
        };
        if let Err(e) = surface.validate() {
            let at = match &e {
                AeroError::Geometry {
                    section: Some(k), ..
                } => sec_lines.get(*k).copied().unwrap_or(line),
                _ => line,
            };
            return Err(AeroError::Parse {
                file: file.to_string(),
                line: at,
                message: e.to_string(),
            });
        }
        config.surfaces.push(surface);
        Ok(())
    }
}
