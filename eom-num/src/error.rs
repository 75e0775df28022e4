//! The error type of eom-num.

/// Everything that can go wrong in a numeric analysis. Messages name the matrix, signal or
/// parameter at fault.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum NumError {
    /// Matrix dimensions do not fit together (names the matrices, gives the sizes).
    #[error("dimension mismatch: {0}")]
    Dimension(DimensionError),
    /// A matrix, vector or point contains NaN or infinite entries (names it, and the entry
    /// where known).
    #[error("non-finite entry in {0}")]
    NonFinite(NonFiniteError),
    /// A matrix entry so large (beyond `max`, [`crate::MAX_ENTRY`]) that the products inside
    /// the factorisations would overflow.
    #[error(
        "entry too large: {entry}: larger in magnitude than {max:e}, beyond which the products \
         inside the factorisations overflow (express the model in other units)"
    )]
    OutOfRange {
        /// The entry.
        entry: MatrixEntry,
        /// The largest magnitude accepted.
        max: f64,
    },
    /// An option or argument is out of its valid range (names the option, gives the value).
    #[error("invalid option: {0}")]
    InvalidOption(OptionError),
    /// An iterative factorisation (eigenvalues, SVD, QZ) did not converge (names the step and
    /// the size).
    #[error("no convergence: {0}")]
    NoConvergence(ConvergenceError),
    /// A matrix that must be inverted is singular to working precision (names the matrix and
    /// gives the decision margin).
    #[error("singular matrix: {0}")]
    Singular(SingularError),
    /// The descriptor pencil `s E − A` is singular (det(sE − A) ≡ 0): the model does not
    /// determine its own motion.
    #[error("singular pencil: {0}")]
    SingularPencil(String),
    /// The descriptor pencil is regular but has index > 1 (the algebraic block A22 is
    /// singular); only index-1 pencils are reduced.
    #[error("descriptor index > 1: {0}")]
    HigherIndex(String),
    /// A rank decision that the result depends on lies so close to its tolerance that another
    /// admissible tolerance gives a different answer (the message gives both): the result
    /// cannot be trusted either way.
    #[error("ambiguous rank decision: {0}")]
    AmbiguousRank(String),
    /// The analysis would need more memory than the limit ([`crate::budget`]); the message
    /// names the step, the predicted size, the limit and how to raise it.
    #[error(
        "too large: {step} would need about {} of memory, more than the limit of {} (raise it \
         with the environment variable EOM_MEMORY_LIMIT, e.g. EOM_MEMORY_LIMIT=32G)",
        crate::budget::format_bytes(*bytes),
        crate::budget::format_bytes(*limit)
    )]
    TooLarge {
        /// The step that would allocate (`eigenvectors of a 40000×40000 matrix`).
        step: String,
        /// The predicted size in bytes.
        bytes: usize,
        /// The limit in bytes.
        limit: usize,
    },
}

/// An entry of a matrix, as an error names it: `A[1, 0] = 1e300 (3×3 matrix)`.
#[derive(Clone, Debug, PartialEq)]
pub struct MatrixEntry {
    /// The matrix's name.
    pub matrix: String,
    /// Row index (from 0).
    pub row: usize,
    /// Column index (from 0).
    pub col: usize,
    /// The value found there.
    pub value: f64,
    /// Rows of the matrix.
    pub nrows: usize,
    /// Columns of the matrix.
    pub ncols: usize,
}

impl std::fmt::Display for MatrixEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}[{}, {}] = {:?} ({}×{} matrix)",
            self.matrix, self.row, self.col, self.value, self.nrows, self.ncols
        )
    }
}

/// What must hold of an option's value, as an error says it: `must be finite and ≥ 0`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Bound {
    /// Finite and not negative.
    FiniteNonNegative,
    /// Finite and positive.
    FinitePositive,
    /// Positive (infinity allowed).
    Positive,
    /// At least one (a count).
    AtLeastOne,
    /// An integer in `low..=high`.
    Between(usize, usize),
}

impl std::fmt::Display for Bound {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Bound::FiniteNonNegative => write!(f, "finite and ≥ 0"),
            Bound::FinitePositive => write!(f, "finite and > 0"),
            Bound::Positive => write!(f, "> 0"),
            Bound::AtLeastOne => write!(f, "≥ 1"),
            Bound::Between(low, high) => write!(f, "in {low}..={high}"),
        }
    }
}

