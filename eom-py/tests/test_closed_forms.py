"""Model.symbolic against independent closed forms: the spring–mass–damper's characteristic
polynomial s² + (c/m)s + k/m, its transfer functions 1/(m s² + c s + k) from the force,
its stability conditions against the roots (NumPy) at random parameter signs, and sympy
parsing every expression."""

import numpy as np
import pytest

import eom


def test_smd_matrices_and_polynomial_text():
    sym = eom.load("smd").symbolic()
    assert sym.matrices["A"] == [["0", "1"], ["-k/m", "-c/m"]]
    assert "\\frac" in sym.latex["A"]
    p = sym.characteristic_polynomial
    # det(sI − A) = (k + c s + m s²)/m, s⁰ first.
    assert p.coefficients == ["k", "c", "m"] and p.scale == "m" and p.zero_roots == 0
    assert p.normalized
    assert p.latex.startswith("m s^{2}")
    # Every parameter positive by its declared range: no condition left, always stable.
    assert sym.stability == [] and sym.stability_verdict == "always"
    assert "\\det(sI - A)" in sym.to_latex()


def test_smd_with_sympy():
    sympy = pytest.importorskip("sympy")
    sym = eom.load("smd").symbolic()
    out = sym.to_sympy()
    m, k, c = sympy.symbols("m k c")
    s = out["s"]
    assert sympy.simplify(out["A"] - sympy.Matrix([[0, 1], [-k / m, -c / m]])) == sympy.zeros(2, 2)
    # det(sI − A) = s² + (c/m)s + k/m: p(s)/scale.
    p = out["characteristic_polynomial"] / sympy.sympify(sym.characteristic_polynomial.scale, locals={"m": m})
    assert sympy.expand(p - (s**2 + c / m * s + k / m)) == 0
    assert sympy.expand((s * sympy.eye(2) - out["A"]).det() - p) == 0
    wn, zeta = out["second_order"]
    # ωₙ = √(k/m), ζ = c/(2√(km)), for the positive values the parameters are declared to take.
    at = {m: sympy.Rational(5, 2), k: 40, c: sympy.Rational(7, 10)}
    assert sympy.simplify((wn - sympy.sqrt(k / m)).subs(at)) == 0
    assert sympy.simplify((zeta - c / (2 * sympy.sqrt(k * m))).subs(at)) == 0
    # The force f drives the block: z / f = 1/(m s² + c s + k); the other outputs as their
    # rows of C say (the velocity s z, the spring force k z).
    lin = eom.load("smd").linearize()
    assert lin.inputs == ["f"]
    tfs = out["transfer_functions"]
    assert set(tfs) == {(o, "f") for o in lin.outputs}
    assert len(sym.transfer_functions) == len(lin.outputs)
    base = 1 / (m * s**2 + c * s + k)
    C = eom.load("smd").symbolic().to_sympy()["C"]
    for i, o in enumerate(lin.outputs):
        # Output i is C[i, :] · (z, ż): z → 1, ż → s.
        want = (C[i, 0] + C[i, 1] * s) * base
        assert sympy.simplify(tfs[(o, "f")] - want) == 0, o
    assert sympy.simplify(tfs[(lin.outputs[0], "f")] - base) == 0


def test_kept_parameters_and_substituted_defaults():
    kept = eom.load("smd").symbolic(keep=["k"])
    assert kept.matrices["A"][1][0] == "-k"
    # The defaults as exact numbers (c = 0.1 is 1/10).
    assert dict(kept.substituted) == {"m": "1", "c": "1/10"}
    assert kept.characteristic_polynomial.coefficients == ["k", "1/10", "1"]


@pytest.fixture(scope="module")
def smd_any_sign(tmp_path_factory):
    """The smd with k and c allowed any sign (m stays positive): the conditions on them are
    then not divided out by the declared ranges."""
    lines = eom.load("smd").to_toml().splitlines()
    for i, line in enumerate(lines):
        if line.startswith(("k = ", "c = ")):
            lines[i] = line.replace('range = "> 0"', 'range = "any"')
    text = "\n".join(lines) + "\n"
    assert text.count('range = "any"') == 2
    path = tmp_path_factory.mktemp("smd") / "smd_any.toml"
    path.write_text(text)
    return eom.load(str(path))


