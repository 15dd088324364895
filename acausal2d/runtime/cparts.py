"""A large straight-line body cut into parts that gcc compiles quickly
(the background compile of the chain of 81 links at -O1 in <= 5 s).

gcc's -O1 time grows faster than the size of a function: register
allocation and the CSE after it walk the values live at once, and a body of
CasADi's code keeps hundreds of them live.  :func:`partition` rewrites a
straight body ``casadi_fN_s`` (:mod:`~acausal2d.runtime.cstraight`) of at
least :data:`PART_FROM` statements into

- ``casadi_fN_s0``: the values that outputs of more than one part need
  (shared), stored into an array ``S`` on the caller's stack;
- ``casadi_fN_s1`` ... : one part per run of consecutive outputs, about
  :data:`PART` statements each, with the values only its outputs need;
- ``casadi_fN_s``: calls them in this order.

Reads of an input or a constant are written where they are used, so every
part reads the inputs it needs itself; no other value is computed twice.
The operations and their order within each value are unchanged, so are the
values to the last bit.  The parts are ``noinline`` (gcc would inline a
static function called once back into one body), and
:func:`~acausal2d.runtime.csplit.split` spreads them over the translation
units.

A body of another shape, whose parts would share more than
:data:`SHARED_AT_MOST` of its statements (one long computation every output
needs: the belt drive's band geometry) or more than :data:`CARRY_AT_MOST`
values is left as it is.

Measured (chain of 81 links, gcc 12, CPU seconds of one gcc process, a
loaded 2-core machine): model library 3.65 -> 2.03 s, rows library 8.15 ->
3.64 s at -O1; the functions ran as fast as before (res 4.8-5.1 against
5.0-5.2 us per call, the rows' EJ 8.7 against 9.1).
"""
import re

from . import csplit

PART = 500
"""Statements per part, about (measured on the chain: 150-500 compiled
fastest; smaller parts repeat more declarations and reads)."""
PART_FROM = 2 * PART   # statements of a body from which it is cut
SHARED_AT_MOST = 0.25  # fraction of a body's statements its shared part may hold
CARRY_AT_MOST = 8192   # shared values handed on (64 kB on the stack)
NOINLINE = "A2D_NOINLINE"
_MACRO = ("#if defined(__GNUC__) || defined(__clang__)\n#define A2D_NOINLINE "
          "__attribute__((noinline))\n#else\n#define A2D_NOINLINE\n#endif\n")
_BODY = re.compile(r"^static int (casadi_f\d+)_s\(([^)]*)\) \{\n(.*?)^  return 0;\n\}\n",
                   re.M | re.S)
_STATEMENT = re.compile(r"  (a\d+|R\d+\[\d+\])=([^;\n]*);")
_VAR = re.compile(r"\ba(\d+)\b")
_LEAF = re.compile(r"\s*(A\d+\[\d+\]|[-+]?[0-9.]+(?:e[-+]?\d+)?)\s*")
_DEFINE = re.compile(r"^#define (casadi_f\d+)_s CASADI_PREFIX\((f\d+)_s\)\n", re.M)


class _Body:
    """One straight body as a list of statements, each value numbered once
    (CasADi reuses its variables ``aNNNN``)."""

    def __init__(self, lines):
        self.lhs, self.pieces, self.deps, self.leaf = [], [], [], []
        current = {}
        for line in lines:
            m = _STATEMENT.fullmatch(line)
            if m is None:
                raise ValueError(line)
            lhs, rhs = m.groups()
            pieces = _VAR.split(rhs)      # text, variable, text, ...
            for k in range(1, len(pieces), 2):
                pieces[k] = current[pieces[k]]
            node = len(self.lhs)
            self.pieces.append(pieces)
            self.deps.append(pieces[1::2])
            leaf = _LEAF.fullmatch(rhs) if lhs[0] == "a" else None
            self.leaf.append("(%s)" % leaf.group(1) if leaf else None)
            if lhs[0] == "a":
                current[lhs[1:]] = node
                self.lhs.append(None)
            else:
                self.lhs.append(lhs)

    def tags(self, per_group):
        """Each value's part: the group of the outputs that need it, -1
        where outputs of several groups do (shared), None where none does."""
        n = len(self.lhs)
        tag, k = [None] * n, 0
        for i in range(n):
            if self.lhs[i] is not None:
                tag[i] = k // per_group
                k += 1
        for i in range(n - 1, -1, -1):
            t = tag[i]
            if t is None or self.leaf[i]:
                continue
            for d in self.deps[i]:
                if tag[d] is None:
                    tag[d] = t
                elif tag[d] != t:
                    tag[d] = -1
        return tag


