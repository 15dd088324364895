"""Balance and structural-singularity check of the flattened equations.

Builds the bipartite graph equations x unknowns (an unknown is incident to an
equation if it or one of its derivatives appears), finds a maximum matching
and, if it is not perfect, reports which equations over-determine which
unknowns and which unknowns no equation determines (Dulmage-Mendelsohn
coarse decomposition), naming components and equations.
"""
from ..errors import StructuralError
from .incidence import variable_incidence
from .matching import Matching

_LIST = 20


def incidence_rows(equations, variables, table):
    """For each equation the sorted indices of the unknowns (``variables``)
    it contains; derivatives count for their base variable."""
    index = {v.sym.element_hash(): j for j, v in enumerate(variables)}
    syms, inc = variable_incidence([eq.expr for eq in equations], table)
    col = [index.get(table.base_and_level(s)[0].element_hash(), -1) for s in syms]
    return [sorted({col[c] for c in inc.row(i) if col[c] >= 0}) for i in range(len(equations))]


def _names(items, describe):
    lines = [describe(x) for x in items[:_LIST]]
    if len(items) > _LIST:
        lines.append("... and %d more" % (len(items) - _LIST))
    return "\n".join("  - " + s for s in lines)


def _var_desc(v):
    owner = v.owner.describe() if v.owner is not None else "model"
    return "%s (in %s)" % (v.name, owner)


def check_balance(equations, variables, table):
    """Raise :class:`StructuralError` unless the system is square and has a
    perfect structural matching."""
    rows = incidence_rows(equations, variables, table)
    empty = [i for i, r in enumerate(rows) if not r]
    if empty:
        raise StructuralError(
            "Equation without unknowns (it repeats what other equations already state, e.g. "
            "a connection closing a loop of equal potentials, or a value fixed twice):\n%s\n"
            "If the equation is your own, remove it; if it belongs to a library element, a "
            "connection of that element is missing or made twice."
            % _names([equations[i] for i in empty], lambda e: e.describe()))
    n_eq, n_var = len(equations), len(variables)
    m = Matching(rows, n_var).match_all()
    if n_eq == n_var and m.perfect:
        return
    _report(equations, variables, rows, m.col_of)


def _alternating(starts, adjacent, partner):
    """Nodes reachable from ``starts`` along alternating paths: from a node
    to its ``adjacent`` ones on the other side, then back along the
    matching (``partner``).  Returns (this side, other side)."""
    here, there = set(starts), set()
    stack = list(starts)
    while stack:
        a = stack.pop()
        for b in adjacent[a]:
            if b not in there:
                there.add(b)
                back = partner.get(b)
                if back is not None and back not in here:
                    here.add(back)
                    stack.append(back)
    return here, there


def _headline(n_eq, n_var):
    if n_eq > n_var:
        return ("The model is over-determined: %d equations for %d unknowns (%d too many)."
                % (n_eq, n_var, n_eq - n_var))
    if n_eq < n_var:
        return ("The model is under-determined: %d equations for %d unknowns (%d missing)."
                % (n_eq, n_var, n_var - n_eq))
    return ("The model is structurally singular: %d equations and %d unknowns, but some "
            "equations constrain the same unknowns while others are left free." % (n_eq, n_var))


def _over_text(equations, variables, free_eqs, over_eqs, over_vars):
    # the unmatched equations first, then the component equations, then connections
    eqs = sorted(over_eqs, key=lambda i: (i not in free_eqs,
                                          equations[i].origin.startswith("connect("), i))
    return ("These %d equations determine only %d unknowns (%s); one of them is too many - "
            "remove it or add the unknown it should determine:\n%s"
            % (len(eqs), len(over_vars),
               ", ".join(variables[j].name for j in sorted(over_vars)[:_LIST]) or "none",
               _names([equations[i] for i in eqs], lambda e: e.describe())))


def _under_text(equations, variables, free_vars, under_vars, under_eqs):
    parts = ["These unknowns are not determined by any equation (add an equation, connect "
             "the connector, or fix a value):\n%s"
             % _names([variables[j] for j in sorted(free_vars)], _var_desc)]
    vs = sorted(under_vars)
    if len(vs) > len(free_vars):
        parts.append("They compete with %s for the equations:\n%s" % (
            ", ".join(variables[j].name for j in vs if j not in free_vars)[:400],
            _names([equations[i] for i in sorted(under_eqs)], lambda e: e.describe())))
    return parts


def _report(equations, variables, rows, match_eq):
    """The StructuralError for an imperfect matching (Dulmage-Mendelsohn
    coarse decomposition: over- and under-determined parts)."""
    n_eq, n_var = len(equations), len(variables)
    var_of_eq = {i: int(j) for i, j in enumerate(match_eq) if j >= 0}
    eq_of_var = {j: i for i, j in var_of_eq.items()}
    free_eqs = [i for i in range(n_eq) if match_eq[i] < 0]
    free_vars = [j for j in range(n_var) if j not in eq_of_var]
    cols = [[] for _ in range(n_var)]
    for i, r in enumerate(rows):
        for j in r:
            cols[j].append(i)
    parts = [_headline(n_eq, n_var)]
    if free_eqs:
        over_eqs, over_vars = _alternating(free_eqs, rows, eq_of_var)
        parts.append(_over_text(equations, variables, free_eqs, over_eqs, over_vars))
    if free_vars:
        under_vars, under_eqs = _alternating(free_vars, cols, var_of_eq)
        parts.extend(_under_text(equations, variables, free_vars, under_vars, under_eqs))
    raise StructuralError("\n".join(parts))
