"""Every built-in model (each family at a small size) and every shipped model file through
every call of the Python package — the catalogue and the models folder are iterated, never a
typed list — against what the `eom` CLI prints for the same model (`eom analyze --format
json`: eigenvalues, verdicts, structural zeros), against each other (the symbolic reduction's
compiled evaluation against the numeric elimination), against python-control (poles) and
across a pickle round trip."""

import pickle

import numpy as np
import pytest

import eom
from conftest import ROOT, eom_binary

VERDICT = {"stable": 1, "marginal": 0, "unstable": -1}


def every_model():
    names = [n[:-1] + "3" if n.endswith("N") else n for n in eom.models()]
    # The shipped model files (each has its reference answers beside it, NAME.ref.toml)
    # that are not also built-ins (those are the same text, embedded).
    files = [
        str(p)
        for p in sorted((ROOT / "models").glob("*.toml"))
        if p.with_suffix(".ref.toml").exists() and p.stem not in names
    ]
    return names + files


def cli_analyze(model):
    import json
    import subprocess

    out = subprocess.run(
        [eom_binary(), "analyze", model, "--format", "json"],
        check=True, capture_output=True, text=True,
    ).stdout
    return json.loads(out)


def matched(ours, theirs):
    """Pairs (ours, theirs) of the two lists of eigenvalues, each of theirs with the nearest
    unused one of ours."""
    left = list(ours)
    pairs = []
    for z in theirs:
        k = min(range(len(left)), key=lambda i: abs(left[i] - z))
        pairs.append((left.pop(k), z))
    return pairs


@pytest.mark.parametrize("name", every_model(), ids=lambda n: n.split("/")[-1])
def test_every_model_through_every_call(name):
    m = eom.load(name)
    lin = m.linearize()
    n, i, o = len(lin.states), len(lin.inputs), len(lin.outputs)
    assert [x.shape for x in (lin.A, lin.B, lin.C, lin.D)] == [(n, n), (n, i), (o, n), (o, i)]
    assert all(np.isfinite(x).all() for x in (lin.A, lin.B, lin.C, lin.D)), name
    scale = max(1.0, float(np.abs(lin.A).max()))

    # The CLI's numbers for the same model: eigenvalues, each mode's verdict, the verdict.
    cli = cli_analyze(name)
    theirs = [complex(e["re"], e["im"]) for e in cli["eigenvalues"]]
    ours = list(lin.eigenvalues())
    assert len(ours) == len(theirs) == n, name
    for a, b in matched(ours, theirs):
        assert abs(a - b) <= 1e-9 * scale, f"{name}: {a} against the CLI's {b}"
    assert len(lin.structural_zeros) == len(cli["structural_zeros"]), name
    modes = lin.modes()
    cli_modes = {
        (m_["eigenvalue"]["re"], m_["eigenvalue"]["im"]): m_["stability"] for m_ in cli["modes"]
    }
    for mode in modes:
        z = mode.eigenvalue
        key = min(cli_modes, key=lambda k: abs(complex(*k) - z))
        assert mode.stability == cli_modes[key], f"{name}: mode {z}"

    # Stability at the defaults: the CLI's verdict.
    p0 = {k: np.array([v]) for k, v in m.parameters.items()}
    st = m.stability(p0)
    assert st.verdict[0] == VERDICT[cli["stability"]], f"{name}: {st} against {cli['stability']}"

    # The symbolic reduction, compiled and evaluated at the defaults, is the numeric A..D.
    ev = m.evaluate(p0)
    for got, want in zip((ev.A[0], ev.B[0], ev.C[0], ev.D[0]), (lin.A, lin.B, lin.C, lin.D)):
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-9 * max(1.0, np.abs(want).max(initial=0.0)))

    # Closed forms of the small models, generated code, python-control, pickle.
    if n <= 4:
        s = m.symbolic(transfer=False)
        assert sorted(s.matrices) == ["A", "B", "C", "D"], name
        assert len(s.matrices["A"]) == n
    code = m.codegen()
    assert "pub fn" in code and "pub mod" in code, name
    control = pytest.importorskip("control")
    if n > 0:
        poles = list(np.asarray(control.poles(lin.to_control())))
        for a, b in matched(poles, theirs):
            assert abs(a - b) <= 1e-8 * scale, f"{name}: pole {a} against {b}"
    again = pickle.loads(pickle.dumps(m))
    np.testing.assert_array_equal(again.linearize().A, lin.A)
