//! A mass on a spring and damper, built in Rust: its state matrix as expressions, then numbers
//! at other parameter values. `cargo run --release -p eom-model --example spring_mass`

use eom_model::prelude::*;

fn main() -> Result<(), ModelError> {
    let mut m = Model::new("mass on a spring");
    let mass = m.param("m", 2.0)?;
    let k = m.param("k", 8.0)?;
    let c = m.param("c", 0.4)?;
    m.add(Body::new("block").mass(mass));
    // The block slides along z only: two forces and three moments hold it.
    m.add(
        RigidPoint::new("slider")
            .between("block", "ground")
            .forces(2)
            .moments(3)
            .axis(z_axis()),
    );
    m.add(
        FlexPoint::new("spring")
            .between("block", "ground")
            .forces(1)
            .axis(z_axis())
            .stiffness(k, 0)
            .damping(c, 0),
    );

    // Symbolic: A = [[0, 1], [−k/m, −c/m]] as expressions over the parameters.
    let sym = Linearizer::new(&m).symbolic()?;
    let a = &sym.state_space().a;
    println!(
        "A = [[{}, {}], [{}, {}]]",
        a[(0, 0)],
        a[(0, 1)],
        a[(1, 0)],
        a[(1, 1)]
    );

    // Numeric, at k = 18 N/m, by the robust path: the eigenvalues −c/2m ± i·sqrt(k/m − (c/2m)²).
    let lin = Linearizer::new(&m)
        .at(&[("k", 18.0)])
        .method(Method::Robust)
        .run()?;
    let eig = eom_num::modes::eigenvalues(&lin.state_space.a)?;
    let expected = (18.0_f64 / 2.0 - 0.01).sqrt();
    assert!(
        eig.iter()
            .all(|z| (z.re + 0.1).abs() < 1e-12 && (z.im.abs() - expected).abs() < 1e-12)
    );
    println!("eigenvalues at k = 18: {} and {}", eig[0], eig[1]);
    Ok(())
}
