//! Sizes that do not fit together.

/// Matrix or vector sizes that do not fit together: the payload of [`NumError::Dimension`](super::NumError::Dimension).
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
