"""CasADi-generated function bodies made straight-line C, so that the C
compiler spends less time on them (a cheaper compile).

CasADi's code generator guards every read of an input and every write of an
output: ``a0=arg[1]? arg[1][12] : 0;`` and ``if (res[0]!=0) res[0][7]=a0;``.
Each guard is a branch, so a body of 3000 statements is a control-flow graph
of thousands of blocks, and gcc's -O1 passes (SSA renaming, dead-store
elimination, register allocation) work on that graph.  :func:`straighten`
rewrites a body ``casadi_fN`` into ``casadi_fN_s``, whose inputs and outputs
are plain pointers (``A1[12]``, ``R0[7]``: no branch), and a small
``casadi_fN`` of the original signature that passes a zero array for an
input that is null and scratch memory for an output that is null - what the
guards did - and calls it.  The arithmetic and its order are unchanged, so
are the values to the last bit.

Measured (chain of 81 links, its model library, gcc 12, two units, CPU
seconds of gcc on a loaded 2-core machine): -O1 16.8 -> 10.4 s, -O0 5.4 ->
1.7 s.  A body that uses its inputs or outputs otherwise (a call of another
function, a copy of a whole vector) is left as it is.
"""
import re

_BODY = re.compile(r"^static int (casadi_f\d+)\(const casadi_real\*\* arg, casadi_real\*\* res, "
                   r"casadi_int\* iw, casadi_real\* w, int mem\) \{\n(.*?)^\}\n", re.M | re.S)
_READ = re.compile(r"arg\[(\d+)\]\? arg\[(\d+)\]\[(\d+)\] : 0")
_WRITE = re.compile(r"if \(res\[(\d+)\]!=0\) res\[(\d+)\]\[(\d+)\]=")
_DEFINE = re.compile(r"^#define (casadi_f\d+) CASADI_PREFIX\((f\d+)\)\n", re.M)
_SIGNATURE = "const casadi_real** arg, casadi_real** res, casadi_int* iw, casadi_real* w, int mem"


def _extent(matches):
    """Index -> one past the largest element used, of the guarded vectors."""
    size = {}
    for m in matches:
        if m.group(1) != m.group(2):
            return None
        i, k = int(m.group(1)), int(m.group(3))
        size[i] = max(size.get(i, 0), k + 1)
    return size


def _wrapper(name, reads, writes):
    """The function of CasADi's signature that calls the straight body."""
    lines = ["static int %s(%s) {" % (name, _SIGNATURE)]
    if reads:
        lines.append("  static const casadi_real z[%d];" % max(reads.values()))
    lines.append("  casadi_real *s = 0; int r;")
    if writes:
        nulls = " || ".join("!res[%d]" % i for i in sorted(writes))
        lines.append("  if (%s) { s = (casadi_real*)calloc(%d, sizeof(casadi_real)); "
                     "if (!s) return 1; }" % (nulls, sum(writes.values())))
    call, offset = [], 0
    for i in sorted(reads):
        call.append("arg[%d] ? arg[%d] : z" % (i, i))
    for i in sorted(writes):
        call.append("res[%d] ? res[%d] : s + %d" % (i, i, offset))
        offset += writes[i]
    lines.append("  r = %s_s(%s);" % (name, ", ".join(call + ["iw", "w"])))
    lines.append("  free(s);\n  return r;\n}\n")
    return "\n".join(lines)


def _straight(m):
    """The replacement of one body (the match of :data:`_BODY`)."""
    name, body = m.group(1), m.group(2)
    reads, writes = _extent(_READ.finditer(body)), _extent(_WRITE.finditer(body))
    if reads is None or writes is None:
        return m.group(0)
    flat = _WRITE.sub(r"R\1[\3]=", _READ.sub(r"A\1[\3]", body))
    if "arg[" in flat or "res[" in flat or "mem" in flat:
        return m.group(0)
    params = ["const casadi_real* A%d" % i for i in sorted(reads)]
    params += ["casadi_real* R%d" % i for i in sorted(writes)]
    head = "static int %s_s(%s) {\n" % (name, ", ".join(params + ["casadi_int* iw",
                                                                   "casadi_real* w"]))
    return head + flat + "}\n\n" + _wrapper(name, reads, writes)


def straighten(text):
    """CasADi's generated C ``text`` with its function bodies straight-line
    (see the module docstring); text of another shape is returned as it is."""
    if "CASADI_PREFIX" not in text or "#include <math.h>\n" not in text:
        return text
    out = _BODY.sub(_straight, text)
    if out == text:
        return text
    out = out.replace("#include <math.h>\n", "#include <math.h>\n#include <stdlib.h>\n", 1)
    return _DEFINE.sub(lambda d: "%s#define %s_s CASADI_PREFIX(%s_s)\n"
                       % (d.group(0), d.group(1), d.group(2)), out)
