#![allow(warnings)]
// The bicycle's module as emitted by two checkouts of eom (written by ../baseline.sh), called
// from C next to PyDy's: this branch's (`bicycle_f64.rs`) and a baseline's
// (`bicycle_base_f64.rs`, its module renamed `bicycle_base`).
include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../bicycle_f64.rs"));
include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../bicycle_base_f64.rs"));

/// `extern "C" fn NAME(p, a, b, c, d) -> i32` around `MODULE::eval_abcd` (1 on error).
macro_rules! wrap {
    ($name:ident, $m:ident) => {
        #[unsafe(no_mangle)]
        pub unsafe extern "C" fn $name(
            p: *const f64,
            a: *mut f64,
            b: *mut f64,
            c: *mut f64,
            d: *mut f64,
        ) -> i32 {
            use $m::*;
            unsafe {
                let mut w = [0.0; WORK_LEN];
                eval_abcd(
                    &*(p as *const [f64; N_PARAMS]),
                    &mut *(a as *mut [f64; A_LEN]),
                    &mut *(b as *mut [f64; B_LEN]),
                    &mut *(c as *mut [f64; C_LEN]),
                    &mut *(d as *mut [f64; D_LEN]),
                    &mut w,
                )
                .is_err() as i32
            }
        }
    };
}

wrap!(bicycle_rs, bicycle);
wrap!(bicycle_base_rs, bicycle_base);
