"""Relations pass: comparisons in equations become event-driven discrete values.

Every relation that depends on unknowns or time (``a < b``, ``a <= b`` and the
relations hidden in ``sign``, ``fmin`` and ``fmax``) is replaced by a discrete
symbol ``d`` that holds 0 or 1 between events, and a zero-crossing function
``g`` (positive while the relation is true).  The integrator locates the
zeros of ``g``, flips ``d`` and re-initializes consistently (Modelica event
semantics).  Relations among parameters only stay as they are.  ``fabs`` is
kept continuous.
"""
import casadi as ca

from ..language import symbols

_REL_OPS = (ca.OP_LT, ca.OP_LE, ca.OP_SIGN, ca.OP_FMIN, ca.OP_FMAX)


class Relation:
    """A discrete relation value ``sym`` with zero-crossing function ``g``
    (relation true where g > 0, or g >= 0 when not ``strict``)."""

    __slots__ = ("sym", "g", "strict", "text")

    def __init__(self, sym, g, strict, text):
        self.sym = sym
        self.g = g
        self.strict = strict
        self.text = text

    def value(self, g_value):
        """Relation value (0.0 or 1.0) for a crossing-function value."""
        return 1.0 if (g_value > 0 if self.strict else g_value >= 0) else 0.0


def extract_relations(exprs):
    """Replace relations in the list of scalar SX ``exprs``; returns
    (new_exprs, relations)."""
    if not exprs:
        return exprs, []
    allexpr = ca.vertcat(*exprs)
    syms = ca.symvar(allexpr)
    f = ca.Function("rel_scan", [ca.vertcat(*syms)] if syms else [ca.SX(0, 1)], [allexpr])
    n = f.n_instructions()
    ops = [f.instruction_id(k) for k in range(n)]
    if not any(op in _REL_OPS for op in ops):
        return exprs, []
    dynamic = [s for s in syms if symbols.kind(s) in (symbols.VAR, symbols.TIME)]
    dyn = ca.vertcat(*dynamic) if dynamic else None
    work = {}
    out = [None] * len(exprs)
    relations = []

    def depends(e):
        return dyn is not None and ca.depends_on(e, dyn)

    def relation(g, strict, text):
        d = symbols.new_discrete("rel%d" % len(relations))
        relations.append(Relation(d, g, strict, text))
        return d

    for k in range(n):
        op = ops[k]
        ins = f.instruction_input(k)
        outs = f.instruction_output(k)
        if op == ca.OP_INPUT:
            work[outs[0]] = syms[ins[1]]
        elif op == ca.OP_OUTPUT:
            out[outs[1]] = work[ins[0]]
        elif op == ca.OP_CONST:
            work[outs[0]] = ca.SX(f.instruction_constant(k))
        elif op == ca.OP_PARAMETER:
            raise ValueError("unexpected free parameter in equations")
        else:
            args = [work[i] for i in ins]
            if op in (ca.OP_LT, ca.OP_LE) and depends(args[1] - args[0]):
                g = args[1] - args[0]
                res = relation(g, op == ca.OP_LT, "%s %s %s" % (args[0], "<" if op == ca.OP_LT else "<=", args[1]))
            elif op == ca.OP_SIGN and depends(args[0]):
                d = relation(args[0], True, "%s > 0" % args[0])
                res = 2 * d - 1
            elif op == ca.OP_FMIN and depends(args[1] - args[0]):
                d = relation(args[1] - args[0], True, "%s < %s" % (args[0], args[1]))
                res = ca.if_else(d, args[0], args[1])
            elif op == ca.OP_FMAX and depends(args[0] - args[1]):
                d = relation(args[0] - args[1], True, "%s > %s" % (args[0], args[1]))
                res = ca.if_else(d, args[0], args[1])
            elif len(args) == 1:
                res = ca.SX.unary(op, args[0])
            else:
                res = ca.SX.binary(op, args[0], args[1])
            work[outs[0]] = res
    return out, relations
