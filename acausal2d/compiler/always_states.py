"""Pass: variables declared ``state_select="always"`` get a derivative.

A variable such as a joint's ``w`` in ``w == der(phi)`` has no derivative
node after index reduction when no equation is differentiated through it;
it could then never be a state and the declaration would be ignored.  This
pass differentiates the equation matched to such a variable once, when all
other unknowns of that equation already have derivative nodes (so the new
equation determines exactly the new node der(w)); the selection then keeps
der(w) as a state derivative.  Where that is not possible, state selection
reports the variable (see :mod:`~acausal2d.compiler.dummy_derivatives`).
"""
from dataclasses import replace

import casadi as ca

from ..language.dsl import STATE_SELECT
from ..language.symbols import time
from .structure import DiffMap, NodeBuilder

_ALWAYS = STATE_SELECT.index("always")


def _candidates(s, priority):
    """(node, equation) pairs to differentiate."""
    eq_of = {j: i for j, i in enumerate(s.matching) if i >= 0}
    out = []
    for j in range(s.n_var):
        if priority[j] != _ALWAYS or s.var_level[j] != 0 or s.var_to_diff[j] >= 0:
            continue
        i = eq_of.get(j)
        if i is None or s.eq_to_diff[i] >= 0:
            continue
        if all(s.var_to_diff[k] >= 0 for k in s.eq_vars[i] if k != j):
            out.append((j, i))
    return out


def differentiate_for_always(s, priority):
    """The structure with the equations of 'always' variables differentiated
    (see module docstring); ``s`` itself is returned when there is none."""
    todo = _candidates(s, priority)
    if not todo:
        return s
    nodes = NodeBuilder.of(s)
    exprs, origin, level = list(s.eq_expr), list(s.eq_origin), list(s.eq_level)
    eq_vars, B, matching = list(s.eq_vars), list(s.eq_to_diff.to_diff), list(s.matching)
    pairs = list(s.velocity_of)
    for j, i in todo:
        others = [k for k in s.eq_vars[i] if k != j]
        if len(others) == 1 and s.var_level[others[0]] >= 1:
            pairs.append((j, others[0]))
        dj = nodes.derivative(j)
        inc = sorted(set(s.eq_vars[i]) | {nodes.to_diff[k] for k in s.eq_vars[i]})
        V = ca.vertcat(time, *[nodes.sym[k] for k in s.eq_vars[i]])
        Vdot = ca.vertcat(1, *[nodes.sym[nodes.to_diff[k]] for k in s.eq_vars[i]])
        B[i] = len(exprs)
        exprs.append(ca.jtimes(s.eq_expr[i], V, Vdot))
        origin.append(origin[i])
        level.append(level[i] + 1)
        eq_vars.append(tuple(inc))
        B.append(-1)
        matching.extend([-1] * (len(nodes.sym) - len(matching)))
        matching[dj] = B[i]
    return replace(s, eq_expr=tuple(exprs), eq_origin=tuple(origin), eq_level=tuple(level),
                   eq_vars=tuple(eq_vars), eq_to_diff=DiffMap(tuple(B)),
                   var_sym=tuple(nodes.sym), var_base=tuple(nodes.base),
                   var_level=tuple(nodes.level), var_to_diff=DiffMap(tuple(nodes.to_diff)),
                   matching=tuple(matching), velocity_of=tuple(pairs),
                   _var_index=dict(nodes.index))