/// An option or argument out of its valid range: the payload of [`NumError::InvalidOption`].
/// Each case names the option (as the Rust API spells it) and carries the values at fault.
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum OptionError {
    /// A tolerance out of range: `MinrealOptions.rtol = -1 (must be finite and ≥ 0)`.
    #[error("{option} = {value} (must be {must})")]
    Tolerance {
        /// The option (`MinrealOptions.rtol`, `sweep tolerance`).
        option: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        must: Bound,
    },
    /// A setting out of range: `ModeOptions::tol_factor = 0: must be finite and > 0`.
    #[error("{option} = {value}: must be {must}")]
    Value {
        /// The option (`ModeOptions::tol_factor`, `time step dt`).
        option: &'static str,
        /// The value given (a count as a float: it prints the same).
        value: f64,
        /// What it must be.
        must: Bound,
    },
    /// A time response's size limit out of range: `SizeLimit::Relative(-1): must be …`.
    #[error("SizeLimit::{kind}({value}): must be {must}")]
    SizeLimit {
        /// `Relative` or `Absolute`.
        kind: &'static str,
        /// The value given.
        value: f64,
        /// What it must be.
        must: Bound,
    },
    /// An explicit rank tolerance that is negative or not finite.
    #[error("rank tolerance {tolerance:?}: must be finite and ≥ 0")]
    RankTolerance {
        /// The tolerance given.
        tolerance: crate::linalg::RankTolerance,
    },
    /// A model reduction's error tolerance that is not finite and positive.
    #[error("tolerance {tolerance}: must be finite and > 0")]
    ReductionTolerance {
        /// The tolerance given.
        tolerance: f64,
    },
    /// A frequency grid with more points than [`crate::freq::MAX_POINTS`].
    #[error(
        "frequency grid of {points:.3e} points ({decades:.1} decades at {per_decade} per \
         decade) exceeds the limit of {limit}"
    )]
    FrequencyGridTooLarge {
        /// The points the grid would have.
        points: f64,
        /// The decades it spans.
        decades: f64,
        /// Points per decade asked for.
        per_decade: usize,
        /// The most points allowed.
        limit: usize,
    },
    /// A listed frequency that is negative or not finite.
    #[error("FreqRange::Points contains {value}: frequencies must be finite and ≥ 0")]
    FrequencyPoint {
        /// The frequency at fault.
        value: f64,
    },
    /// A frequency range that is not `0 < low < high`, finite.
    #[error("FreqRange::Range {{ low: {low}, high: {high} }}: need 0 < low < high, finite")]
    FrequencyRange {
        /// The lower end given.
        low: f64,
        /// The upper end given.
        high: f64,
    },
    /// A given time horizon with more samples than [`crate::time::MAX_SAMPLES`].
    #[error(
        "Horizon::Given t_end = {t_end}, dt = {dt}: {samples:.3e} samples exceed the limit of \
         {limit}"
    )]
    TooManySamples {
        /// The end time given.
        t_end: f64,
        /// The time step given.
        dt: f64,
        /// The samples that would take.
        samples: f64,
        /// The most samples allowed.
        limit: usize,
    },
    /// A sweep without values.
    #[error("sweep of {param} has no values")]
    EmptySweep {
        /// The swept parameter.
        param: String,
    },
    /// A sweep value that is not finite.
    #[error("sweep value {index} of {param} is {value}")]
    SweepValue {
        /// The swept parameter.
        param: String,
        /// The value's index (from 0).
        index: usize,
        /// The value.
        value: f64,
    },
    /// Sweep values that are not strictly monotone.
    #[error(
        "sweep values of {param} must be strictly monotone (values {index} and {}: {} and {})",
        index + 1,
        values[0],
        values[1]
    )]
    SweepNotMonotone {
        /// The swept parameter.
        param: String,
        /// The index (from 0) of the first of the two values out of order.
        index: usize,
        /// The two values.
        values: [f64; 2],
    },
    /// A sweep allowed no evaluations.
    #[error("sweep max_evaluations must be ≥ 1")]
    SweepMaxEvaluations,
    /// A Lyapunov equation whose state matrix has a diagonal block that is not stable.
    #[error(
        "Lyapunov equation: the diagonal block at {block} has an eigenvalue with real part \
         {real_part:e}, not in the open left half-plane"
    )]
    UnstableLyapunovBlock {
        /// The block's first row (from 0).
        block: usize,
        /// The real part of its eigenvalue.
        real_part: f64,
    },
    /// A frequency band given to balanced truncation.
    #[error("a frequency band chooses the modes of modal truncation: use the modal method")]
    BandNeedsModal,
    /// A frequency band that is not `0 ≤ low ≤ high`, finite.
    #[error("band {low}:{high} Hz: needs 0 ≤ low ≤ high, both finite")]
    Band {
        /// The lower end (Hz).
        low: f64,
        /// The upper end (Hz).
        high: f64,
    },
    /// Modal truncation given both a band and an order.
    #[error("modal truncation takes a band or an order, not both")]
    BandAndOrder,
    /// Modal truncation given an error tolerance.
    #[error(
        "modal truncation has no a-priori error bound to meet a tolerance: give an order or a \
         band"
    )]
    ModalTolerance,
    /// Modal truncation given neither an order nor a band.
    #[error("modal truncation needs an order or a frequency band")]
    ModalWithoutOrder,
    /// A reduced order below the states that are kept whole.
    #[error(
        "order {order}: the model has {kept} states that are kept whole (zero, marginal or \
         unstable modes), so at least {kept}"
    )]
    OrderBelowKept {
        /// The order asked for.
        order: usize,
        /// The states kept whole (zero, marginal or unstable modes).
        kept: usize,
    },
    /// A balanced order above the states that balanced truncation can keep.
    #[error(
        "order {order}: at most {} ({kept} kept whole and {reducible} stable states above \
         rounding{})",
        kept + reducible,
        hidden_note(*hidden)
    )]
    OrderAboveReducible {
        /// The order asked for.
        order: usize,
        /// The states kept whole.
        kept: usize,
        /// The stable states with Hankel singular values above rounding.
        reducible: usize,
        /// The stable states that are uncontrollable or unobservable.
        hidden: usize,
    },
    /// A modal order outside `kept..=all`.
    #[error("order {order}: between {kept} (the states kept whole) and {all} (all)")]
    ModalOrder {
        /// The order asked for.
        order: usize,
        /// The states kept whole.
        kept: usize,
        /// All states.
        all: usize,
    },
    /// A modal order that would split a complex pair or modes of equal frequency.
    #[error(
        "order {order} would split the modes at {hz:.6} Hz (a complex pair or equal \
         frequencies): use {} or {}",
        order.saturating_sub(1),
        order + 1
    )]
    OrderSplitsModes {
        /// The order asked for.
        order: usize,
        /// The frequency of the modes it would split (Hz).
        hz: f64,
    },
}

