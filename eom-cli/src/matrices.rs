//! Numeric matrices with their row and column names written as a file another tool reads:
//! NumPy's `.npz` (`numpy.load`) or MATLAB's `.mat` (`load` in MATLAB or Octave,
//! `scipy.io.loadmat`), chosen by the file's extension (`eom analyze --matrices FILE`; any
//! command that has named matrices to hand over calls [`write_matrices`]).
//!
//! * `.npz`: a zip archive of one `.npy` array per name (stored, not compressed, as
//!   `numpy.savez` writes it), through the `npyz` and `zip` crates: matrices as 2-D float64
//!   arrays in C order, names as 1-D Unicode string arrays (`<U…`, loaded without pickles).
//! * `.mat`: a MATLAB level-5 MAT-file (the format of MATLAB 5 to 7.2, which MATLAB, Octave
//!   and SciPy read), written here: matrices as `double` arrays, names as column cell arrays of
//!   character rows (UTF-8 data, `miUTF8`). No maintained pure-Rust crate writes this format
//!   to a caller's buffer with its errors reported: `matfile` only reads, `matrw` writes to a
//!   path and discards write errors, `mat5` (one release) writes numeric arrays only. The
//!   format is small: a 128-byte header, then one tagged `miMATRIX` element per variable
//!   (MathWorks, "MAT-File Format", the level-5 chapter).
//!
//! The file is encoded in memory first and written in one go by
//! [`crate::output::write_output`], so a failure never leaves half a file.

use crate::error::CliError;
use crate::output::{self, Written};
use nalgebra::DMatrix;
use std::io::Write;
use std::path::Path;

/// The file formats, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MatrixFormat {
    /// NumPy `.npz`.
    Npz,
    /// MATLAB level-5 `.mat`.
    Mat,
}

/// Named matrices and named lists of names (e.g. `states`, `inputs`) to write together.
#[derive(Clone, Debug, Default)]
pub struct NamedMatrices<'a> {
    /// `(variable name, matrix)`, in the order they are written.
    pub matrices: Vec<(&'a str, &'a DMatrix<f64>)>,
    /// `(variable name, strings)`: each a 1-D string array (`.npz`) or a column cell array of
    /// strings (`.mat`).
    pub names: Vec<(&'a str, &'a [String])>,
}

/// The format of `path` by its extension (`.npz` or `.mat`, any case), checked before any
/// work: another extension is a usage error naming `option`.
pub fn format_of(option: &str, path: &Path) -> Result<MatrixFormat, CliError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    match ext.as_deref() {
        Some("npz") => Ok(MatrixFormat::Npz),
        Some("mat") => Ok(MatrixFormat::Mat),
        _ => Err(CliError::BadArgument {
            argument: format!("{option} {}", path.display()),
            problem: "the matrices are written as NumPy .npz or MATLAB .mat: give a file name \
                      ending in .npz or .mat"
                .into(),
        }),
    }
}

/// Writes the matrices to `path` in the format its extension names.
///
/// Errors: [`CliError::BadArgument`] for another extension or a variable name MATLAB cannot
/// take; [`CliError::Io`] naming the path for every write failure.
pub fn write_matrices(
    option: &str,
    path: &Path,
    m: &NamedMatrices<'_>,
) -> Result<Written, CliError> {
    let bytes = match format_of(option, path)? {
        MatrixFormat::Npz => npz(m),
        MatrixFormat::Mat => mat(m),
    }
    .map_err(|e| match e {
        Encode::Name(name) => CliError::BadArgument {
            argument: format!("{option} {}", path.display()),
            problem: format!("`{name}` is not a valid variable name"),
        },
        Encode::Io(source) => CliError::Io {
            path: path.display().to_string(),
            source,
        },
    })?;
    output::write_output(path, &bytes)
}

/// Why a file could not be encoded.
#[derive(Debug)]
enum Encode {
    /// A variable name the format cannot hold.
    Name(String),
    /// The encoder failed.
    Io(std::io::Error),
}

impl From<std::io::Error> for Encode {
    fn from(e: std::io::Error) -> Self {
        Encode::Io(e)
    }
}

