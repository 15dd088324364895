"""Dummy-derivative state selection (Mattsson & Soederlind 1993) and the
index-1 formulation handed to IDA.

Starting from the highest differentiated equations, each level picks as many
derivative unknowns as there are differentiated equations such that their
Jacobian block is regular; those become *dummy* derivatives (algebraic).
The choice honours state priorities (``state_select``: never < avoid <
default < prefer < always) and, inside one priority class, takes the best
conditioned columns at the current point (QR with column pivoting on
nominal-scaled columns).  Where a class offered a real choice, the level is
*dynamic*: the integrator watches the determinant of the chosen block and
re-selects when it decays (e.g. a slider-crank passing a dead centre).  The
block of the highest level is always watched: when no other choice is better
conditioned, the mechanism itself is at a singular position (a limit
position of a driven linkage, a branch point of a dyad).
"""
import casadi as ca
import numpy as np
import scipy.linalg as sla

from ..language import symbols
from ..language.dsl import STATE_SELECT
from ..errors import SimulationError

_MAX_MONITOR = 40          # largest dummy block whose determinant is watched during a run
_MAX_DET_NODES = 20000     # ... and the largest symbolic determinant


class Level:
    """One step of the selection: equations ``eqs``, candidate derivative
    nodes ``cands``, the chosen dummies and whether there was a choice."""

    __slots__ = ("eqs", "cands", "chosen", "dynamic")

    def __init__(self, eqs, cands, chosen, dynamic):
        self.eqs, self.cands, self.chosen, self.dynamic = eqs, cands, chosen, dynamic


class Selection:
    """Result of :func:`select_dummies`: the set of dummy derivative nodes and
    the levels it was built from."""

    def __init__(self, dummies, levels):
        self.dummies = frozenset(dummies)
        self.levels = levels

    @property
    def dynamic(self):
        return any(lv.dynamic for lv in self.levels)


def _pick(H, prio, need, what):
    """Choose ``need`` columns of H (rows x cands) giving a regular block,
    lowest priority class first; returns (indices, choice_made)."""
    chosen = []
    Q = None
    scale = max(float(np.max(np.abs(H))) if H.size else 0.0, 1e-300)
    tol = 1e-9 * scale
    choice = False
    for cls in range(len(STATE_SELECT)):
        if len(chosen) == need:
            break
        idx = [c for c in range(H.shape[1]) if prio[c] == cls]
        if not idx:
            continue
        M = H[:, idx]
        if Q is not None:
            M = M - Q @ (Q.T @ M)
        _, r, piv = sla.qr(M, pivoting=True, mode="economic")
        d = np.abs(np.diag(r)) if r.size else np.zeros(0)
        k = min(int(np.sum(d > tol)), need - len(chosen))
        if k == 0:
            continue
        if len(idx) > k:        # structurally, another choice was possible
            choice = True
        chosen.extend(idx[p] for p in piv[:k])
        Q, _ = np.linalg.qr(H[:, chosen])
    if len(chosen) < need:
        raise SimulationError(
            "State selection failed: the derivative equations of %s are singular here "
            "(the mechanism is at a singular position or a constraint is redundant)." % what)
    return chosen, choice


def select_dummies(R, n_original, priority, nominal, jacobian):
    """Select dummy derivatives.

    R: :class:`~acausal2d.compiler.pantelides.IndexReduced`; priority[j], nominal[j]:
    per variable node; jacobian(eq_ids, node_ids) -> dense numpy matrix at the
    current point.  Returns a :class:`Selection`.
    """
    lower = {R.A[j]: j for j in range(R.n_var) if R.A[j] >= 0}
    pred = {R.B[i]: i for i in range(R.n_eq) if R.B[i] >= 0}
    h = [c[-1] for c in R.chains(n_original) if len(c) > 1]
    z = None
    dummies, levels = set(), []
    while h:
        if z is None:
            zs = set()
            for i in h:
                zs.update(j for j in R.eq_inc[i] if R.A[j] < 0 and R.var_level[j] >= 1)
            z = sorted(zs)
        H = jacobian(h, z) * np.array([nominal[j] for j in z])[None, :]
        what = ", ".join(sorted({"'%s'" % symbols.base_and_level(R.var_sym[j])[0].name()
                                 for j in z})[:6])
        idx, choice = _pick(H, [priority[j] for j in z], len(h), "the unknowns " + what)
        chosen = [z[k] for k in idx]
        dummies.update(chosen)
        levels.append(Level(list(h), list(z), chosen, choice))
        h = [pred[i] for i in h if R.eq_level[i] >= 2]
        z = sorted(lower[j] for j in chosen if R.var_level[j] >= 2)
    return Selection(dummies, levels)


