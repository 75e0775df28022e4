//! # eom-num — linear analysis engineers can trust
//!
//! (Narrative crate documentation to be written: modes, frequency response, steady-state gains,
//! minimal realization, transmission zeros, time response, sweeps and stability boundaries.)

#![warn(missing_docs)]

pub mod error;
pub mod statespace;
pub mod linalg;
pub mod descriptor;
pub mod modes;
pub mod freq;
pub mod gain;
pub mod time;
pub mod minreal;
pub mod zeros;
pub mod sweep;

pub use error::NumError;
pub use statespace::{Descriptor, SignalNames, StateSpace};
