// The C entry points around eom-codegen's `eval_abcd` kernels, shared by rslib/ and
// baseline/ (each includes this file).

/// `extern "C" fn NAME(p, a, b, c, d) -> i32` around `MODULE::eval_abcd` (or the kernel
/// named third, e.g. `eval_abcd_varying`; 1 on error).
macro_rules! wrap {
    ($name:ident, $m:ident) => {
        wrap!($name, $m, eval_abcd);
    };
    ($name:ident, $m:ident, $f:ident) => {
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
                $f(
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
