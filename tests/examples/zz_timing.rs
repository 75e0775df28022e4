use std::hint::black_box;
include!(concat!(env!("OUT_DIR"), "/generated.rs"));
macro_rules! t {
    ($label:expr, $m:path, $ty:ty) => {{
        use $m as g;
        let pts: Vec<[$ty; g::N_PARAMS]> = (0..64).map(|i| core::array::from_fn(|k| g::NOMINAL[k] * (1.0 + 0.001 * ((i * 7 + k) % 13) as $ty))).collect();
        let (mut a, mut b, mut c, mut d, mut w) = ([0.0; g::A_LEN], [0.0; g::B_LEN], [0.0; g::C_LEN], [0.0; g::D_LEN], [0.0; g::WORK_LEN]);
        let mut best = f64::MAX;
        for _ in 0..2000 {
            let t = std::time::Instant::now();
            for k in 0..1024 {
                let r = g::eval_abcd(black_box(&pts[k & 63]), &mut a, &mut b, &mut c, &mut d, &mut w);
                black_box((&a, &b, &c, &d, r));
            }
            best = best.min(t.elapsed().as_nanos() as f64 / 1024.0);
        }
        println!("{:40} {:8.2} ns (min of batches)", $label, best);
    }};
}
fn main() {
    t!("bicycle f64", gen64::bicycle, f64);
    t!("bicycle std", gen64::bicycle_std, f64);
    t!("bicycle simplified", gen64::bicycle_simplified, f64);
    t!("bicycle chunked", gen64::bicycle_chunked, f64);
    t!("bicycle f32", gen32::bicycle, f32);
    t!("bicycle v", gen64::bicycle_speed, f64);
    t!("shimmy", gen64::shimmy, f64);
    t!("chain50", gen64::chain50, f64);
    t!("chain50 f32", gen32::chain50, f32);
}