/// The note on hidden states in [`OptionError::OrderAboveReducible`].
fn hidden_note(hidden: usize) -> String {
    if hidden > 0 {
        format!("; {hidden} are uncontrollable or unobservable")
    } else {
        String::new()
    }
}

/// Matrix or vector sizes that do not fit together: the payload of [`NumError::Dimension`].
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum DimensionError {
    /// A model matrix of the wrong shape: `B is 3×1, expected 2×1 (B has one row per state)`.
    #[error("{matrix} is {rows}×{cols}, expected {expected_rows}×{expected_cols} ({why})")]
    Shape {
        /// The matrix (`A`, `B`, `C`, `D`, `E`).
        matrix: &'static str,
        /// Its rows.
        rows: usize,
        /// Its columns.
        cols: usize,
        /// The rows expected.
        expected_rows: usize,
        /// The columns expected.
        expected_cols: usize,
        /// The rule it breaks.
        why: &'static str,
    },
    /// A matrix that must be square is not.
    #[error("{matrix} is {rows}×{cols}, expected a square matrix")]
    NotSquare {
        /// The matrix.
        matrix: &'static str,
        /// Its rows.
        rows: usize,
        /// Its columns.
        cols: usize,
    },
    /// B's rows or C's columns are not one per state.
    #[error("{matrix} has {len} {axis}, expected {states} (one per state)")]
    PerState {
        /// The matrix (`B` or `C`).
        matrix: &'static str,
        /// `rows` or `columns`.
        axis: &'static str,
        /// How many it has.
        len: usize,
        /// The states.
        states: usize,
    },
    /// A list of signal names whose length is not that of the signals.
    #[error("names.{field} has {len} entries, expected {expected} (or none)")]
    NamesLength {
        /// The field of [`crate::SignalNames`] (`inputs`).
        field: &'static str,
        /// Its entries.
        len: usize,
        /// The signals.
        expected: usize,
    },
    /// A physical map whose columns are not one per state.
    #[error(
        "phys is {rows}×{cols}, expected one column per {}state ({states})",
        if *descriptor { "descriptor " } else { "" }
    )]
    PhysColumns {
        /// Its rows.
        rows: usize,
        /// Its columns.
        cols: usize,
        /// The states.
        states: usize,
        /// Whether the states are a descriptor model's.
        descriptor: bool,
    },
    /// Body names that are not one per six rows of the physical map.
    #[error("names.bodies has {bodies} entries but phys has {rows} rows (six per body expected)")]
    BodyRows {
        /// The body names.
        bodies: usize,
        /// The rows of `phys`.
        rows: usize,
    },
    /// Input samples whose rows are not one per input.
    #[error("input samples u have {rows} rows, expected one per input ({inputs})")]
    InputSamples {
        /// Rows of `u`.
        rows: usize,
        /// The model's inputs.
        inputs: usize,
    },
    /// An initial state whose length is not the states'.
    #[error("x0 has length {len}, expected one entry per state ({states})")]
    InitialState {
        /// Its length.
        len: usize,
        /// The model's states.
        states: usize,
    },
    /// The arguments of [`crate::small_eigen::eigenvalues_small`] do not fit.
    #[error(
        "eigenvalues_small: a {n}×{n} matrix (at most {max}×{max}) given {entries} entries and \
         an output of length {out}"
    )]
    SmallEigen {
        /// The order given.
        n: usize,
        /// The largest order accepted.
        max: usize,
        /// The entries given.
        entries: usize,
        /// The output's length.
        out: usize,
    },
    /// Structural zeros found on a matrix of another order.
    #[error(
        "eigenvalues_small_known: a {n}×{n} matrix, structural zeros found on a {known}×{known} \
         one"
    )]
    KnownZeros {
        /// The order given.
        n: usize,
        /// The order the zeros were found on.
        known: usize,
    },
    /// A swept model whose order changes along the sweep.
    #[error("A is {states}×{states} here but {first}×{first} at {param} = {value}")]
    SweepOrder {
        /// The order here.
        states: usize,
        /// The order at the first value.
        first: usize,
        /// The swept parameter.
        param: String,
        /// Its first value.
        value: f64,
    },
    /// A swept model whose order is not the sweep grid's.
    #[error("A is {states}×{states} here but {grid}×{grid} on the sweep grid")]
    SweepGrid {
        /// The order here.
        states: usize,
        /// The order on the grid.
        grid: usize,
    },
    /// A frequency-response workspace or output made for another model.
    #[error(
        "{function}: model has n = {n}, m = {m}, p = {p}; workspace is for n = {workspace_n}, \
         m = {workspace_m}; output has length {out} (expected {expected})"
    )]
    FreqWorkspace {
        /// The function called (`evaluate_in`).
        function: &'static str,
        /// The model's states.
        n: usize,
        /// Its inputs.
        m: usize,
        /// Its outputs.
        p: usize,
        /// The states the workspace is for.
        workspace_n: usize,
        /// The inputs the workspace is for.
        workspace_m: usize,
        /// The output's length.
        out: usize,
        /// The length expected.
        expected: usize,
    },
    /// An eigenvalue workspace or output made for another order.
    #[error(
        "eigenvalues_in: A is {rows}×{cols}, workspace is for {workspace}×{workspace}, output \
         has length {out}"
    )]
    EigenWorkspace {
        /// A's rows.
        rows: usize,
        /// A's columns.
        cols: usize,
        /// The order the workspace is for.
        workspace: usize,
        /// The output's length.
        out: usize,
    },
    /// A parameter derivative of A of another shape than A.
    #[error("∂A/∂p of parameter {parameter} is {rows}×{cols}, A is {a_rows}×{a_cols}")]
    Derivative {
        /// The parameter's index (from 0).
        parameter: usize,
        /// The derivative's rows.
        rows: usize,
        /// Its columns.
        cols: usize,
        /// A's rows.
        a_rows: usize,
        /// A's columns.
        a_cols: usize,
    },
    /// Response states whose rows are not the model's states.
    #[error("the states have {rows} rows, the model {states} states")]
    ResponseStates {
        /// Rows given.
        rows: usize,
        /// The model's states.
        states: usize,
    },
    /// Response inputs whose shape is not inputs × samples.
    #[error("the inputs are {rows}×{cols}, expected {expected_rows}×{expected_cols}")]
    ResponseInputs {
        /// Rows given.
        rows: usize,
        /// Columns given.
        cols: usize,
        /// The model's inputs.
        expected_rows: usize,
        /// The samples of the states.
        expected_cols: usize,
    },
}

