//! Options and arguments out of range.

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

/// An option or argument out of its valid range: the payload of [`NumError::InvalidOption`](super::NumError::InvalidOption).
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
