//! Memory predicted before large allocations: the analyses that allocate dense matrices of
//! the model's size (n × n eigenvectors, complex workspaces, mode shapes) first compute how
//! many bytes they need and refuse with [`NumError::TooLarge`] when that exceeds the limit,
//! instead of letting the allocator abort the process.
//!
//! The limit is process-wide: [`DEFAULT_LIMIT`] unless [`set_limit`] changed it (the `eom`
//! command reads it from the environment variable `EOM_MEMORY_LIMIT`).

use std::sync::atomic::{AtomicUsize, Ordering};

use crate::NumError;

/// The default limit of one allocation step: 8 GiB.
pub const DEFAULT_LIMIT: usize = 8 << 30;

static LIMIT: AtomicUsize = AtomicUsize::new(DEFAULT_LIMIT);

/// Sets the largest number of bytes one analysis step may allocate (process-wide).
pub fn set_limit(bytes: usize) {
    LIMIT.store(bytes, Ordering::Relaxed);
}

/// The current limit in bytes.
pub fn limit() -> usize {
    LIMIT.load(Ordering::Relaxed)
}

/// Bytes in a human-readable binary unit (`1.5 GiB`).
pub fn format_bytes(bytes: usize) -> String {
    const UNITS: [&str; 5] = ["B", "KiB", "MiB", "GiB", "TiB"];
    let mut v = bytes as f64;
    let mut u = 0;
    while v >= 1024.0 && u + 1 < UNITS.len() {
        v /= 1024.0;
        u += 1;
    }
    if u == 0 {
        format!("{bytes} B")
    } else {
        format!("{v:.1} {}", UNITS[u])
    }
}

/// `Ok` when `bytes` (the predicted size of what `what` allocates) is within the limit,
/// else [`NumError::TooLarge`] naming both.
pub fn check(what: &str, bytes: usize) -> Result<(), NumError> {
    let limit = limit();
    if bytes <= limit {
        return Ok(());
    }
    Err(NumError::TooLarge {
        step: what.to_string(),
        bytes,
        limit,
    })
}

/// `a · b · c` in bytes, saturating (a size that overflows is certainly too large).
pub fn product(factors: &[usize]) -> usize {
    factors.iter().fold(1usize, |acc, &f| acc.saturating_mul(f))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_printed_in_binary_units() {
        assert_eq!(format_bytes(512), "512 B");
        assert_eq!(format_bytes(3 << 29), "1.5 GiB");
        assert_eq!(product(&[usize::MAX, 2]), usize::MAX);
    }

    #[test]
    fn a_step_over_the_limit_is_refused_with_its_numbers() {
        let e = check("eigenvectors", usize::MAX).unwrap_err();
        match &e {
            NumError::TooLarge { step, bytes, limit } => {
                assert_eq!((step.as_str(), *bytes), ("eigenvectors", usize::MAX));
                assert_eq!(*limit, super::limit());
            }
            other => panic!("{other:?}"),
        }
        assert!(check("eigenvectors", 1).is_ok());
    }
}
