use eom_sym::*;
#[test]
fn probe() {
    let x = Expr::param("x", 1.5).unwrap();
    let bad = x / Expr::zero();
    println!("bad check {:?}", bad.check().is_err());
    let b2 = bad.powi(2);
    println!("bad^2 check {:?} invalid {}", b2.check().is_err(), b2.is_invalid());
    let b0 = bad.powi(0);
    println!("bad^0 check {:?}", b0.check().is_err());
    let y = Expr::param("y", 2.0).unwrap();
    println!("y/(x/0) check {:?}", y.try_div(bad).is_err());
    let r = std::panic::catch_unwind(|| {
        let x = Expr::param("x", 1.5).unwrap();
        let b2 = (x / Expr::zero()).powi(2);
        eval_generic::<f64>(&[b2], |_| Some(1.0)).map(|v| v[0])
    });
    println!("eval_generic on bad^2: {:?}", r.is_err());
    let p = Expr::int(2).powi(3000);
    println!("2^3000 invalid {}", p.is_invalid());
    let q = Expr::int(2).powi(1000).powi(3);
    println!("(2^1000)^3 invalid {}", q.is_invalid());
    println!("float 1e10 {:?}", Expr::float(1e10).unwrap().view());
    let e = Expr::e() * x;
    let s = e.subs(&[(x, y)]).unwrap();
    println!("e*x subs {:?} vs {:?}", s.view(), (Expr::e() * y).view());
    println!("(-2)^(1/3) {:?}", Expr::int(-2).pow_rational(Rational::new(1,3).unwrap()).view());
    println!("{:?}", eval_nominal::<f64>(&[Expr::int(-2).pow_rational(Rational::new(1,3).unwrap())]));
}
