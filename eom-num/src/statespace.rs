//! State-space and descriptor model types.
//!
//! [`StateSpace`] is generic over the entry type so that the symbolic pipeline (in `eom-sym`)
//! can produce a `StateSpace<Expr>` with the same shape as the numeric `StateSpace<f64>` that
//! every analysis in this crate works on.

use nalgebra::{DMatrix, Scalar};
use serde::{Deserialize, Serialize};

use crate::{DimensionError, NonFiniteError, NumError};

/// Names (and units) of the signals of a model, carried along so that tables, plots and JSON
/// can say what each row and column is.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SignalNames {
    /// One name per state (length n).
    pub states: Vec<String>,
    /// One name per input (length m).
    pub inputs: Vec<String>,
    /// Units of the inputs (length m, may be empty strings).
    pub input_units: Vec<String>,
    /// One name per output (length p).
    pub outputs: Vec<String>,
    /// Units of the outputs (length p, may be empty strings).
    pub output_units: Vec<String>,
    /// Names of the bodies whose physical coordinates are the rows of
    /// [`StateSpace::phys`]: six rows per body, in the order `x, y, z, rx, ry, rz`
    /// (small global translations of the mass centre, then small global rotations).
    pub bodies: Vec<String>,
}

/// A linear time-invariant model `ẋ = A x + B u`, `y = C x + D u`, with the map back to
/// the physical coordinates of the bodies (`p = phys · x`, six rows per body, see
/// [`SignalNames::bodies`]).
#[derive(Clone, Debug, PartialEq)]
pub struct StateSpace<T: Scalar = f64> {
    /// State matrix, n × n.
    pub a: DMatrix<T>,
    /// Input matrix, n × m.
    pub b: DMatrix<T>,
    /// Output matrix, p × n.
    pub c: DMatrix<T>,
    /// Feedthrough matrix, p × m.
    pub d: DMatrix<T>,
    /// Map from the state to the physical displacements of the bodies, (6·bodies) × n.
    /// May have zero rows when the model has no bodies (e.g. a system built from matrices).
    pub phys: DMatrix<T>,
    /// Names of states, inputs, outputs and bodies.
    pub names: SignalNames,
}

impl<T: Scalar> StateSpace<T> {
    /// Number of states n.
    pub fn states(&self) -> usize {
        self.a.nrows()
    }
    /// Number of inputs m.
    pub fn inputs(&self) -> usize {
        self.b.ncols()
    }
    /// Number of outputs p.
    pub fn outputs(&self) -> usize {
        self.c.nrows()
    }
}

/// A descriptor model `E ẋ = A x + B u`, `y = C x + D u` (E may be singular).
#[derive(Clone, Debug, PartialEq)]
pub struct Descriptor<T: Scalar = f64> {
    /// Descriptor (mass-like) matrix, n × n.
    pub e: DMatrix<T>,
    /// State matrix, n × n.
    pub a: DMatrix<T>,
    /// Input matrix, n × m.
    pub b: DMatrix<T>,
    /// Output matrix, p × n.
    pub c: DMatrix<T>,
    /// Feedthrough matrix, p × m.
    pub d: DMatrix<T>,
}

/// Whether an entry is finite and at most [`crate::MAX_ENTRY`] in magnitude.
pub(crate) fn in_range(x: f64) -> bool {
    x.is_finite() && x.abs() <= crate::MAX_ENTRY
}

/// Checks that every entry of `m` is finite and within [`crate::MAX_ENTRY`]; the error names
/// the matrix and the entry.
pub(crate) fn check_finite(m: &DMatrix<f64>, name: &str) -> Result<(), NumError> {
    check_finite_slice(m.as_slice(), m.nrows(), m.ncols(), name)
}

/// [`check_finite`] of a column-major `nrows × ncols` matrix given as a slice.
pub(crate) fn check_finite_slice(
    m: &[f64],
    nrows: usize,
    ncols: usize,
    name: &str,
) -> Result<(), NumError> {
    if let Some(k) = m.iter().position(|x| !in_range(*x)) {
        let (i, j) = (k % nrows.max(1), k / nrows.max(1));
        let entry = crate::MatrixEntry {
            matrix: name.to_string(),
            row: i,
            col: j,
            value: m[k],
            nrows,
            ncols,
        };
        if m[k].is_finite() {
            return Err(NumError::OutOfRange {
                entry,
                max: crate::MAX_ENTRY,
            });
        }
        return Err(NumError::NonFinite(NonFiniteError::Entry(entry)));
    }
    Ok(())
}

fn check_shape(
    m: &DMatrix<f64>,
    matrix: &'static str,
    rows: usize,
    cols: usize,
    why: &'static str,
) -> Result<(), NumError> {
    if m.nrows() != rows || m.ncols() != cols {
        return Err(NumError::Dimension(DimensionError::Shape {
            matrix,
            rows: m.nrows(),
            cols: m.ncols(),
            expected_rows: rows,
            expected_cols: cols,
            why,
        }));
    }
    Ok(())
}

