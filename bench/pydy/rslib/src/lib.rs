#![allow(warnings)]
// eom-codegen's modules for the bicycle and the shimmy (written by build.sh), called from C.
include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../bicycle_f64.rs"));
include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../shimmy_f64.rs"));
include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../bicycle_simplified_f64.rs"));
include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../shimmy_simplified_f64.rs"));

mod anatomy;

include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../wrap.rs"));

wrap!(bicycle_rs, bicycle);
wrap!(shimmy_rs, shimmy);
wrap!(bicycle_simplified_rs, bicycle_simplified);
wrap!(shimmy_simplified_rs, shimmy_simplified);
// Constant entries written once (the driver's arrays keep them between calls).
wrap!(bicycle_varying_rs, bicycle, eval_abcd_varying);
wrap!(shimmy_varying_rs, shimmy_simplified, eval_abcd_varying);
