"""Reference values for benches/maintained.rs: sin, cos, tan, exp, ln, sqrt and atan2(x, 0.7)
at a few arguments, to 50 digits (mpmath), written as two doubles `hi lo` with hi + lo the
value rounded to about 106 bits. Run: python3 dd_reference.py > dd_reference.txt"""
import mpmath

mpmath.mp.dps = 50
args = ["0.1", "0.7", "1.3", "2.0", "-3.5", "10.0", "37.25", "100.0", "1e-3", "0.5"]
funcs = {
    "sin": mpmath.sin,
    "cos": mpmath.cos,
    "tan": mpmath.tan,
    "exp": mpmath.exp,
    "ln": lambda x: mpmath.log(abs(x)),
    "sqrt": lambda x: mpmath.sqrt(abs(x)),
    "atan2": lambda x: mpmath.atan2(x, mpmath.mpf("0.7")),
}
for name, f in funcs.items():
    for a in args:
        x = mpmath.mpf(float(a))  # the double nearest the argument, exactly
        if name == "exp" and abs(x) > 50:
            continue
        v = f(x)
        hi = float(v)
        lo = float(v - mpmath.mpf(hi))
        print(name, repr(float(a)), repr(hi), repr(lo))
