"""eom.aero against AVL 3.32's own output (eom-aero/tests/data, see its README): the
.sb/.st numbers read back as printed, the vortex lattice of the .avl geometries within
0.2 % of AVL (the tolerance of eom-aero/tests/avl_fixtures.rs), the dimensional matrix
against its definition, and errors naming the file."""

import re

import numpy as np
import pytest

import eom
from conftest import ROOT

DATA = ROOT / "eom-aero" / "tests" / "data"
NAMES = [
    [f"C{force}{x}" for x in "uvwpqr"] for force in ("X", "Y", "Z", "l", "m", "n")
]


def printed_derivatives(path):
    """The 36 geometry-axis derivatives as AVL printed them (`CYv =  -2.474202`), parsed
    here with a regular expression, independently of eom's reader."""
    text = path.read_text()
    body = text[text.index("Geometry-axis derivatives") :]
    found = dict(re.findall(r"\b(C[XYZlmn][uvwpqr])\s*=\s*(-?\d+\.\d+)", body))
    return np.array([[float(found[n]) for n in row] for row in NAMES])


def within_avl_tolerance(ours, avl):
    # An entry passes within 0.2 % of AVL's value or of the largest entry of its row.
    row_max = np.abs(avl).max(axis=1, keepdims=True)
    dev = np.abs(ours - avl)
    return (dev <= 0.002 * np.abs(avl)) | (dev <= 0.002 * row_max)


def test_sb_file_reads_back_as_printed():
    path = DATA / "seed_fin_a0_avl332.sb"
    d = eom.aero(str(path))
    assert d.source == "body-axis derivatives (SB)"
    assert d.names == NAMES and list(d) == [n for row in NAMES for n in row]
    np.testing.assert_allclose(d.coefficients, printed_derivatives(path), rtol=0, atol=5e-7)
    assert d["CYv"] == pytest.approx(-2.474202, abs=5e-7)
    assert d.to_dict()["Cnr"] == pytest.approx(-0.146157, abs=5e-7)
    assert d.reference == (0.5, 0.5, 1.0, (0.125, 0.0, 0.0))
    assert d.alpha_deg == 0.0 and d.unknown == []
    assert not d.coefficients.flags.writeable


@pytest.mark.parametrize(
    "geometry, output, alpha",
    [
        ("seed_fin.avl", "seed_fin_a0_avl332.sb", None),
        ("dihedral10_ar6.avl", "dihedral10_ar6_a5_avl332.sb", 5.0),
    ],
)
def test_vortex_lattice_matches_avl(geometry, output, alpha):
    d = eom.aero(str(DATA / geometry), alpha=alpha)
    assert d.source == "geometry (vortex lattice)"
    assert d.alpha_deg == (alpha or 0.0)
    ok = within_avl_tolerance(d.coefficients, printed_derivatives(DATA / output))
    bad = [NAMES[i][j] for i, j in zip(*np.nonzero(~ok))]
    assert not bad, f"{geometry}: {bad}"


def test_st_file_gives_body_axes_and_names_the_unknown():
    d = eom.aero(str(DATA / "dihedral10_ar6_a5_avl332.st"))
    assert d.source == "stability-axis derivatives (ST)"
    assert d.alpha_deg == 5.0
    # The .sb of the same run case: every entry the .st determines agrees (5-6 printed digits).
    sb = printed_derivatives(DATA / "dihedral10_ar6_a5_avl332.sb")
    known = np.array([[n not in d.unknown for n in row] for row in NAMES])
    assert 12 <= known.sum() < 36
    np.testing.assert_allclose(d.coefficients[known], sb[known], rtol=2e-4, atol=2e-5)


def test_dimensional_matrix_is_its_definition():
    rho, v = 1.1, 23.0
    d = eom.aero(str(DATA / "dihedral10_ar6_a5_avl332.sb"), density=rho, speed=v)
    s, c, b = d.reference.sref, d.reference.cref, d.reference.bref
    # F_i = ½ρV² S ℓ_i C_i with ℓ = 1, 1, 1, b, c, b; x̂ = (u, v, w)/V, p b/2V, q c/2V, r b/2V.
    rows = np.array([1, 1, 1, b, c, b])
    cols = np.array([1 / v, 1 / v, 1 / v, b / (2 * v), c / (2 * v), b / (2 * v)])
    want = 0.5 * rho * v**2 * s * rows[:, None] * d.coefficients * cols[None, :]
    np.testing.assert_allclose(d.dimensional, want, rtol=1e-13, atol=0)


def test_errors_name_the_file(tmp_path):
    missing = tmp_path / "nope.avl"
    with pytest.raises(eom.EomError, match=re.escape(str(missing))):
        eom.aero(str(missing))
    other = tmp_path / "wing.txt"
    other.write_text("x")
    with pytest.raises(eom.EomError, match=re.escape(str(other)) + ".*expected an AVL"):
        eom.aero(str(other))
    with pytest.raises(eom.EomError, match="alpha.*AVL geometry"):
        eom.aero(str(DATA / "seed_fin_a0_avl332.sb"), alpha=2.0)
    broken = tmp_path / "broken.avl"
    lines = (DATA / "seed_fin.avl").read_text().splitlines()
    k = next(i for i, l in enumerate(lines) if l.strip().upper().startswith("SURFACE"))
    # The surface's lattice line (after its name) made unreadable.
    lines[k + 3] = "eight panels"
    broken.write_text("\n".join(lines) + "\n")
    with pytest.raises(eom.EomError, match=re.escape(f"{broken}:")):
        eom.aero(str(broken))