/// An iterative factorisation that did not converge: the payload of
/// [`NumError::NoConvergence`].
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum ConvergenceError {
    /// A factorisation of a whole matrix or pencil: `SVD of a 3×4 matrix`.
    #[error("{step} of a {rows}×{cols} {object}")]
    Factorisation {
        /// The factorisation (`SVD`, `singular values`, `eigenvalues`, `QZ`).
        step: &'static str,
        /// Rows.
        rows: usize,
        /// Columns.
        cols: usize,
        /// `matrix` or `pencil`.
        object: &'static str,
    },
    /// The QR iteration of the small-matrix eigenvalue solver.
    #[error("eigenvalues of a {n}×{n} matrix: the QR iteration did not converge")]
    QrIteration {
        /// The order.
        n: usize,
    },
    /// The SVD of a block of the staircase form (`detail`: the SVD's own report).
    #[error("SVD of a {rows}×{cols} block: {detail}")]
    BlockSvd {
        /// Rows of the block.
        rows: usize,
        /// Columns of the block.
        cols: usize,
        /// The factorisation's own report.
        detail: String,
    },
    /// A step of a PBH test at an eigenvalue.
    #[error("{step} at λ = {lambda}{}", detail_suffix(detail))]
    AtEigenvalue {
        /// The step (`PBH SVD`, `inverse iteration of the PBH test`).
        step: &'static str,
        /// The eigenvalue.
        lambda: num_complex::Complex64,
        /// The factorisation's own report, if it gave one.
        detail: Option<String>,
    },
    /// The QR iteration of the real Schur form of the state matrix.
    #[error("the real Schur form of the {n}×{n} state matrix (QR iteration)")]
    Schur {
        /// The order.
        n: usize,
    },
    /// Two diagonal blocks of a real Schur form too close to swap.
    #[error(
        "reordering the real Schur form: swapping the blocks of {first:?} and {second:?} would \
         perturb them by {perturbation:.3e} relative to {scale:.3e} (eigenvalues too close to \
         separate)"
    )]
    SchurSwap {
        /// The eigenvalues of the first block.
        first: Vec<num_complex::Complex64>,
        /// The eigenvalues of the second block.
        second: Vec<num_complex::Complex64>,
        /// The size of the swap's residual.
        perturbation: f64,
        /// The blocks' norm.
        scale: f64,
    },
    /// The QZ iteration of the reduced zero pencil.
    #[error("QZ of the {n}×{n} reduced zero pencil: {detail}")]
    ZeroPencilQz {
        /// The pencil's order.
        n: usize,
        /// The factorisation's own report.
        detail: String,
    },
}

