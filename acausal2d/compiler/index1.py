"""The index-1 system handed to IDA, in semi-explicit form.

For a dummy selection, the unknowns ``y`` are all variable nodes of the
index-reduced structure: the states ``x`` (nodes whose derivative node is
not a dummy), the derivative nodes of the states ``v`` and the remaining
algebraic unknowns.  The residual is

    yp[x] - y[der(x)] = 0            (one link per state)
    E(t, y, p, d)     = 0            (all equations, every derivative order)

so the derivatives IDA integrates enter linearly with a constant
coefficient, and every derivative the equations contain is an algebraic
unknown.  (Handing IDA the fully implicit form, with the derivatives of the
states inside nonlinear equations, took 40-400 times as many steps near
singular positions.)  The iteration matrix dF/dy + cj dF/dyp is exact and
sparse; dense below :data:`SPARSE_FROM` unknowns.
"""
import casadi as ca
import numpy as np

from ..errors import SimulationError
from ..language.symbols import time
from .structure import column

SPARSE_FROM = 100          # unknowns from which IDA uses its sparse linear solver
_MAX_MONITOR = 40          # largest dummy block whose determinant is watched
_MAX_DET_NODES = 20000     # ... and the largest symbolic determinant


def _jacobian_y(s, F, y, links, dEdz):
    """dF/dy; the rows of the equations are the system's dE/dz where it is
    given (``dEdz``, over the same symbols): CasADi derives the identical
    expressions (the same serialized functions: belt drive, piston engine,
    pendulum), and the belt drive's 84 x 84 took 0.010 s of its run."""
    if dEdz is None or dEdz.shape != (s.n_eq, s.n_var):
        return ca.jacobian(F, y)
    tail = ca.jacobian(column(links), y) if links else ca.SX(0, s.n_var)
    return ca.vertcat(dEdz, tail)


class Formulation:
    """The semi-explicit index-1 DAE of one dummy selection (see module
    docstring): CasADi functions of (t, y, yp, p, d) for the residual, the
    iteration matrix (extra input cj), the event functions (``n_rel``
    relation crossings, ``n_mon`` determinants of the dummy blocks with a
    choice, ``n_pass`` = 1 determinant of the highest level whose sign
    changes mark singular positions passed)."""

    def __init__(self, s, selection, p, d, crossings, dEdz=None):
        n = s.n_var
        A = s.var_to_diff
        self.n = n
        self.states = np.array(s.state_nodes(selection), dtype=int)
        self.state_deriv = np.array([A[j] for j in self.states], dtype=int)
        self.differential = np.zeros(n, dtype=bool)
        self.differential[self.states] = True
        self.all_deriv = np.array(A.to_diff, dtype=int)
        self.level = np.array(s.var_level, dtype=int)
        if n - s.n_eq != len(self.states):
            raise SimulationError("internal error: index-1 system is not square (%d equations, "
                                  "%d unknowns)" % (s.n_eq + len(self.states), n))
        t = time
        y, yp = column(s.var_sym), ca.SX.sym("yp", n)
        links = [yp[j] - y[A[j]] for j in self.states]
        F = column(list(s.eq_expr) + links)
        cj = ca.SX.sym("cj")
        Jac = _jacobian_y(s, F, y, links, dEdz) + cj * ca.jacobian(F, yp)
        self.sparse = n >= SPARSE_FROM
        self.jac_sparsity = Jac.sparsity()
        args = [t, y, yp, p, d]
        self.res_fn = ca.Function("res", args, [F])
        self.jac_fn = ca.Function("iteration_matrix", args + [cj], [Jac])
        self._events(s, selection, args, crossings)

    def _events(self, s, selection, args, crossings):
        """Event functions: relation crossings, then the determinants of the
        dummy blocks with a choice (monitored), then the highest level's
        (passages); ``det_fn`` evaluates the scanned determinants."""
        g = [crossings] if crossings is not None and crossings.numel() else []
        self.n_rel = g[0].numel() if g else 0
        dets = _watched_determinants(s, selection)
        self.scan_levels = sorted(dets)
        self.monitor_levels = [k for k in self.scan_levels if selection.levels[k].dynamic]
        self.n_mon = len(self.monitor_levels)
        self.n_pass = 1 if 0 in dets else 0     # passages: sign changes of the highest det
        watched = [dets[k] for k in self.monitor_levels] + ([dets[0]] if self.n_pass else [])
        self.det_fn = ca.Function("dets", args, [ca.vertcat(*[dets[k] for k in
                                                              self.scan_levels])]) \
            if self.scan_levels else None
        self.watched_fn = ca.Function("watched", args, [ca.vertcat(*watched)]) \
            if watched else None
        # event values: crossings, |det| a + b of the monitored blocks, the highest
        # det itself (passages), |det| a + b of the highest block (near singular);
        # a = 1/reference, b = -threshold while watched, a = 0, b = 1 otherwise;
        # then each crossing's bias (see runtime.ida.Problem.set_biases)
        k = self.n_mon + self.n_pass
        ab = ca.SX.sym("ab", 2 * k + self.n_rel)
        scaled = [ca.fabs(w) * ab[i] + ab[k + i] for i, w in enumerate(watched)]
        g = [g[0] + ab[2 * k:]] if g else []
        events = g + scaled[:self.n_mon] + watched[self.n_mon:] + scaled[self.n_mon:]
        self.event_fn = ca.Function("events", args + [ab], [ca.vertcat(*events)]) \
            if events else None

    def y_from(self, z):
        """IDA's (y, yp) from consistent node values: yp of a node is the
        value of its derivative node where that exists (exact for states,
        a good predictor for the algebraic unknowns), else 0."""
        y = np.array(z, dtype=float)
        yp = np.zeros_like(y)
        known = self.all_deriv >= 0
        yp[known] = y[self.all_deriv[known]]
        return y, yp


def _watched_determinants(s, selection):
    """{level: det of its dummy block} for the highest level and the levels
    with a choice, where the block is small enough to watch cheaply."""
    dets = {}
    for k, lv in enumerate(selection.levels):
        if not (k == 0 or lv.dynamic) or len(lv.eqs) > _MAX_MONITOR:
            continue
        det = ca.det(ca.jacobian(ca.vertcat(*[s.eq_expr[i] for i in lv.eqs]),
                                 ca.vertcat(*[s.var_sym[j] for j in lv.chosen])))
        if ca.n_nodes(det) <= _MAX_DET_NODES:
            dets[k] = det
    return dets