class Formulation:
    """The index-1 DAE for one dummy selection.

    y holds every variable node except non-dummy derivatives that are not
    themselves differentiated (those are replaced by yp of the node below).
    Link equations ``yp[lower] = y[node]`` tie derivative states.  Provides
    CasADi functions of (t, y, yp, p, d): residual, iteration matrix
    dF/dy + cj dF/dyp, zero crossings and the map to all node values.
    """

    def __init__(self, R, selection, t, p, d, crossings):
        A = R.A
        dummy = selection.dummies
        lower = {A[j]: j for j in range(R.n_var) if A[j] >= 0}
        n_nodes = R.n_var
        is_state = [A[j] >= 0 and A[j] not in dummy for j in range(n_nodes)]
        in_y = [R.var_level[j] == 0 or j in dummy or is_state[j] for j in range(n_nodes)]
        self.y_nodes = [j for j in range(n_nodes) if in_y[j]]
        ypos = {j: k for k, j in enumerate(self.y_nodes)}
        n = len(self.y_nodes)
        self.n = n
        y = ca.SX.sym("y", n)
        yp = ca.SX.sym("yp", n)
        repl = []
        self.sub_nodes, self.sub_from = [], []
        for j in range(n_nodes):
            if in_y[j]:
                repl.append(y[ypos[j]])
            else:
                repl.append(yp[ypos[lower[j]]])
                self.sub_nodes.append(j)
                self.sub_from.append(ypos[lower[j]])
        links = [yp[ypos[lower[j]]] - y[ypos[j]] for j in self.y_nodes
                 if R.var_level[j] >= 1 and j not in dummy]
        node_syms = ca.vertcat(*R.var_sym)
        repl = ca.vertcat(*repl)
        eqs = ca.substitute(ca.vertcat(*R.eq_expr), node_syms, repl)
        F = ca.vertcat(eqs, *links) if links else eqs
        if F.numel() != n:
            raise SimulationError("internal error: index-1 system is not square (%d x %d)"
                                  % (F.numel(), n))
        self.differential = np.array([is_state[j] for j in self.y_nodes], dtype=bool)
        self.y_pos = np.array(self.y_nodes, dtype=int)
        self.sub_nodes = np.array(self.sub_nodes, dtype=int)
        self.sub_from = np.array(self.sub_from, dtype=int)
        self.state_deriv = np.array([A[j] if is_state[j] else -1 for j in self.y_nodes])
        self.all_deriv = np.array([A[j] for j in self.y_nodes])
        cj = ca.SX.sym("cj")
        Jac = ca.jacobian(F, y) + cj * ca.jacobian(F, yp)
        self.sparse = n >= 100
        self.jac_sparsity = Jac.sparsity()
        args = [t, y, yp, p, d]
        self.res_fn = ca.Function("res", args, [F])
        self.jac_fn = ca.Function("iteration_matrix", args + [cj], [Jac])
        # zero crossings: relation functions, then determinants of watched dummy blocks
        g = [ca.substitute(crossings, node_syms, repl)] \
            if crossings is not None and crossings.numel() else []
        self.n_rel = g[0].numel() if g else 0
        # watched dummy blocks: every level with a choice (events trigger a
        # re-selection) and the highest level (scanned for singular positions)
        self.monitor_levels, self.scan_levels, dets = [], [], {}
        for k, lv in enumerate(selection.levels):
            if (k == 0 or lv.dynamic) and len(lv.eqs) <= _MAX_MONITOR:
                Hs = ca.jacobian(ca.vertcat(*[R.eq_expr[i] for i in lv.eqs]),
                                 ca.vertcat(*[R.var_sym[j] for j in lv.chosen]))
                det = ca.det(Hs)
                if ca.n_nodes(det) > _MAX_DET_NODES:
                    continue        # too large to watch cheaply
                dets[k] = ca.substitute(det, node_syms, repl)
                self.scan_levels.append(k)
                if lv.dynamic:
                    self.monitor_levels.append(k)
                    g.append(dets[k])
        self.n_mon = len(self.monitor_levels)
        self.det_fn = ca.Function("dets", args, [ca.vertcat(*[dets[k] for k in self.scan_levels])]) \
            if self.scan_levels else None
        self.det_scan = None    # buffered evaluation of det_fn over many points (singularities)
        self.event_fn = ca.Function("events", args, [ca.vertcat(*g)]) if g else None

    def nodes_from(self, y, yp):
        """Values of all variable nodes from IDA's y and yp (vectors, or
        arrays with one point per row)."""
        y, yp = np.asarray(y), np.asarray(yp)
        z = np.empty(y.shape[:-1] + (len(self.y_pos) + len(self.sub_nodes),))
        z[..., self.y_pos] = y
        z[..., self.sub_nodes] = yp[..., self.sub_from]
        return z

    def y_from(self, z):
        """IDA's (y, yp) from consistent node values; algebraic components get
        their derivative too where it is known, so that IDA's first error
        test sees consistent values."""
        y = z[self.y_pos]
        yp = np.zeros_like(y)
        st = self.all_deriv >= 0
        yp[st] = z[self.all_deriv[st]]
        return y, yp
