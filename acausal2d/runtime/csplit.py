"""CasADi-generated C cut into translation units, so that they are
compiled in parallel (:mod:`~acausal2d.runtime.cunits`).

CasADi's code generator writes one file: a preamble (the symbol prefix
macros, includes, the ``static`` sparsity patterns, constants and helper
functions), one ``static int casadi_fN(...) { ... }`` body per function,
then the exported wrappers.  :func:`split` spreads the bodies over ``k``
units balanced by size; each unit gets the preamble (its ``static``
definitions, and the helper functions such as ``casadi_sq`` made
``static``, are private to a unit) and the prototypes of every body, which
lose their ``static`` so that the units link (their names carry the file's
CasADi prefix, e.g. ``a2d_model_f0``).  The wrappers and what follows them
(the native driver) stay in the first unit, and so do the preamble's
exported definitions (``CASADI_SYMBOL_EXPORT``).  Text of another shape is
returned as one unit.

Measured (chain of 81 links, 2 cores, a loaded machine): the formulation's
library is two bodies of 265 and 273 kB (residual, iteration matrix), so two
units halve the compile's wall time.  CasADi's ``avoid_stack`` form, which could be cut
anywhere, compiled in 0.43x the wall time but ran the chain 1.8x slower
(warm simulate 1.9 s against 1.05 s).
"""
import re

SPLIT_FROM = 150_000
"""Characters of C from which a file is cut (below, one compiler process
starts faster than two)."""
BODY = re.compile(r"^static int (casadi_f\d+)\(([^)]*)\) \{\n(.*?)^\}\n", re.M | re.S)
"""A function body of CasADi's generated C: name, parameters, body."""
_HELPER = re.compile(r"^(casadi_real|casadi_int|void|int) (casadi_\w+)\(", re.M)
_EXPORTED = re.compile(r"^CASADI_SYMBOL_EXPORT [^\n]*\{(?:[^\n]*\}\n|\n.*?^\}\n)", re.M | re.S)


def split(text, k):
    """The C file ``text`` as a list of at most ``k`` translation units (see
    the module docstring)."""
    bodies = list(BODY.finditer(text)) if len(text) >= SPLIT_FROM else []
    first = bodies[0].start() if bodies else 0
    preamble = _HELPER.sub(r"static \1 \2(", text[:first])     # helpers: one copy per unit
    if not bodies or "CASADI_PREFIX" not in preamble:
        return [text]
    defs = [("int %s(%s);\n" % (m.group(1), m.group(2)), m.group(0)[len("static "):])
            for m in bodies]
    protos = "".join(p for p, _ in defs)
    rest = text[first:]
    for m in reversed(bodies):
        rest = rest[:m.start() - first] + rest[m.end() - first:]
    units = [[] for _ in range(max(1, k))]
    sizes = [len(rest)] + [0] * (len(units) - 1)
    for _, d in sorted(defs, key=lambda d: -len(d[1])):
        j = sizes.index(min(sizes))
        units[j].append(d)
        sizes[j] += len(d)
    out = [preamble + protos + "".join(units[0]) + rest]
    head = _EXPORTED.sub("", preamble) + protos
    out += [head + "".join(u) for u in units[1:] if u]
    return out
