"""The characteristic polynomial of a model's descriptor pencil with sympy, for comparison with
eom's closed form (sizes and times). Run by hand, not in CI:

    cargo run --release -p tests --example pencil_json -- bicycle > bicycle_pencil.json
    pip install sympy
    python3 det_size.py bicycle_pencil.json [--simplify]

Prints sympy's time and operation count (count_ops) for det(sE − F), before and after
simplification, and eom's operation count of the same polynomial's coefficients.
"""
import json
import re
import sys
import time

import sympy as sp


def to_sympy(text, names):
    text = text.replace("^", "**")
    text = re.sub(r"float\(([^)]*)\)", r"(\1)", text)
    text = re.sub(r"\bln\(", "log(", text)
    # `lambda` is a Python keyword.
    text = re.sub(r"\blambda\b", "lam", text)
    return sp.parse_expr(text, local_dict=names)


def main():
    data = json.load(open(sys.argv[1]))
    simplify = "--simplify" in sys.argv
    names = {n: sp.Symbol(n) for n in data["parameters"]}
    names["lam"] = sp.Symbol("lambda")
    s = sp.Symbol("s")
    E = sp.Matrix([[to_sympy(x, names) for x in row] for row in data["E"]])
    F = sp.Matrix([[to_sympy(x, names) for x in row] for row in data["F"]])
    t = time.time()
    det = (s * E - F).det(method="berkowitz")
    t_det = time.time() - t
    ops = sp.count_ops(det)
    print(f"sympy det(sE - F): {t_det:.1f} s, count_ops {ops}")
    if simplify:
        t = time.time()
        simple = sp.simplify(det)
        print(f"sympy simplify: {time.time() - t:.1f} s, count_ops {sp.count_ops(simple)}")
    print(f"eom: {data['operations']} operations ({data['unique_nodes']} unique nodes) for the "
          f"coefficients of s^{data['zero_roots']} * p(s)")


if __name__ == "__main__":
    main()
