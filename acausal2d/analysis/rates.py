"""First and second time derivatives of every variable of a result, from
the index-reduced system itself.

The index reduction differentiates only what the integration needs, so a
result holds ``der(x)`` for some variables and not for others (an output
frame of a VDI element whose mass sits elsewhere, the length of a node
constraint nobody holds).  The missing rates follow from the total time
derivative of the system's equations E(t, z) = 0 at each output point:

    E_z z' + E_t = 0,

with z' known for every node that has a derivative node (its value is in
the result) and unknown for the others; the second derivative likewise
from d/dt (E_z z' + E_t) = 0 with the same matrix.  Both are linear least
squares problems at each output point (overdetermined and consistent),
solved exactly; no output grid is differenced.  Linkages and node models
give rates to round-off; where a run's values do not satisfy the
differentiated equations (seen for stiff belt spans with relations, e.g.
models/pulley_block.py) an error says so instead of returning a guess.
"""
import casadi as ca
import numpy as np

from ..errors import Acausal2dError
from ..language.symbols import time


class Rates:
    """Rates (first and second time derivatives) of the variables of
    ``result``, computed once for all nodes on first use."""

    def __init__(self, result):
        cm = getattr(result, "model", None)
        if cm is None:
            raise Acausal2dError("the result has no compiled model: rates of variables without "
                                 "der() columns need the model's equations")
        self.res, self.system = result, cm.system
        self._z1 = self._z2 = None

    def _function(self):
        s, system = self.system.structure, self.system
        n = s.n_var
        z = ca.vertcat(*s.var_sym)
        E = ca.vertcat(*s.eq_expr)
        zd, zdd = ca.SX.sym("zd", n), ca.SX.sym("zdd", n)
        Ez = ca.jacobian(E, z)
        F = ca.mtimes(Ez, zd) + ca.jacobian(E, time)
        G = ca.mtimes(ca.jacobian(F, z), zd) + ca.jacobian(F, time) + ca.mtimes(Ez, zdd)
        return ca.Function("rates", [time, z, system.p, system.d, zd, zdd], [Ez, F, G])

    def _node_values(self):
        res = self.res
        return np.column_stack([res[name] for name in self.system.node_names])

    def _relations(self, t, z, p):
        """Relation values d at a point from the signs of their crossing functions."""
        system = self.system
        if not system.relations:
            return np.zeros(0)
        d0 = np.zeros(len(system.relations))
        g = np.asarray(system.crossing_fn(t, z, p, d0)).ravel()
        return np.array([r.value(v) for r, v in zip(system.relations, g)])

    def _solve(self):
        s = self.system.structure
        diff = np.array([s.var_to_diff[j] for j in range(s.n_var)])
        known, unknown = np.flatnonzero(diff >= 0), np.flatnonzero(diff < 0)
        fn, Z = self._function(), self._node_values()
        p = np.array([self.res.parameters[name] for name, *_ in self.system.parameters])
        Z1, Z2 = np.empty_like(Z), np.empty_like(Z)
        for k, (t, z) in enumerate(zip(self.res.time, Z)):
            d = self._relations(t, z, p)
            zd = np.zeros(len(z))
            zd[known] = z[diff[known]]
            Ez, F, _ = (np.asarray(a) for a in fn(t, z, p, d, zd, np.zeros(len(z))))
            zd[unknown] = _lstsq(Ez[:, unknown], -F.ravel(), t)
            zdd = np.zeros(len(z))
            zdd[known] = zd[diff[known]]
            _, _, G = (np.asarray(a) for a in fn(t, z, p, d, zd, zdd))
            zdd[unknown] = _lstsq(Ez[:, unknown], -G.ravel(), t)
            Z1[k], Z2[k] = zd, zdd
        self._z1, self._z2 = Z1, Z2

    def of(self, name, order):
        """d^order/dt^order of the variable ``name`` (a node or an eliminated
        alias) at every output point; order 1 or 2."""
        system = self.system
        if name in system.node_names:
            j, sign = system.node_names.index(name), 1.0
        elif name in system.alias_names:
            k = system.alias_names.index(name)
            j, sign = int(system.alias_node[k]), float(system.alias_sign[k])
            if j < 0:
                return np.zeros_like(self.res.time)
        else:
            raise Acausal2dError("no variable %r in the model (rates are taken of variables, "
                                 "not of parameters or expressions)" % name)
        if self._z1 is None:
            self._solve()
        return sign * (self._z1 if order == 1 else self._z2)[:, j]


def _lstsq(A, b, t):
    """Least-squares solution of the (overdetermined, consistent) system;
    an error where it leaves unknowns undetermined (rank deficient) or is
    inconsistent beyond the accuracy of the run's own values (residual
    against the size of each equation's terms)."""
    if A.shape[1] == 0:
        return np.zeros(0)
    x, _, rank, _ = np.linalg.lstsq(A, b, rcond=None)
    scale = np.abs(A) @ np.abs(x) + np.abs(b)
    if rank < A.shape[1] or (np.abs(A @ x - b) > 1e-6 * scale + 1e-9 * scale.max()).any():
        raise Acausal2dError(
            "the rates at t = %.6g cannot be recovered from the model's equations (%s); use a "
            "signal the run holds a der() column of" % (t, "they leave some undetermined"
                                                        if rank < A.shape[1] else
                                                        "the run's values do not satisfy their "
                                                        "time derivative there"))
    return x