/// `: detail` where a factorisation gave its own report.
fn detail_suffix(detail: &Option<String>) -> String {
    detail.as_ref().map(|d| format!(": {d}")).unwrap_or_default()
}

/// A matrix that must be inverted but is singular to working precision: the payload of
/// [`NumError::Singular`].
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum SingularError {
    /// A matrix that passed its rank test but whose LU factorisation or solve then failed:
    /// `A22 (3×3) passed the rank test but its LU factorisation broke down`.
    #[error("{matrix} ({n}×{n}) {passed} but its LU {failed}")]
    LuFailed {
        /// The matrix (`A`, `E`, `A22`, `E11`).
        matrix: &'static str,
        /// Its order.
        n: usize,
        /// The test it passed (`passed the rank test`, `has full numerical rank`).
        passed: &'static str,
        /// What then failed (`factorisation broke down`, `solve is not finite`).
        failed: &'static str,
    },
    /// `sI − A` at a point that is numerically an eigenvalue of A.
    #[error("sI − A at s = {s} ({n}×{n} model): s is numerically an eigenvalue of A")]
    Eigenvalue {
        /// The point.
        s: num_complex::Complex64,
        /// The model's states.
        n: usize,
    },
    /// A 2×2 diagonal block of a Gramian's Cholesky factor that is singular.
    #[error(
        "Lyapunov equation: the Gramian's 2×2 diagonal block at {block} is singular though its \
         output is not zero"
    )]
    GramianBlock {
        /// The block's first row (from 0).
        block: usize,
    },
    /// The block A₂₂ that singular perturbation inverts.
    #[error("the residualised block A₂₂ of the balanced realization")]
    Residualised,
    /// The error system of a model reduction with a pole on the imaginary axis.
    #[error("the error system at ω = {omega} rad/s: a pole on the imaginary axis")]
    ErrorSystemPole {
        /// The frequency (rad/s).
        omega: f64,
    },
    /// The reduced feedthrough of the zero pencil is not square.
    #[error("reduced feedthrough of the zero pencil is {rows}×{cols} instead of square")]
    FeedthroughNotSquare {
        /// Its rows.
        rows: usize,
        /// Its columns.
        cols: usize,
    },
    /// `[C D]` of the reduced zero pencil without full row rank.
    #[error("[C D] of the reduced zero pencil has numerical rank {rank} < {rows}")]
    ZeroPencilRank {
        /// The numerical rank.
        rank: usize,
        /// The rows.
        rows: usize,
    },
    /// The zero pencil's `B_f` passed the conditioning test but its LU solve is not finite.
    #[error(
        "the {n}×{n} zero pencil: B_f passed the conditioning test but its LU solve is not \
         finite"
    )]
    ZeroPencilSolve {
        /// The pencil's order.
        n: usize,
    },
    /// A singular A whose zero-eigenvalue subspace the right and left chains disagree on.
    #[error(
        "A ({n}×{n}) is singular but its zero-eigenvalue subspace is ill-determined: the right \
         chain gives dimension {right} (index {right_index}), the left chain {left} (index \
         {left_index})"
    )]
    ZeroSubspace {
        /// A's order.
        n: usize,
        /// The dimension from the right chain.
        right: usize,
        /// Its index.
        right_index: usize,
        /// The dimension from the left chain.
        left: usize,
        /// Its index.
        left_index: usize,
    },
    /// The basis of the zero/nonzero eigenvalue split of A.
    #[error("the basis [V₀ V₁] of the zero/nonzero eigenvalue split of A ({n}×{n}) is singular")]
    SplitBasis {
        /// A's order.
        n: usize,
    },
    /// A restricted to its nonzero modes.
    #[error("A restricted to its nonzero modes ({n}×{n}) is singular")]
    NonzeroModes {
        /// The restriction's order.
        n: usize,
    },
    /// `A − λI` near an eigenvalue, in inverse iteration.
    #[error("A − λI near λ = {lambda}")]
    Shifted {
        /// The eigenvalue.
        lambda: num_complex::Complex64,
    },
    /// Inverse iteration that gave no vector.
    #[error("inverse iteration for λ = {lambda} did not give a vector")]
    InverseIteration {
        /// The eigenvalue.
        lambda: num_complex::Complex64,
    },
}