def test_stability_conditions_agree_with_the_roots(smd_any_sign):
    sympy = pytest.importorskip("sympy")
    sym = smd_any_sign.symbolic(solve_for="k")
    assert sym.stability and all(c.satisfiable for c in sym.stability)
    assert sym.stability_verdict == "when all conditions hold"
    # m s² + c s + k with m > 0: Routh–Hurwitz gives c > 0 and k > 0 (c/m, k/m > 0).
    assert sorted(c.expression for c in sym.stability) == ["c", "k"]
    conds = sym.to_sympy()["stability"]
    m, k, c = sympy.symbols("m k c")
    f = sympy.lambdify((m, k, c), [cond.lhs for cond in conds])
    rng = np.random.default_rng(29)
    agree = 0
    for mm, kk, cc in rng.uniform([0.1, -5, -5], [5, 5, 5], (400, 3)):
        # Asymptotically stable: both roots of m s² + c s + k in the left half plane.
        stable = bool(np.all(np.roots([mm, cc, kk]).real < 0))
        assert all(v > 0 for v in f(mm, kk, cc)) == stable, (mm, kk, cc)
        agree += stable
    assert 50 < agree < 350  # both verdicts drawn
    # The boundary in k: k = 0.
    bounds = [c.boundary for c in sym.stability if c.boundary is not None]
    assert ("k", ["0"]) in bounds
    for c in sym.stability:
        assert c.latex.endswith("> 0")


def test_bicycle_closed_forms_parse_in_sympy():
    # `lambda` is a Python keyword and a bicycle parameter: it must still parse.
    sympy = pytest.importorskip("sympy")
    sym = eom.load("bicycle").symbolic(keep=["v", "lambda"], transfer=False)
    out = sym.to_sympy()
    v, lam = sympy.symbols("v lambda")
    assert out["A"].free_symbols <= {v, lam}
    p = out["characteristic_polynomial"]
    assert p.free_symbols <= {v, lam, out["s"]}
    # At v = 5 and the default λ, the roots are the benchmark's (tests/data/bicycle_table2.csv).
    lam0 = eom.load("bicycle").parameters["lambda"]
    coeffs = sympy.Poly(p.subs({v: 5, lam: lam0}), out["s"]).all_coeffs()
    roots = np.roots([float(x) for x in coeffs])
    lin = eom.load("bicycle").linearize(v=5.0)
    nonzero = [z for z in lin.eigenvalues() if abs(z) > 1e-9]
    np.testing.assert_allclose(np.sort_complex(roots), np.sort_complex(nonzero), rtol=1e-9)
    assert sym.characteristic_polynomial.zero_roots == 2


def test_solve_for_must_be_kept():
    with pytest.raises(eom.EomError, match="keep it symbolic"):
        eom.load("smd").symbolic(keep=["k"], solve_for="c")


@pytest.mark.parametrize("v, verdict", [(3.0, "never"), (5.0, "always"), (8.0, "never")])
def test_bicycle_with_every_parameter_substituted_is_decided(tmp_path, v, verdict):
    # The benchmark bicycle is stable for 4.2923825 < v < 6.0242620 m/s (Meijaard et al.
    # 2007, Table 2a; docs/references.md §A): below, the weave mode is unstable; above, the
    # capsize mode. With keep=[] every condition is an exact constant (trigonometric
    # functions of rationals), whose sign the summary decides.
    path = tmp_path / "bicycle.toml"
    path.write_text(eom.load("bicycle").to_toml(v=v))
    sym = eom.load(str(path)).symbolic(keep=[], transfer=False)
    assert sym.stability_verdict.startswith(verdict), sym.stability_verdict
    if verdict == "always":
        assert sym.stability == []