impl From<zip::result::ZipError> for Encode {
    fn from(e: zip::result::ZipError) -> Self {
        Encode::Io(std::io::Error::other(e))
    }
}

/// A MATLAB (and Python) identifier: a letter, then letters, digits and `_`, at most 63.
fn check_name(name: &str) -> Result<(), Encode> {
    let mut chars = name.chars();
    let ok = chars.next().is_some_and(|c| c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && name.len() <= 63;
    if ok {
        Ok(())
    } else {
        Err(Encode::Name(name.to_string()))
    }
}

/// The `.npz` archive in memory.
fn npz(m: &NamedMatrices<'_>) -> Result<Vec<u8>, Encode> {
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let opts = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Stored)
        .large_file(false);
    for &(name, a) in &m.matrices {
        check_name(name)?;
        zip.start_file(format!("{name}.npy"), opts)?;
        zip.write_all(&npy_matrix(a)?)?;
    }
    for &(name, list) in &m.names {
        check_name(name)?;
        zip.start_file(format!("{name}.npy"), opts)?;
        zip.write_all(&npy_strings(list)?)?;
    }
    Ok(zip.finish()?.into_inner())
}

/// A 2-D float64 `.npy` in C order.
fn npy_matrix(a: &DMatrix<f64>) -> Result<Vec<u8>, Encode> {
    use npyz::WriterBuilder;
    let mut out = Vec::new();
    let mut w = npyz::WriteOptions::<f64>::new()
        .default_dtype()
        .shape(&[a.nrows() as u64, a.ncols() as u64])
        .writer(&mut out)
        .begin_nd()?;
    for i in 0..a.nrows() {
        for j in 0..a.ncols() {
            w.push(&a[(i, j)])?;
        }
    }
    w.finish()?;
    Ok(out)
}

/// A 1-D Unicode string `.npy` (`<U` of the longest string, at least 1).
fn npy_strings(list: &[String]) -> Result<Vec<u8>, Encode> {
    use npyz::WriterBuilder;
    let width = list
        .iter()
        .map(|s| s.chars().count())
        .max()
        .unwrap_or(0)
        .max(1);
    let dtype = npyz::DType::Plain(
        format!("<U{width}")
            .parse()
            .map_err(|e| Encode::Io(std::io::Error::other(format!("{e}"))))?,
    );
    let mut out = Vec::new();
    let mut w = npyz::WriteOptions::<str>::new()
        .dtype(dtype)
        .shape(&[list.len() as u64])
        .writer(&mut out)
        .begin_nd()?;
    for s in list {
        w.push(s.as_str())?;
    }
    w.finish()?;
    Ok(out)
}

// MAT-file level 5: data types and array classes (MathWorks, "MAT-File Format").
const MI_INT8: u32 = 1;
const MI_INT32: u32 = 5;
const MI_UINT32: u32 = 6;
const MI_DOUBLE: u32 = 9;
const MI_MATRIX: u32 = 14;
const MI_UTF8: u32 = 16;
const MX_CELL_CLASS: u32 = 1;
const MX_CHAR_CLASS: u32 = 4;
const MX_DOUBLE_CLASS: u32 = 6;

/// The `.mat` file in memory: the header, then one `miMATRIX` element per variable.
fn mat(m: &NamedMatrices<'_>) -> Result<Vec<u8>, Encode> {
    let mut out = Vec::new();
    // 116 bytes of text, 8 bytes of subsystem offset (none), version 0x0100, and the endian
    // indicator: the characters `MI` written as one 16-bit value, which a little-endian
    // writer stores as `IM`.
    let text = format!(
        "MATLAB 5.0 MAT-file, Platform: {}, Created by: eom {}",
        std::env::consts::OS,
        env!("CARGO_PKG_VERSION")
    );
    let mut header = text.into_bytes();
    header.resize(116, b' ');
    out.extend_from_slice(&header);
    out.extend_from_slice(&[0; 8]);
    out.extend_from_slice(&0x0100u16.to_le_bytes());
    out.extend_from_slice(&u16::from_be_bytes(*b"MI").to_le_bytes());
    for &(name, a) in &m.matrices {
        check_name(name)?;
        let data: Vec<u8> = a.as_slice().iter().flat_map(|x| x.to_le_bytes()).collect();
        let body = element(MI_DOUBLE, &data);
        out.extend(matrix(
            MX_DOUBLE_CLASS,
            &[a.nrows(), a.ncols()],
            name,
            &body,
        )?);
    }
    for &(name, list) in &m.names {
        check_name(name)?;
        let mut cells = Vec::new();
        for s in list {
            cells.extend(char_row(s)?);
        }
        out.extend(matrix(MX_CELL_CLASS, &[list.len(), 1], name, &cells)?);
    }
    Ok(out)
}