/// What holds a NaN or infinite value: the payload of [`NumError::NonFinite`].
#[derive(Debug, thiserror::Error, Clone, PartialEq)]
#[non_exhaustive]
pub enum NonFiniteError {
    /// An entry of a matrix: `A[1, 0] = NaN (3×3 matrix)`.
    #[error("{0}")]
    Entry(MatrixEntry),
    /// A matrix (entry not located).
    #[error("{matrix}")]
    Matrix {
        /// The matrix (`A`, `B`, `C`).
        matrix: &'static str,
    },
    /// A point at which a frequency response is evaluated.
    #[error("evaluation point s = {s}")]
    EvaluationPoint {
        /// The point.
        s: num_complex::Complex64,
    },
    /// A simulation's initial state.
    #[error("initial state x0")]
    InitialState,
    /// An eigenvalue whose mode shape is asked for.
    #[error("eigenvalue {lambda}")]
    Eigenvalue {
        /// The eigenvalue.
        lambda: num_complex::Complex64,
    },
}

#[cfg(test)]
mod tests {
    use super::{
        Bound, ConvergenceError, DimensionError, MatrixEntry, NonFiniteError, NumError, OptionError,
        SingularError,
    };
    use num_complex::Complex64;
    use crate::linalg::RankTolerance;

    fn text(e: OptionError) -> String {
        NumError::InvalidOption(e).to_string()
    }

