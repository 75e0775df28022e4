//! Every built-in model's generated module, in `f64` and `f32`, compiled in this `#![no_std]`
//! crate: the host build of the workspace proves that generated code needs `core` and `libm`
//! only (a cross build for a bare-metal target is `check-thumbv7em.sh`).

include!(concat!(env!("OUT_DIR"), "/check_all.rs"));
