"""Pantelides' algorithm: find which equations must be differentiated.

Works on the bipartite graph of equations and variable symbols (every
derivative order of a variable is its own node; ``A[j]`` is the node of
der(j), ``B[i]`` the equation der(i)).  Matching uses only the highest
derivatives.  Whenever an equation cannot be matched, the equations and
variables of the failed augmenting-path search are differentiated
(Pantelides 1988).  The differentiated equations are then built
symbolically (chain rule over the derivative symbols), so library code never
writes velocity or acceleration equations.
"""
from ..language import symbols
from .incidence import variable_incidence
from ..errors import StructuralError


class IndexReduced:
    """Pantelides' result.

    eq_expr[i], eq_origin[i] (index of the original equation), eq_level[i]
    (differentiation order), B[i] (derivative equation or -1);
    var_sym[j], var_base[j] (index of the level-0 variable), var_level[j],
    A[j] (derivative node or -1); assign[j] (matched equation of a highest
    derivative, -1 if none).
    """

    def __init__(self):
        self.eq_expr, self.eq_origin, self.eq_level, self.B, self.eq_inc = [], [], [], [], []
        self.var_sym, self.var_base, self.var_level, self.A = [], [], [], []
        self.assign = []
        self.var_index = {}

    @property
    def n_eq(self):
        return len(self.eq_expr)

    @property
    def n_var(self):
        return len(self.var_sym)

    def chains(self, n_original):
        """For each original equation the list [i, B[i], B[B[i]], ...]."""
        out = []
        for i in range(n_original):
            chain = [i]
            while self.B[chain[-1]] >= 0:
                chain.append(self.B[chain[-1]])
            out.append(chain)
        return out

    def structural_index(self):
        """Largest number of differentiations of an equation (the index is
        this plus one for systems with algebraic variables)."""
        return max(self.eq_level) if self.eq_level else 0


def pantelides(equations, variables, max_differentiations=None):
    """Index reduction of ``equations`` (flatten.Equation) in the unknowns
    ``variables`` (VarInfo); returns :class:`IndexReduced`."""
    R = IndexReduced()

    def var_node(sym):
        k = symbols.key(sym)
        j = R.var_index.get(k)
        if j is not None:
            return j
        base, level = symbols.base_and_level(sym)
        if level > 0:
            lower = var_node(_lower(base, level - 1))
        j = len(R.var_sym)
        R.var_index[k] = j
        R.var_sym.append(sym)
        R.var_base.append(R.var_index[symbols.key(base)] if level > 0 else j)
        R.var_level.append(level)
        R.A.append(-1)
        R.assign.append(-1)
        if level > 0:
            R.A[lower] = j
        return j

    def _lower(base, level):
        s = base
        for _ in range(level):
            s = symbols.derivative_symbol(s)
        return s

    for v in variables:
        var_node(v.sym)
    syms, inc_matrix = variable_incidence([eq.expr for eq in equations])
    col_node = [var_node(sym) for sym in syms]
    for n, eq in enumerate(equations):
        cols = inc_matrix.indices[inc_matrix.indptr[n]:inc_matrix.indptr[n + 1]]
        R.eq_expr.append(eq.expr)
        R.eq_origin.append(n)
        R.eq_level.append(0)
        R.B.append(-1)
        R.eq_inc.append(sorted({col_node[c] for c in cols}))

    if max_differentiations is None:
        max_differentiations = len(equations) + 3
    A, B, assign = R.A, R.B, R.assign
    colV, colE = set(), set()

    def highest(i):
        return [j for j in R.eq_inc[i] if A[j] < 0]

    def augment(i0):
        colE.add(i0)
        stack = [[i0, 0, False, highest(i0)]]
        via = []
        while stack:
            top = stack[-1]
            i, pos, checked, cands = top
            if not checked:
                top[2] = True
                for j in cands:
                    if assign[j] < 0:
                        assign[j] = i
                        for k in range(len(via) - 1, -1, -1):
                            assign[via[k]] = stack[k][0]
                        return True
            advanced = False
            while pos < len(cands):
                j = cands[pos]
                pos += 1
                if j not in colV:
                    colV.add(j)
                    top[1] = pos
                    nxt = assign[j]
                    colE.add(nxt)
                    via.append(j)
                    stack.append([nxt, 0, False, highest(nxt)])
                    advanced = True
                    break
            if not advanced:
                stack.pop()
                if via:
                    via.pop()
        return False

    def differentiate_eq(l):
        inc = set()
        for j in R.eq_inc[l]:
            inc.add(j)
            if A[j] < 0:
                var_node(symbols.derivative_symbol(R.var_sym[j]))
            inc.add(A[j])
        n = len(R.eq_expr)
        R.eq_expr.append(None)        # built symbolically after the structural pass
        R.eq_origin.append(R.eq_origin[l])
        R.eq_level.append(R.eq_level[l] + 1)
        R.B.append(-1)
        R.eq_inc.append(sorted(inc))
        B[l] = n
        return n

    for k in range(len(equations)):
        i = k
        while True:
            colV.clear()
            colE.clear()
            if augment(i):
                break
            if R.eq_level[i] >= max_differentiations:
                raise StructuralError(
                    "Index reduction does not terminate: equation '%s' would be differentiated "
                    "more than %d times. The model is structurally singular (a constraint "
                    "repeats another one or an unknown is missing)."
                    % (equations[R.eq_origin[i]].describe(), max_differentiations))
            for j in list(colV):
                if A[j] < 0:
                    var_node(symbols.derivative_symbol(R.var_sym[j]))
            for l in sorted(colE):
                differentiate_eq(l)
            for j in colV:
                assign[A[j]] = B[assign[j]]
            i = B[i]
    _differentiate_symbolically(R)
    return R


def _differentiate_symbolically(R):
    """Build the expressions of all differentiated equations, one derivative
    order at a time, with a single forward-mode derivative per order."""
    import casadi as ca
    parent = {R.B[i]: i for i in range(R.n_eq) if R.B[i] >= 0}
    level = 1
    while True:
        todo = [i for i in range(R.n_eq) if R.eq_expr[i] is None and R.eq_level[i] == level]
        if not todo:
            break
        nodes = sorted({j for i in todo for j in R.eq_inc[parent[i]]})
        V = ca.vertcat(symbols.time, *[R.var_sym[j] for j in nodes])
        Vdot = ca.vertcat(1, *[R.var_sym[R.A[j]] for j in nodes])
        F = ca.vertcat(*[R.eq_expr[parent[i]] for i in todo])
        dF = ca.vertsplit(ca.jtimes(F, V, Vdot))
        for i, e in zip(todo, dF):
            R.eq_expr[i] = e
        level += 1