    /// The typed option errors print the messages the string ones did (the old format
    /// strings, copied here, are the reference).
    #[test]
    fn option_errors_print_the_former_messages() {
        let (r, t, f) = (-1.5, f64::NAN, 0.0);
        assert_eq!(
            text(OptionError::Tolerance {
                option: "MinrealOptions.rtol",
                value: r,
                must: Bound::FiniteNonNegative
            }),
            format!("invalid option: MinrealOptions.rtol = {r} (must be finite and ≥ 0)")
        );
        assert_eq!(
            text(OptionError::Value {
                option: "ModeOptions::tol_factor",
                value: f,
                must: Bound::FinitePositive
            }),
            format!("invalid option: ModeOptions::tol_factor = {f}: must be finite and > 0")
        );
        assert_eq!(
            text(OptionError::Value {
                option: "TimeOptions::max_steps",
                value: 1.0,
                must: Bound::Between(2, 50_000_000)
            }),
            "invalid option: TimeOptions::max_steps = 1: must be in 2..=50000000"
        );
        assert_eq!(
            text(OptionError::SizeLimit {
                kind: "Absolute",
                value: f,
                must: Bound::Positive
            }),
            format!("invalid option: SizeLimit::Absolute({f}): must be > 0")
        );
        let tol = RankTolerance::Relative(t);
        assert_eq!(
            text(OptionError::RankTolerance { tolerance: tol }),
            format!("invalid option: rank tolerance {tol:?}: must be finite and ≥ 0")
        );
        let (steps, decades, ppd) = (1.234e10, 4.56, 1_000_000_000usize);
        assert_eq!(
            text(OptionError::FrequencyGridTooLarge {
                points: steps,
                decades,
                per_decade: ppd,
                limit: 10_000_000
            }),
            format!(
                "invalid option: frequency grid of {steps:.3e} points ({decades:.1} decades at \
                 {ppd} per decade) exceeds the limit of 10000000"
            )
        );
        let (low, high) = (2.0, 1.0);
        assert_eq!(
            text(OptionError::FrequencyRange { low, high }),
            format!(
                "invalid option: FreqRange::Range {{ low: {low}, high: {high} }}: need 0 < low \
                 < high, finite"
            )
        );
        assert_eq!(
            text(OptionError::SweepNotMonotone {
                param: "v".into(),
                index: 3,
                values: [2.0, 1.5]
            }),
            "invalid option: sweep values of v must be strictly monotone (values 3 and 4: 2 and \
             1.5)"
        );
        let lam_re = 0.25;
        assert_eq!(
            text(OptionError::UnstableLyapunovBlock {
                block: 2,
                real_part: lam_re
            }),
            format!(
                "invalid option: Lyapunov equation: the diagonal block at 2 has an eigenvalue \
                 with real part {lam_re:e}, not in the open left half-plane"
            )
        );
        for (hidden, note) in [(0, ""), (2, "; 2 are uncontrollable or unobservable")] {
            assert_eq!(
                text(OptionError::OrderAboveReducible {
                    order: 9,
                    kept: 2,
                    reducible: 5,
                    hidden
                }),
                format!(
                    "invalid option: order 9: at most 7 (2 kept whole and 5 stable states above \
                     rounding{note})"
                )
            );
        }
        let hz = 1.0 / 3.0;
        assert_eq!(
            text(OptionError::OrderSplitsModes { order: 4, hz }),
            format!(
                "invalid option: order 4 would split the modes at {hz:.6} Hz (a complex pair or \
                 equal frequencies): use 3 or 5"
            )
        );
    }

    /// The typed dimension errors print the messages the string ones did.
    #[test]
    fn dimension_errors_print_the_former_messages() {
        let text = |e: DimensionError| NumError::Dimension(e).to_string();
        assert_eq!(
            text(DimensionError::Shape {
                matrix: "B",
                rows: 3,
                cols: 1,
                expected_rows: 2,
                expected_cols: 1,
                why: "B has one row per state"
            }),
            "dimension mismatch: B is 3×1, expected 2×1 (B has one row per state)"
        );
        assert_eq!(
            text(DimensionError::PhysColumns {
                rows: 6,
                cols: 3,
                states: 2,
                descriptor: true
            }),
            "dimension mismatch: phys is 6×3, expected one column per descriptor state (2)"
        );
        assert_eq!(
            text(DimensionError::PhysColumns {
                rows: 6,
                cols: 3,
                states: 2,
                descriptor: false
            }),
            "dimension mismatch: phys is 6×3, expected one column per state (2)"
        );
        assert_eq!(
            text(DimensionError::FreqWorkspace {
                function: "evaluate_in",
                n: 3,
                m: 1,
                p: 2,
                workspace_n: 3,
                workspace_m: 1,
                out: 0,
                expected: 2
            }),
            "dimension mismatch: evaluate_in: model has n = 3, m = 1, p = 2; workspace is for \
             n = 3, m = 1; output has length 0 (expected 2)"
        );
        assert_eq!(
            text(DimensionError::SweepOrder {
                states: 4,
                first: 2,
                param: "v".into(),
                value: 1.5
            }),
            "dimension mismatch: A is 4×4 here but 2×2 at v = 1.5"
        );
    }