/// A character row `1 × chars` with UTF-8 data (a cell's element: no name).
fn char_row(s: &str) -> Result<Vec<u8>, Encode> {
    let body = element(MI_UTF8, s.as_bytes());
    matrix(MX_CHAR_CLASS, &[1, s.chars().count()], "", &body)
}

/// An `miMATRIX` element: array flags, dimensions, name, then `body` (the data elements).
fn matrix(class: u32, dims: &[usize], name: &str, body: &[u8]) -> Result<Vec<u8>, Encode> {
    let mut flags = Vec::with_capacity(8);
    flags.extend_from_slice(&class.to_le_bytes());
    flags.extend_from_slice(&0u32.to_le_bytes());
    let mut d = Vec::with_capacity(4 * dims.len());
    for &n in dims {
        let n = i32::try_from(n).map_err(|_| {
            Encode::Io(std::io::Error::other(format!(
                "a dimension of {n} is beyond the MAT-file's 32-bit sizes"
            )))
        })?;
        d.extend_from_slice(&n.to_le_bytes());
    }
    let mut content = element(MI_UINT32, &flags);
    content.extend(element(MI_INT32, &d));
    content.extend(element(MI_INT8, name.as_bytes()));
    content.extend_from_slice(body);
    let len = u32::try_from(content.len()).map_err(|_| {
        Encode::Io(std::io::Error::other(
            "a variable beyond the MAT-file's 32-bit sizes",
        ))
    })?;
    let mut out = Vec::with_capacity(8 + content.len());
    out.extend_from_slice(&MI_MATRIX.to_le_bytes());
    out.extend_from_slice(&len.to_le_bytes());
    out.extend(content);
    Ok(out)
}

/// A data element: an 8-byte tag (type, byte count), the data, zeros to a multiple of 8.
fn element(kind: u32, data: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(16 + data.len());
    out.extend_from_slice(&kind.to_le_bytes());
    out.extend_from_slice(&(data.len() as u32).to_le_bytes());
    out.extend_from_slice(data);
    out.resize(out.len() + (8 - data.len() % 8) % 8, 0);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_extension_chooses_the_format() {
        let f = |p: &str| format_of("--matrices", Path::new(p));
        assert_eq!(f("a.npz").unwrap(), MatrixFormat::Npz);
        assert_eq!(f("dir/a.MAT").unwrap(), MatrixFormat::Mat);
        let e = f("a.csv").unwrap_err();
        assert!(e.to_string().contains("--matrices a.csv"), "{e}");
        assert_eq!(e.exit_code(), crate::error::EXIT_USAGE);
    }

    #[test]
    fn mat_elements_are_padded_to_eight_bytes() {
        assert_eq!(element(MI_INT8, b"A").len(), 16);
        assert_eq!(element(MI_INT8, b"").len(), 8);
        assert_eq!(element(MI_INT8, b"abcdefgh").len(), 16);
        let a = DMatrix::from_row_slice(2, 1, &[1.0, 2.0]);
        let m = NamedMatrices {
            matrices: vec![("A", &a)],
            names: Vec::new(),
        };
        let bytes = mat(&m).unwrap();
        assert_eq!(&bytes[124..128], &[0x00, 0x01, b'I', b'M']);
        assert_eq!(bytes.len() % 8, 0);
        assert!(check_name("1x").is_err() && check_name("x_1").is_ok());
    }
}
