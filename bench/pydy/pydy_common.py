"""Shared helper: run PyDy's C code generator on a list of sympy matrices."""
import time

import sympy as sm
from pydy.codegen.c_code import CMatrixGenerator


def write_pydy(name, params, mats, path='.'):
    t0 = time.time()
    gen = CMatrixGenerator([params], mats, cse=True)
    hdr, src = gen.doprint(prefix='pydy_' + name)
    t1 = time.time()
    # PyDy always names the function `evaluate`; rename it so several can be linked.
    fn = name + '_pydy'
    hdr = hdr.replace('void evaluate(', 'void %s(' % fn)
    src = src.replace('void evaluate(', 'void %s(' % fn)
    with open('%s/pydy_%s.h' % (path, name), 'w') as f:
        f.write(hdr)
    with open('%s/pydy_%s.c' % (path, name), 'w') as f:
        f.write(src)
    ops_cse = sum(sm.count_ops(e) for _, e in gen.subexprs) + \
        sum(sm.count_ops(e) for M in gen.simplified_matrices for e in M)
    ops_raw = sum(sm.count_ops(e) for M in mats for e in M)
    msg = ('%s: PyDy codegen %.1f s, %d cse subexpressions, count_ops after cse = %d '
           '(before cse %d), outputs %s' % (name, t1 - t0, len(gen.subexprs), ops_cse,
                                            ops_raw, [M.shape for M in mats]))
    print(msg)
    with open('%s/opcounts.txt' % path, 'a') as f:
        f.write(msg + '\n')
    return gen