fn check_names(names: &[String], len: usize, field: &'static str) -> Result<(), NumError> {
    if !names.is_empty() && names.len() != len {
        return Err(NumError::Dimension(DimensionError::NamesLength {
            field,
            len: names.len(),
            expected: len,
        }));
    }
    Ok(())
}

impl StateSpace<f64> {
    /// Builds a validated model from its four matrices, with no physical map (`phys` has zero
    /// rows) and no names.
    ///
    /// Errors: [`NumError::Dimension`] when the shapes do not fit (A n×n, B n×m, C p×n,
    /// D p×m), [`NumError::NonFinite`] when an entry is NaN or infinite.
    pub fn new(
        a: DMatrix<f64>,
        b: DMatrix<f64>,
        c: DMatrix<f64>,
        d: DMatrix<f64>,
    ) -> Result<Self, NumError> {
        let n = a.nrows();
        let ss = StateSpace {
            phys: DMatrix::zeros(0, n),
            a,
            b,
            c,
            d,
            names: SignalNames::default(),
        };
        ss.validate()?;
        Ok(ss)
    }

    /// Replaces the map to physical coordinates (`(6·bodies) × n`), validating its shape.
    pub fn with_phys(mut self, phys: DMatrix<f64>) -> Result<Self, NumError> {
        self.phys = phys;
        self.validate()?;
        Ok(self)
    }

    /// Replaces the signal names, validating their lengths.
    pub fn with_names(mut self, names: SignalNames) -> Result<Self, NumError> {
        self.names = names;
        self.validate()?;
        Ok(self)
    }

    /// Checks shapes, finiteness and name lengths. Every analysis in this crate calls it first,
    /// since the fields are public and may have been filled by hand.
    ///
    /// Name lists may be empty (unnamed) or have exactly one entry per signal;
    /// `names.bodies`, when not empty, must have `phys.nrows() / 6` entries.
    pub fn validate(&self) -> Result<(), NumError> {
        let n = self.a.nrows();
        let m = self.b.ncols();
        let p = self.c.nrows();
        check_shape(&self.a, "A", n, n, "A must be square")?;
        check_shape(&self.b, "B", n, m, "B has one row per state")?;
        check_shape(&self.c, "C", p, n, "C has one column per state")?;
        check_shape(&self.d, "D", p, m, "D is outputs × inputs")?;
        if self.phys.ncols() != n {
            return Err(NumError::Dimension(DimensionError::PhysColumns {
                rows: self.phys.nrows(),
                cols: self.phys.ncols(),
                states: n,
                descriptor: false,
            }));
        }
        check_finite(&self.a, "A")?;
        check_finite(&self.b, "B")?;
        check_finite(&self.c, "C")?;
        check_finite(&self.d, "D")?;
        check_finite(&self.phys, "phys")?;
        check_names(&self.names.states, n, "states")?;
        check_names(&self.names.inputs, m, "inputs")?;
        check_names(&self.names.input_units, m, "input_units")?;
        check_names(&self.names.outputs, p, "outputs")?;
        check_names(&self.names.output_units, p, "output_units")?;
        if !self.names.bodies.is_empty() && self.names.bodies.len() * 6 != self.phys.nrows() {
            return Err(NumError::Dimension(DimensionError::BodyRows {
                bodies: self.names.bodies.len(),
                rows: self.phys.nrows(),
            }));
        }
        Ok(())
    }
}

impl Descriptor<f64> {
    /// Builds a validated descriptor model.
    ///
    /// Errors: [`NumError::Dimension`] when the shapes do not fit (E and A n×n, B n×m, C p×n,
    /// D p×m), [`NumError::NonFinite`] when an entry is NaN or infinite.
    pub fn new(
        e: DMatrix<f64>,
        a: DMatrix<f64>,
        b: DMatrix<f64>,
        c: DMatrix<f64>,
        d: DMatrix<f64>,
    ) -> Result<Self, NumError> {
        let dss = Descriptor { e, a, b, c, d };
        dss.validate()?;
        Ok(dss)
    }

    /// Number of descriptor states n.
    pub fn states(&self) -> usize {
        self.a.nrows()
    }

    /// Checks shapes and finiteness (see [`Descriptor::new`]).
    pub fn validate(&self) -> Result<(), NumError> {
        let n = self.a.nrows();
        let m = self.b.ncols();
        let p = self.c.nrows();
        check_shape(&self.a, "A", n, n, "A must be square")?;
        check_shape(&self.e, "E", n, n, "E has the shape of A")?;
        check_shape(&self.b, "B", n, m, "B has one row per state")?;
        check_shape(&self.c, "C", p, n, "C has one column per state")?;
        check_shape(&self.d, "D", p, m, "D is outputs × inputs")?;
        check_finite(&self.e, "E")?;
        check_finite(&self.a, "A")?;
        check_finite(&self.b, "B")?;
        check_finite(&self.c, "C")?;
        check_finite(&self.d, "D")?;
        Ok(())
    }
}
