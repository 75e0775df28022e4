#![allow(warnings)]
// The bicycle's module as emitted by two checkouts of eom (written by ../baseline.sh), called
// from C next to PyDy's: this branch's (`bicycle_f64.rs`) and a baseline's
// (`bicycle_base_f64.rs`, its module renamed `bicycle_base`).
include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../bicycle_f64.rs"));
include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../bicycle_base_f64.rs"));

include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../wrap.rs"));

wrap!(bicycle_rs, bicycle);
wrap!(bicycle_base_rs, bicycle_base);
