//! Tutorials: narrative walk-throughs whose code runs as tests.
//!
//! * [`_01_closed_forms`]: a model in closed form — its characteristic polynomial, stability
//!   conditions and boundaries, transfer functions and eigenvalue sensitivities.

/// # Closed forms: exploring a model's equations
///
/// eom keeps every matrix of a model as an exact expression of its parameters, so a model can
/// be explored in closed form, not only at numbers. This tutorial takes the shimmy — a body
/// pulled at speed `u`, a lateral spring ahead of its mass centre, a tyre behind it that cannot
/// slip sideways (Schwab & Meijaard 2003; `docs/references.md` §B) — from its items to the
/// condition for stable running.
///
/// ## The model
///
/// Parameters are declared with their sign: masses, lengths and stiffnesses are positive, and
/// saying so lets the closed forms divide such factors out of the stability conditions.
///
/// ```
/// use eom_model::*;
/// use eom_sym::{Assumption, Expr, ParamInfo};
/// use eom_sym::closed::ClosedForms;
///
/// let mut m = Model::new("shimmy");
/// let positive = |name: &str, nominal: f64| ParamInfo {
///     name: name.into(),
///     nominal,
///     unit: None,
///     description: None,
///     assume: Assumption::Positive,
/// };
/// let mass = m.param_info(positive("m", 5.0)).unwrap();
/// let iz = m.param_info(positive("I", 1.05)).unwrap();
/// let k = m.param_info(positive("k", 1.5)).unwrap();
/// let l = m.param_info(positive("l", 1.0)).unwrap();
/// let x = m.param("x", 0.5).unwrap(); // a/l, any real value
/// let u = m.param("u", 10.0).unwrap(); // forward speed, either sign
/// let (a, b) = (x * l, (1i64 - x) * l);
/// m.add(Body::new("chassis").mass(mass).moments(vec3(0, 0, iz)).velocity(vec3(u, 0, 0)));
/// m.add(FlexPoint::new("spring").between("chassis", "ground").at(vec3(b, 0, 0)).forces(1).axis(y_axis()).stiffness(k, 0));
/// m.add(NhPoint::new("tyre").between("chassis", "ground").at(vec3(-a, 0, 0)).forces(1).axis(y_axis()));
/// m.add(RigidPoint::new("road").between("chassis", "ground").forces(1).moments(2).axis(z_axis()));
/// m.add(RigidPoint::new("speed").between("chassis", "ground").forces(1).axis(x_axis()));
///
/// // The symbolic state space: three states (lateral position, yaw, yaw rate).
/// let sym = Linearizer::new(&m).symbolic().unwrap();
/// assert_eq!(sym.state_space().a.nrows(), 3);
///
/// // ## The characteristic polynomial
/// //
/// // From the descriptor pencil (E = diag(I, M), no division by the reduced mass): the cubic
/// // (I + m a²) s³ + m a u s² + k l² s + k l u, with det(sI − A) = p(s)/(I + m a²).
/// let cf = ClosedForms::default();
/// let (e, f) = sym.pencil();
/// let p = cf.pencil_polynomial(Some(&e), &f).unwrap();
/// let want = [k * l * u, k * l * l, mass * a * u, iz + mass * a * a];
/// for (got, want) in p.polynomial.coefficients.iter().zip(want) {
///     assert!(eom_sym::zero::is_identically_zero(*got - want));
/// }
///
/// // ## When is it stable?
/// //
/// // The Liénard–Chipart conditions, with the factors of known sign divided out. Once a
/// // condition establishes u > 0, the later conditions drop the factor u too.
/// let conditions = cf.stability_conditions(&p).unwrap();
/// let text: Vec<String> = conditions.iter().map(|c| format!("{} > 0", c.expression)).collect();
/// assert_eq!(text, ["u > 0", "x > 0", "m*l^2*x - I - m*l^2*x^2 > 0"]);
///
/// // m·x·(1 − x)·l² > I: stable for a band of mass-centre positions, whatever the speed and
/// // the stiffness. Its edges, solved for x: x = 1/2 ∓ √(1/4 − I/(m l²)).
/// let edges = cf.solve_boundary(conditions[2].expression, x).unwrap().unwrap();
/// let at = m.scope.nominal_values();
/// let tape = eom_sym::Tape::new(&edges.roots, &m.scope.params()).unwrap();
/// let v = tape.eval_vec(&at).unwrap();
/// assert!((v[0] - 0.3).abs() < 1e-15 && (v[1] - 0.7).abs() < 1e-15);
///
/// // ## Sensitivities
/// //
/// // How each eigenvalue moves with each parameter, at a point: from the exact ∂A/∂p and the
/// // eigenvectors. On the stability edge x = 0.3 the complex pair crosses the axis; how fast
/// // it crosses as x changes is ∂(Re λ)/∂x.
/// let at = m.scope.values_with(&[("x", 0.3)]).unwrap();
/// let s = sensitivities(&sym, &at).unwrap();
/// let pair = s.eigenvalues.iter().find(|e| e.eigenvalue.im > 0.5).unwrap();
/// let kx = s.params.iter().position(|p| p == "x").unwrap();
/// assert!(pair.derivatives.as_ref().unwrap()[kx].re < 0.0); // more x: more stable
/// ```
///
/// ## The same from the command line
///
/// ```text
/// eom symbolic shimmy --stability --solve-for x
/// eom symbolic shimmy --set u=10 --set k=1.5 --format latex
/// eom analyze shimmy --set x=0.3 --sensitivity
/// ```
///
/// ## A second-order model
///
/// For two states, the natural frequency and damping ratio come out in closed form too:
///
/// ```
/// use eom_sym::closed::ClosedForms;
/// let m = models::build("smd", &[]).unwrap();
/// let sym = eom_model::Linearizer::new(&m).symbolic().unwrap();
/// let cf = ClosedForms::default();
/// let p = cf.characteristic_polynomial(&sym.state_space().a).unwrap();
/// let so = cf.second_order(&p).unwrap().unwrap();
/// assert_eq!(so.damping_ratio.to_string(), "c/(2*sqrt(m)*sqrt(k))");
/// ```
///
/// ## Under a wing
///
/// The same block under a horizontal wing in an air stream (the seed paper's example,
/// `docs/references.md` §D): the wing's quasi-steady lift opposes the vertical velocity, and
/// the damping becomes c + ρVS(CLα + CD)/2, the paper's eq. 13, now read off the model:
///
/// ```
/// use eom_sym::closed::ClosedForms;
/// let m = models::build("smd_wing", &[]).unwrap();
/// let sym = eom_model::Linearizer::new(&m).symbolic().unwrap();
/// let cf = ClosedForms::default();
/// let p = cf.characteristic_polynomial(&sym.state_space().a).unwrap();
/// let so = cf.second_order(&p).unwrap().unwrap();
/// let s = |n: &str| m.scope.get(n).unwrap();
/// let (rho, v, area) = (s("rho"), s("V"), s("S"));
/// let damping = s("c") + rho * v * area * (s("CLa") + s("CD")) / 2i64;
/// let want = damping / (2i64 * eom_sym::Expr::sqrt(s("m") * s("k")));
/// // Equal as functions of the parameters (the printed forms may group terms differently).
/// assert!(eom_sym::zero::is_identically_zero(so.damping_ratio - want));
/// // Stable exactly when the total damping is positive.
/// let conditions = cf.stability_conditions(&p).unwrap();
/// assert_eq!(conditions.len(), 1);
/// assert!(eom_sym::zero::is_identically_zero(
///     conditions[0].expression - damping
/// ) || eom_sym::zero::is_identically_zero(conditions[0].expression - 2i64 * damping));
/// ```
pub mod _01_closed_forms {}
