"""Reports of numbers that went wrong: equations whose residuals are not
finite (a division by zero, the square root of a negative number, an
overflow), named with their components and those components' parameter
values, so that the user sees which element and which value to change."""
import numpy as np

_LIST = 6


def _component_parameters(system, owner, p):
    """'name = value' of the parameters of ``owner``."""
    if owner is None:
        return ""
    prefix = owner.path + "." if owner.path else ""
    vals = ["%s = %.6g" % (name[len(prefix):], p[k]) for k, (name, *_) in
            enumerate(system.parameters) if name.startswith(prefix)
            and "." not in name[len(prefix):]]
    return "; its parameters: %s" % ", ".join(vals[:12]) if vals else ""


def non_finite(system, residual, p):
    """Text naming the equations whose residuals are inf or NaN, or None
    if all are finite."""
    bad = np.nonzero(~np.isfinite(residual))[0]
    if not len(bad):
        return None
    lines, owners = [], []
    for i in bad[:_LIST]:
        owner = system.owner_of_equation(i)
        lines.append("  - %s   (%s)%s" % (system.describe_equation(i), residual[i],
                                           "" if owner in owners else
                                           _component_parameters(system, owner, p)))
        owners.append(owner)
    more = "\n  ... and %d more" % (len(bad) - _LIST) if len(bad) > _LIST else ""
    return ("these equations evaluate to inf or NaN (a division by zero, the square root or "
            "logarithm of a negative number, or an overflow):\n%s%s\nCheck the parameters "
            "named (a zero length or direction, parallel guides, coincident pivots) and the "
            "start values." % ("\n".join(lines), more))
