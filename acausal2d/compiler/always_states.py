"""Pass: variables declared ``state_select="always"`` get a derivative.

A variable such as a joint's ``w`` in ``w == der(phi)`` has no derivative
node after index reduction when no equation is differentiated through it;
it could then never be a state and the declaration would be ignored.  This
pass differentiates the equation matched to such a variable once and lets
Pantelides' reduction go on from there
(:func:`~acausal2d.compiler.pantelides.differentiate_further`): ``der(w) ==
der(der(phi))`` needs the angle's second derivative, so the constraints
through which the angle moves are differentiated once more too.  The
selection then keeps der(w) as a state derivative.  Where 'always' still
cannot be honoured, state selection reports the variable (see
:mod:`~acausal2d.compiler.dummy_derivatives`).
"""
from ..language.dsl import STATE_SELECT
from .pantelides import differentiate_further

_ALWAYS = STATE_SELECT.index("always")


def _candidates(s, priority):
    """(node, equation) pairs to differentiate."""
    out = []
    for j in range(s.n_var):
        if priority[j] != _ALWAYS or s.var_level[j] != 0 or s.var_to_diff[j] >= 0:
            continue
        i = s.matching[j] if j < len(s.matching) else -1
        if i >= 0 and s.eq_to_diff[i] < 0:
            out.append((j, i))
    return out


def differentiate_for_always(s, priority, describe_equation):
    """The structure with the equations of 'always' variables differentiated
    (see module docstring); ``s`` itself is returned when there is none.
    A variable that equals a derivative (``w`` in ``w == der(phi)``) is
    recorded in ``velocity_of``."""
    todo = _candidates(s, priority)
    if not todo:
        return s
    pairs = list(s.velocity_of)
    for j, i in todo:
        others = [k for k in s.eq_vars[i] if k != j]
        if len(others) == 1 and s.var_level[others[0]] >= 1:
            pairs.append((j, others[0]))
    return differentiate_further(s, sorted({i for _, i in todo}), describe_equation,
                                 velocity_of=tuple(pairs))