def _statement(body, i, ref):
    pieces = list(body.pieces[i])
    for k in range(1, len(pieces), 2):
        d = pieces[k]
        pieces[k] = body.leaf[d] or ref(d)
    lhs = body.lhs[i] or "v%d" % i
    return "  %s=%s;" % (lhs, "".join(pieces))


def _function(name, params, body, nodes, ref, tail=()):
    """The C of one part: its values ``nodes`` in order."""
    values = ["v%d" % i for i in nodes if body.lhs[i] is None]
    lines = ["static %s int %s(%s) {" % (NOINLINE, name, params)]
    lines += ["  casadi_real %s;" % ", ".join(values[k:k + 12]) for k in range(0, len(values), 12)]
    lines += [_statement(body, i, ref) for i in nodes]
    return "\n".join(lines + list(tail) + ["  return 0;", "}\n"])


def _carried(body, tag):
    """Shared value -> its index in ``S``: the shared values a part reads."""
    carry = {}
    for i, t in enumerate(tag):
        if t is None or t < 0 or body.leaf[i]:
            continue
        for d in body.deps[i]:
            if tag[d] == -1 and not body.leaf[d] and d not in carry:
                carry[d] = len(carry)
    return carry


def _plan(body):
    """(tags, groups, shared values, carried values) or None where cutting
    does not pay (see the module docstring)."""
    n, outputs = len(body.lhs), sum(x is not None for x in body.lhs)
    per_group = max(1, outputs * PART // n)
    groups = -(-outputs // per_group)
    if groups < 2:
        return None
    tag = body.tags(per_group)
    shared = [i for i in range(n) if tag[i] == -1 and not body.leaf[i]]
    carry = _carried(body, tag)
    if len(shared) > SHARED_AT_MOST * n or len(carry) > CARRY_AT_MOST:
        return None
    return tag, groups, shared, carry


def _cut(name, params, lines):
    """The parts of one body and the function that calls them, or None."""
    try:
        body = _Body(lines)
    except (ValueError, KeyError):
        return None, 0
    plan = _plan(body)
    if plan is None:
        return None, 0
    tag, groups, shared, carry = plan
    sub = "%s_s%%d" % name
    texts = [_function(sub % 0, params + ", casadi_real* S", body, shared, "v%d".__mod__,
                       ["  S[%d]=v%d;" % (j, i) for i, j in carry.items()])]
    private = [[] for _ in range(groups)]
    for i, t in enumerate(tag):
        if t is not None and t >= 0 and not body.leaf[i]:
            private[t].append(i)

    def ref(d):
        return "S[%d]" % carry[d] if d in carry else "v%d" % d
    texts += [_function(sub % (g + 1), params + ", const casadi_real* S", body, nodes, ref)
              for g, nodes in enumerate(private)]
    names = ", ".join(p.split()[-1].lstrip("*") for p in params.split(","))
    calls = ["  %s(%s, S);" % (sub % k, names) for k in range(groups + 1)]
    main = ["static int %s_s(%s) {" % (name, params),
            "  casadi_real S[%d];" % max(1, len(carry))] + calls + ["  return 0;", "}\n"]
    return "\n".join(texts + ["\n".join(main)]), groups + 1


def partition(text):
    """CasADi's straight-line C ``text`` with its large bodies cut into
    parts (see the module docstring); text without such a body is returned
    as it is."""
    counts = {}

    def replace(m):
        name, params, block = m.groups()
        lines = [x for x in block.split("\n") if x and not x.startswith("  casadi_real ")]
        if len(lines) < PART_FROM:
            return m.group(0)
        cut, counts[name] = _cut(name, params, lines)
        return m.group(0) if cut is None else cut

    out = _BODY.sub(replace, text)
    if out == text:
        return text

    def define(d):
        parts = counts.get(d.group(1), 0)
        return d.group(0) + "".join("#define %s_s%d CASADI_PREFIX(%s_s%d)\n"
                                    % (d.group(1), k, d.group(2), k) for k in range(parts))
    out = _DEFINE.sub(define, out)
    first = _DEFINE.search(out)
    return out[:first.start()] + _MACRO + out[first.start():]


def longest(text):
    """Lines of the longest function body of generated C ``text`` (0 where
    it has none; the bodies as :func:`~acausal2d.runtime.csplit.split`
    finds them): what gcc's -O1 time grows with."""
    return max((m.group(3).count("\n") for m in csplit.BODY.finditer(text)), default=0)
