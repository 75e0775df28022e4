use eom_sym::model::{Linearizer, ValidityCheck};
use eom_sym::Expr;
fn main() {
    for name in ["smd", "pendulum", "shimmy", "bicycle", "quarter_car", "top", "disk", "chain3", "chain50"] {
        let m = models::build(name, &[]).unwrap();
        let t = std::time::Instant::now();
        let s = Linearizer::new(&m).symbolic().unwrap();
        let dt = t.elapsed();
        let ss = s.state_space();
        let mut roots = vec![];
        let mut nz = [0usize; 5];
        for (k, mm) in [&ss.a, &ss.b, &ss.c, &ss.d, &ss.phys].iter().enumerate() {
            for e in mm.iter() { if !e.is_zero() { nz[k] += 1; } roots.push(*e); }
        }
        let abcd: Vec<Expr> = [&ss.a, &ss.b, &ss.c, &ss.d].iter().flat_map(|m| m.iter().copied()).collect();
        let mut croots = vec![];
        let mut npiv = 0; let mut nneg = 0; let mut nent = 0;
        for c in &s.reduction.checks {
            match c { ValidityCheck::Pivot{value,row,..} => { npiv+=1; nent += row.len(); croots.push(*value); croots.extend(row.iter().copied()); }
                      ValidityCheck::Negligible{value,scale,..} => {nneg+=1; nent += scale.len(); croots.push(*value); croots.extend(scale.iter().copied());} }
        }
        let physconst = ss.phys.iter().all(|e| e.is_number());
        println!("{name}: params {} A {}x{} B {}x{} C {}x{} D {}x{} phys {}x{} nnz {:?} physconst {physconst} | abcd ops {:?} total {} dag {} | with checks ops {} | checks piv {npiv} neg {nneg} entries {nent} | sym {:?}",
          m.scope.len(), ss.a.nrows(), ss.a.ncols(), ss.b.nrows(), ss.b.ncols(), ss.c.nrows(), ss.c.ncols(), ss.d.nrows(), ss.d.ncols(), ss.phys.nrows(), ss.phys.ncols(), nz,
          Expr::op_count(&abcd), Expr::op_count(&abcd).total(), Expr::dag_size(&abcd), Expr::op_count(&[abcd.clone(), croots.clone()].concat()).total(), dt);
        if name == "shimmy" || name == "smd" { for c in &s.reduction.checks { println!("   {} ", c.what()); } println!("{:?}", ss.a); }
        if name == "bicycle" { for c in &s.reduction.checks { match c { ValidityCheck::Pivot{value,row,what} => println!("   {what} {value:?}... row {}", row.len()), ValidityCheck::Negligible{what,..} => println!("  neg {what}")} } }
    }
}
