#![allow(warnings)]
// eom-codegen's modules for the bicycle and the shimmy (written by build.sh), called from C.
include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../bicycle_f64.rs"));
include!(concat!(env!("CARGO_MANIFEST_DIR"), "/../shimmy_f64.rs"));

#[unsafe(no_mangle)]
pub unsafe extern "C" fn bicycle_rs(p: *const f64, a: *mut f64, b: *mut f64, c: *mut f64, d: *mut f64) -> i32 {
    use bicycle::*;
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

#[unsafe(no_mangle)]
pub unsafe extern "C" fn shimmy_rs(p: *const f64, a: *mut f64, b: *mut f64, c: *mut f64, d: *mut f64) -> i32 {
    use shimmy::*;
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
