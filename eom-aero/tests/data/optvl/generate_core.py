"""Reference derivatives for AVL's finite vortex core, from OptVL 2.5.0 (PyPI `optvl`, a
Python interface to an AVL 3.52-derived core, double precision): writes the .avl files
`core_*.avl` of this folder and `optvl_core.json`.

Each layout puts one surface's root trailing legs along another surface's root: a wing
with dihedral and a fin on the centre line above its root chord, the same wing with a fin
three chords aft (its root in the wing's wake), and a tailplane with a fin on it (leading
edges together, as the `aircraft_ground` model's tail). Each is solved with AVL's default
core (no CORE keyword: VRCOREC = 0, VRCOREW = 2), with the core off (`CORE 0 0 1`) and
with a core of a quarter chord (`CORE 0.25 0 1`, so the chord term rules), at alpha = 0
and 5 degrees, on two lattices: cosine chordwise spacing (Cspace 1), and uniform chordwise
spacing (Cspace 0, files `*_uniform_*`). With uniform spacing AVL and eom-aero place
vortices and control points identically (the 1/4-3/4 rule); with cosine spacing AVL 3.5x
uses stations 0.5(1 - cos((2j-1)pi/(2N+1))) and 0.5(1 - cos(2j pi/(2N+1))), eom-aero Lan's
0.5(1 - cos((2j-1)pi/2N)) and 0.5(1 - cos(j pi/N)).

Run from this folder, in a virtual environment with `pip install optvl==2.5.0`:
    python generate_core.py
OptVL applies no forces to the trailing legs (AVL >= 3.4x behaviour), so the tests compare
with `SolverOptions { trailing_leg_forces: false, .. }`.
"""
import json

from optvl import OVLSolver

HEADER = """{title}
#Mach
0.0
#IYsym  IZsym  Zsym
0       0      0.0
#Sref   Cref   Bref
{sref}  {cref}  {bref}
#Xref   Yref   Zref
{xref}  0.0    0.0
"""

# AR-8-ish wing, taper 0.6, 5 deg dihedral, 8 x 16 per half, cosine/cosine
WING = """SURFACE
Wing
8 1.0 16 1.0
YDUPLICATE
0.0
SECTION
0.0 0.0 0.0 1.0 0.0
SECTION
0.2 4.0 0.3499546 0.6 0.0
"""

LAYOUTS = {
    # a fin on the centre line, its root along the wing's root chord (x 0.3 ... 1.0)
    "core_wing_fin": (dict(title="Wing with dihedral and a centre-line fin", sref=6.4, cref=0.8,
                           bref=8.0, xref=0.25), WING + """SURFACE
Fin
8 1.0 10 1.0
SECTION
0.3 0.0 0.0 0.7 0.0
SECTION
0.8 0.0 1.2 0.4 0.0
"""),
    # the same wing with a fin three chords aft, its root in the wing's wake
    "core_wing_aft_fin": (dict(title="Wing with dihedral and an aft centre-line fin", sref=6.4,
                               cref=0.8, bref=8.0, xref=0.25), WING + """SURFACE
Fin
8 1.0 10 1.0
TRANSLATE
3.0 0.0 0.0
SECTION
0.0 0.0 0.0 0.8 0.0
SECTION
0.5 0.0 1.2 0.5 0.0
"""),
    # the aircraft_ground model's tail: a 3 m x 0.9 m tailplane, a 1.1 m fin of 0.9 m
    # chord on it, leading edges together
    "core_tail_fin": (dict(title="Tailplane and fin", sref=2.7, cref=0.9, bref=3.0, xref=0.225),
                      """SURFACE
Tailplane
8 1.0 10 1.0
YDUPLICATE
0.0
SECTION
0.0 0.0 0.0 0.9 0.0
SECTION
0.0 1.5 0.0 0.9 0.0
SURFACE
Fin
8 1.0 8 1.0
SECTION
0.0 0.0 0.0 0.9 0.0
SECTION
0.0 0.0 1.1 0.9 0.0
"""),
}

CORES = {"default": "", "off": "CORE\n0.0 0.0 1.0\n", "chord": "CORE\n0.25 0.0 1.0\n"}

ROWS = ["CX", "CY", "CZ", "Cl", "Cm", "Cn"]
COLS = ["u", "v", "w", "p", "q", "r"]


def run(geo, alpha):
    solver = OVLSolver(geo_file=geo)
    solver.set_variable("alpha", alpha)
    solver.set_variable("beta", 0.0)
    solver.execute_run()
    body = solver.get_body_axis_derivs()
    totals = solver.get_total_forces()
    return {
        "file": geo,
        "alpha_deg": alpha,
        "derivatives": {r + c: float(body[f"d{r}/d{c}"]) for r in ROWS for c in COLS},
        "totals": {k: float(totals[k]) for k in ["CX", "CY", "CZ", "Cl", "Cm", "Cn", "CL", "CD"]},
    }


def main():
    cases = []
    for name, (header, surfaces) in LAYOUTS.items():
        for chordwise in ("cosine", "uniform"):
            if chordwise == "uniform":
                name = name + "_uniform"
                surfaces = surfaces.replace("8 1.0 ", "8 0.0 ")
            for core, line in CORES.items():
                geo = f"{name}_{core}.avl"
                with open(geo, "w") as f:
                    f.write(HEADER.format(**header) + line + surfaces)
                for alpha in (0.0, 5.0):
                    case = run(geo, alpha)
                    case["core"] = core
                    case["chordwise"] = chordwise
                    cases.append(case)
    source = "OptVL 2.5.0 (AVL 3.52-derived core), generate_core.py"
    with open("optvl_core.json", "w") as f:
        json.dump({"source": source, "cases": cases}, f, indent=1)


if __name__ == "__main__":
    main()