    /// The typed convergence errors print the messages the string ones did.
    #[test]
    fn convergence_errors_print_the_former_messages() {
        let text = |e: ConvergenceError| NumError::NoConvergence(e).to_string();
        let (r, c, lam) = (3, 4, Complex64::new(-1.0, 2.0));
        assert_eq!(
            text(ConvergenceError::Factorisation {
                step: "singular values",
                rows: r,
                cols: c,
                object: "matrix"
            }),
            format!("no convergence: singular values of a {r}×{c} matrix")
        );
        assert_eq!(
            text(ConvergenceError::AtEigenvalue {
                step: "PBH SVD",
                lambda: lam,
                detail: Some("NoConvergence".into())
            }),
            format!("no convergence: PBH SVD at λ = {lam}: NoConvergence")
        );
        assert_eq!(
            text(ConvergenceError::AtEigenvalue {
                step: "inverse iteration of the PBH test",
                lambda: lam,
                detail: None
            }),
            format!("no convergence: inverse iteration of the PBH test at λ = {lam}")
        );
        let (first, second) = (vec![lam, lam.conj()], vec![Complex64::new(-1.0, 0.0)]);
        let (below, scale) = (1e-9, 2.5);
        assert_eq!(
            text(ConvergenceError::SchurSwap {
                first: first.clone(),
                second: second.clone(),
                perturbation: below,
                scale
            }),
            format!(
                "no convergence: reordering the real Schur form: swapping the blocks of \
                 {first:?} and {second:?} would perturb them by {below:.3e} relative to \
                 {scale:.3e} (eigenvalues too close to separate)"
            )
        );
    }

    /// The typed singular-matrix errors print the messages the string ones did.
    #[test]
    fn singular_errors_print_the_former_messages() {
        let text = |e: SingularError| NumError::Singular(e).to_string();
        let k = 3;
        assert_eq!(
            text(SingularError::LuFailed {
                matrix: "A22",
                n: k,
                passed: "passed the rank test",
                failed: "factorisation broke down"
            }),
            format!(
                "singular matrix: A22 ({k}×{k}) passed the rank test but its LU factorisation \
                 broke down"
            )
        );
        let s = Complex64::new(0.0, 2.0);
        assert_eq!(
            text(SingularError::Eigenvalue { s, n: 2 }),
            format!("singular matrix: sI − A at s = {s} (2×2 model): s is numerically an eigenvalue of A")
        );
        assert_eq!(
            text(SingularError::ZeroSubspace {
                n: 4,
                right: 2,
                right_index: 1,
                left: 1,
                left_index: 1
            }),
            "singular matrix: A (4×4) is singular but its zero-eigenvalue subspace is \
             ill-determined: the right chain gives dimension 2 (index 1), the left chain 1 \
             (index 1)"
        );
    }

    /// The typed non-finite errors print the messages the string ones did.
    #[test]
    fn non_finite_errors_print_the_former_messages() {
        let text = |e: NonFiniteError| NumError::NonFinite(e).to_string();
        let entry = MatrixEntry {
            matrix: "A".into(),
            row: 1,
            col: 0,
            value: f64::NAN,
            nrows: 3,
            ncols: 3,
        };
        assert_eq!(
            text(NonFiniteError::Entry(entry.clone())),
            format!("non-finite entry in {entry}")
        );
        assert_eq!(
            text(NonFiniteError::Entry(entry)),
            "non-finite entry in A[1, 0] = NaN (3×3 matrix)"
        );
        let s = Complex64::new(f64::NAN, 1.0);
        assert_eq!(
            text(NonFiniteError::EvaluationPoint { s }),
            format!("non-finite entry in evaluation point s = {s}")
        );
        assert_eq!(
            text(NonFiniteError::Matrix { matrix: "B" }),
            "non-finite entry in B"
        );
    }
}
