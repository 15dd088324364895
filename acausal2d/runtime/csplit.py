"""CasADi-generated C cut into pieces and translation units, so that it is
compiled in parallel and without the compiler's cost of one huge function
(:mod:`~acausal2d.runtime.cunits`).

CasADi's code generator writes one file: a preamble (the symbol prefix
macros, includes, the ``static`` sparsity patterns, constants and helper
functions), one ``static int casadi_fN(...) { ... }`` body per function,
then the exported wrappers.  With the generator's option ``avoid_stack``
a body of an SX function is a straight sequence of one-line statements on
the work vector ``w``, the inputs ``arg`` and the outputs ``res`` - no
local variable - so it can be cut between any two statements: each run of
:data:`PIECE_LINES` statements becomes a function of its own (hidden
symbol, named with the file's CasADi prefix), and the body calls them in
order: the same operations in the same order, so the same values to the
last bit.  gcc's time on one function grows faster than its length
(measured, chain of 81 links: the 273 kB iteration matrix at -O1 7.5 s of
CPU as one function).

:func:`split` then spreads the definitions over ``k`` units balanced by
size; each unit gets the preamble (its ``static`` definitions are private
to a unit) and the prototypes of every definition.  The wrappers and what
follows them (the native driver) stay in the first unit, and so do the
preamble's exported definitions.  Text of another shape is returned as one
unit.
"""
import re

SPLIT_FROM = 150_000
"""Characters of C from which a file is cut (below, one compiler process
starts faster than two)."""
PIECE_LINES = 1500
_BODY = re.compile(r"^static int (casadi_f\d+)\(([^)]*)\) \{\n(.*?)^\}\n", re.M | re.S)
_EXPORTED = re.compile(r"^CASADI_SYMBOL_EXPORT [^\n]*\{(?:[^\n]*\}\n|\n.*?^\}\n)", re.M | re.S)
_STATEMENT = re.compile(r"^  [^{}]*;$")
_PIECE_ARGS = "const casadi_real** arg, casadi_real** res, casadi_int* iw, casadi_real* w"


def _pieces(name, params, body):
    """[(prototype, definition)] of one body: itself, cut where it can be."""
    lines = body.rstrip("\n").split("\n")
    plain = len(lines) > PIECE_LINES and lines[-1] == "  return 0;" and all(
        _STATEMENT.match(line) and "return" not in line and "casadi_real a" not in line
        for line in lines[:-1])
    if not plain:
        return [("int %s(%s);\n" % (name, params), "int %s(%s) {\n%s}\n" % (name, params, body))]
    out, calls = [], []
    for k, start in enumerate(range(0, len(lines) - 1, PIECE_LINES)):
        piece = "CASADI_PREFIX(%s_p%d)" % (name[len("casadi_"):], k)
        head = "__attribute__((visibility(\"hidden\"))) void %s(%s)" % (piece, _PIECE_ARGS)
        chunk = "\n".join(lines[start:min(start + PIECE_LINES, len(lines) - 1)])
        out.append((head + ";\n", head + " {\n%s\n}\n" % chunk))
        calls.append("  %s(arg, res, iw, w);\n" % piece)
    main = "int %s(%s)" % (name, params)
    return out + [(main + ";\n", main + " {\n%s  return 0;\n}\n" % "".join(calls))]


def split(text, k):
    """The C file ``text`` as a list of at most ``k`` translation units (see
    the module docstring)."""
    bodies = list(_BODY.finditer(text)) if len(text) >= SPLIT_FROM else []
    first = bodies[0].start() if bodies else 0
    preamble = text[:first]
    if not bodies or "CASADI_PREFIX" not in preamble:
        return [text]
    defs = [d for m in bodies for d in _pieces(m.group(1), m.group(2), m.group(3))]
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
