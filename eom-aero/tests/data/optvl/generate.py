"""Reference derivatives from OptVL 2.5.0 (AVL 3.52-derived core, PyPI `optvl`) for the
eom-aero tests: writes the .avl geometries of this folder and `optvl_reference.json`.

Run from this folder, in a virtual environment with `pip install optvl==2.5.0`:
    python generate.py
OptVL applies no forces to the trailing legs (AVL >= 3.4x behaviour), so the tests compare
with `SolverOptions { trailing_leg_forces: false, .. }`.
"""
import json

from optvl import OVLSolver

HEADER = """{title}
#Mach
{mach}
#IYsym  IZsym  Zsym
0       {izsym}      {zsym}
#Sref   Cref   Bref
{sref}  {cref}  {bref}
#Xref   Yref   Zref
{xref}  0.0    0.0
"""

GEOMETRIES = {
    # AR 8, taper 0.5, unswept leading edge, cosine/cosine 8 x 16 per half
    "tapered_ar8.avl": HEADER.format(izsym=0, zsym=0.0, title="Tapered wing AR 8, taper 0.5", mach=0.0,
                                     sref=6.0, cref=0.75, bref=6.0, xref=0.1875) + """
SURFACE
Wing
8 1.0 16 1.0
YDUPLICATE
0.0
SECTION
0.0 0.0 0.0 1.0 0.0
SECTION
0.0 3.0 0.0 0.5 0.0
""",
    # 30 deg leading-edge sweep, taper 0.5, 5 deg dihedral, 2 deg washout, AR 6
    "swept30.avl": HEADER.format(izsym=0, zsym=0.0, title="Swept wing 30 deg, taper 0.5, dihedral 5 deg", mach=0.0,
                                 sref=6.0, cref=1.0, bref=6.0, xref=0.6) + """
SURFACE
Wing
8 1.0 16 1.0
YDUPLICATE
0.0
ANGLE
1.0
SECTION
0.0 0.0 0.0 1.3333333333 0.0
SECTION
1.7320508076 3.0 0.2624579597 0.6666666667 -2.0
""",
    # a cranked wing with strips per section (-sine toward the tip), uniform chordwise panels
    "cranked_sections.avl": HEADER.format(izsym=0, zsym=0.0, title="Cranked wing, strips per section", mach=0.0,
                                          sref=5.0, cref=1.0, bref=5.0, xref=0.3) + """
SURFACE
Wing
6 0.0
YDUPLICATE
0.0
SECTION
0.0 0.0 0.0 1.2 0.0 6 1.0
SECTION
0.1 1.2 0.0 1.0 0.0 10 -2.0
SECTION
0.6 2.5 0.3 0.6 0.0
""",
    # wing, horizontal tail with incidence, and twin fins outboard of the tail: three
    # surfaces (six with the mirror images) in one lattice, tail and fins 3 chords above
    # the wing's wake. Closer to a wake, AVL's finite vortex core changes its result on a
    # coarse lattice (see INTERFERENCE below).
    "wing_tail_fins.avl": HEADER.format(izsym=0, zsym=0.0, title="Wing, tail and twin fins", mach=0.0,
                                        sref=4.0, cref=0.8, bref=5.0, xref=0.3) + """
SURFACE
Wing
8 1.0 14 1.0
YDUPLICATE
0.0
SECTION
0.0 0.0 0.0 1.0 2.0
SECTION
0.2 2.5 0.2 0.6 0.0
SURFACE
Tail
6 1.0 8 1.0
YDUPLICATE
0.0
TRANSLATE
3.0 0.0 3.0
SECTION
0.0 0.0 0.0 0.6 -2.0
SECTION
0.2 0.9 0.0 0.4 -2.0
SURFACE
Fin
6 1.0 8 1.0
YDUPLICATE
0.0
TRANSLATE
3.0 1.2 3.0
SECTION
0.0 0.0 0.0 0.7 0.0
SECTION
0.4 0.0 0.8 0.4 0.0
""",
    # a tapered, swept wing half a chord above the ground (a solid wall: iZsym = 1), and
    # the same wing under a constant-pressure plane (iZsym = -1)
    "ground_effect.avl": HEADER.format(izsym=1, zsym=-0.5, title="Wing in ground effect", mach=0.0,
                                       sref=6.0, cref=1.0, bref=6.0, xref=0.25) + """
SURFACE
Wing
8 1.0 16 1.0
YDUPLICATE
0.0
SECTION
0.0 0.0 0.0 1.0 0.0
SECTION
0.3 3.0 0.1 0.7 0.0
""",
    "free_surface.avl": HEADER.format(izsym=-1, zsym=-0.5, title="Wing under a free surface", mach=0.0,
                                      sref=6.0, cref=1.0, bref=6.0, xref=0.25) + """
SURFACE
Wing
8 1.0 16 1.0
YDUPLICATE
0.0
SECTION
0.0 0.0 0.0 1.0 0.0
SECTION
0.3 3.0 0.1 0.7 0.0
""",
}

# (file, alpha in degrees, Mach); the first is the AVL 3.32 fixture of the folder above (its
# one home), for the AVL 3.32 / 3.52 comparison
CASES = [
    ("../dihedral10_ar6.avl", 5.0, 0.0),
    ("tapered_ar8.avl", 0.0, 0.0),
    ("tapered_ar8.avl", 5.0, 0.0),
    ("swept30.avl", 0.0, 0.0),
    ("swept30.avl", 5.0, 0.0),
    ("swept30.avl", 5.0, 0.5),
    ("cranked_sections.avl", 4.0, 0.0),
    ("wing_tail_fins.avl", 3.0, 0.0),
    ("ground_effect.avl", 3.0, 0.0),
    ("free_surface.avl", 3.0, 0.0),
]

# The wing-tail-fins configuration with the tail and fins in the wing's wake plane
# (z = 0.3), on the lattice above and on one with three times the panels each way, written to
# optvl_interference.json: AVL's finite vortex core makes its coarse-lattice interference
# differ from a coreless lattice, and refining the lattice removes the difference.
INTERFERENCE = {
    "wake_tail_coarse.avl": GEOMETRIES["wing_tail_fins.avl"]
    .replace("3.0 0.0 3.0", "3.0 0.0 0.3").replace("3.0 1.2 3.0", "3.0 1.2 0.3"),
}
INTERFERENCE["wake_tail_fine.avl"] = (
    INTERFERENCE["wake_tail_coarse.avl"].replace("8 1.0 14 1.0", "24 1.0 42 1.0")
    .replace("6 1.0 8 1.0", "18 1.0 24 1.0")
)

ROWS = ["CX", "CY", "CZ", "Cl", "Cm", "Cn"]
COLS = ["u", "v", "w", "p", "q", "r"]


def run(geo, alpha, mach):
    solver = OVLSolver(geo_file=geo)
    solver.set_variable("alpha", alpha)
    solver.set_variable("beta", 0.0)
    solver.set_parameter("Mach", mach)
    solver.execute_run()
    body = solver.get_body_axis_derivs()
    totals = solver.get_total_forces()
    return {
        "file": geo,
        "alpha_deg": alpha,
        "mach": mach,
        "derivatives": {r + c: float(body[f"d{r}/d{c}"]) for r in ROWS for c in COLS},
        "totals": {k: float(totals[k]) for k in ["CX", "CY", "CZ", "Cl", "Cm", "Cn", "CL", "CD"]},
    }


def main():
    for name, text in {**GEOMETRIES, **INTERFERENCE}.items():
        with open(name, "w") as f:
            f.write(text.lstrip())
    source = "OptVL 2.5.0 (AVL 3.52-derived core), generate.py"
    cases = [run(geo, alpha, mach) for geo, alpha, mach in CASES]
    with open("optvl_reference.json", "w") as f:
        json.dump({"source": source, "cases": cases}, f, indent=1)
    cases = [run(geo, 3.0, 0.0) for geo in INTERFERENCE]
    with open("optvl_interference.json", "w") as f:
        json.dump({"source": source, "cases": cases}, f, indent=1)


if __name__ == "__main__":
    main()
