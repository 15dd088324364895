"""Static equilibrium: the point where every state derivative is zero.

With the states x of the dummy selection at the start point and their
derivative nodes der(x), the equilibrium solves all index-reduced
equations together with der(x) = 0,

    E(t, z, p, d) = 0,   z[der(x)] = 0,

a square system in all node values z (every velocity and acceleration is
zero then, position constraints and force balances hold).  It is solved by
Newton's method on the state rates f(x) = z[der(x)] with the exact rate
Jacobian A (:mod:`~acausal2d.analysis.linearize`), together with the
invariants of the motion (nodes v with an equation der(v) = 0, such as a
belt span's material constant, held at their values of the start point;
minimum-norm least squares where A is singular), every iterate made consistent by the runtime's Newton on all
equations with the states held
(:func:`acausal2d.runtime.newton.solve_consistent`), the steps limited to
:data:`MAX_MOVE` in every position state and halved while the rates do not
decrease.  A start where A is singular (a pendulum started exactly
horizontal) or that leads to an unstable equilibrium is followed by starts
with each position state shifted by +-:data:`SHIFTS` times its nominal
value, and the first stable equilibrium is taken (else the first one
found).  Success is judged by the residuals of all equations at the point
(scaled by their Jacobian rows), never by the solver's flag.

The equilibrium is unique only up to the model's invariants (zero
eigenvalues of A): those written as der(v) = 0 are kept at the start
point's values, the others (a free rotation, the gas mass in a closed
cylinder) stay near them (minimum-norm steps); a start moved along them
leads to another equilibrium of the same equations.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..errors import Acausal2dError, SimulationError
from .linearize import (OperatingPoint, index1_states, linearize_point, point_at,
                        relation_values)
from ..runtime.newton import NoConvergence, solve_consistent
from ..runtime.evaluator import Evaluator

if TYPE_CHECKING:
    from ..protocols import CompiledData, Params, Start

SHIFTS = (0.3, 1.5)
"""Shifts of a position state for further starts, in units of its nominal value (at least 1)."""
RESIDUAL_TOL = 1e-8
"""Largest residual (of equations scaled by their Jacobian rows) of an equilibrium."""
MAX_STARTS = 25
"""Starts tried at most (the start and 4 shifts of 6 position states)."""
CONTINUATION_STEPS = 8
"""Steps of the parameter continuation (see :func:`find_equilibrium`)."""
MAX_MOVE = 0.2
"""Largest change of a position in one Newton step, in units of its nominal value (at least 1)."""


class NoEquilibrium(Acausal2dError):
    """No point with all state derivatives zero was found."""


@dataclass
class Equilibrium:
    """An equilibrium ``point``, its largest scaled ``residual``, whether it
    is ``stable`` (no eigenvalue with positive real part) and the number of
    ``starts`` it took."""
    point: OperatingPoint
    residual: float
    stable: bool
    starts: int


def _start_point(compiled, t, params, start):
    """Consistent values at t from the model's start values, with the
    node values ``start`` {name: value} put in."""
    ip = compiled.initial_point(t, params)
    z = np.array(ip.z, dtype=float)
    names = {n: j for j, n in enumerate(compiled.system.node_names)}
    for name, value in (start or {}).items():
        if name not in names:
            raise Acausal2dError("unknown start value %r: give node values such as %s"
                                 % (name, ", ".join(compiled.system.node_names[:6])))
        z[names[name]] = float(value)
    return OperatingPoint(t, z, np.array(ip.d, dtype=float), compiled.parameter_values(params),
                          "equilibrium")


def scaled_residual(ev, point, deriv):
    """Largest residual of E and der(x) = 0 at the point, each equation
    divided by the norm of its Jacobian row times the nominal values."""
    r = np.concatenate([ev.residual(point.t, point.z, point.d), point.z[deriv]])
    J = ev.jacobian(point.t, point.z, point.d, dense=True) * ev.system.nominal[None, :]
    scale = np.concatenate([np.maximum(np.linalg.norm(J, axis=1), 1e-300),
                            ev.system.nominal[deriv]])
    return float(np.max(np.abs(r) / scale)) if r.size else 0.0


def invariant_nodes(system):
    """Nodes v held constant by an equation ``der(v) == 0`` of their own
    (e.g. a belt span's material constant ``l_u0``, recovered from its
    strain state): the invariants of the motion the equilibrium keeps."""
    st = system.structure
    A = st.var_to_diff
    zero_rate = {vars_[0] for vars_ in st.eq_vars if len(vars_) == 1}
    return np.array([j for j in range(st.n_var) if A[j] >= 0 and A[j] in zero_rate
                     and st.var_level[j] == 0], dtype=int)


def step_scale(system):
    """The Newton step's scale of every node: its nominal value, at least 1
    for a position (a node with a velocity and an acceleration) and its
    derivatives, as :data:`MAX_MOVE` and :data:`SHIFTS` count.  A relative
    position's nominal (Modelica's ``phi_nominal = 1e-4``) sets the error
    control of its integration; as the Newton's scale it would make a free
    position (a trolley on a damper) dominate every step's norm."""
    st = system.structure
    A = np.asarray(st.var_to_diff.to_diff)
    level = np.asarray(st.var_level)
    vel = np.where(A >= 0, A, 0)
    chain = (level == 0) & (A >= 0) & (A[vel] >= 0)
    for _ in range(2):                  # velocities, accelerations
        nxt = A[np.nonzero(chain)[0]]
        chain[nxt[nxt >= 0]] = True
    return np.where(chain, np.maximum(system.nominal, 1.0), system.nominal)


class _Step:
    """The Newton system of E = 0, der(x) = 0, invariants held, linearised
    at one consistent point z: ``solve(z')`` is the scaled (:func:`step_scale`)
    minimum-norm step -J^+ F(z') with this point's Jacobian J (the step at
    z' for the natural monotonicity test uses the same J)."""

    def __init__(self, ev, point, z, deriv, held):
        s = ev.system
        self.ev, self.point, self.deriv, self.held = ev, point, deriv, held
        self.inv = np.array(sorted(held), dtype=int)
        n = len(z)
        J = np.vstack([ev.jacobian(point.t, z, point.d, dense=True), np.eye(n)[deriv],
                       np.eye(n)[self.inv]]) * step_scale(s)[None, :]
        self.ok = bool(np.all(np.isfinite(J)))
        self.pinv = np.linalg.pinv(J, rcond=1e-12) if self.ok else None

    def solve(self, z):
        """Scaled step dz / step_scale at z (None where not finite)."""
        F = np.concatenate([self.ev.residual(self.point.t, z, self.point.d), z[self.deriv],
                            z[self.inv] - np.array([self.held[j] for j in self.inv])])
        if not np.all(np.isfinite(F)):
            return None
        return -self.pinv @ F


def _limited(ev, states, dz):
    """(dx, fraction): the states' part of the scaled step dz in node
    units, shortened by ``fraction`` so that no position state moves by
    more than MAX_MOVE times its nominal value (at least 1)."""
    s = ev.system
    dx = dz[states] * step_scale(s)[states]
    pos = np.array([s.structure.var_level[j] == 0 for j in states], dtype=bool)
    limit = MAX_MOVE * np.maximum(s.nominal[states], 1.0)
    move = np.max(np.abs(dx[pos]) / limit[pos]) if np.any(pos) else 0.0
    return (dx / move, 1.0 / move) if move > 1.0 else (dx, 1.0)


def _newton(compiled, ev, point, states, deriv, max_iter=100):
    """Damped Newton (see the module docstring): every iterate consistent,
    the step of the whole system applied to the states (selected anew at
    every iterate, as the runtime would), halved until the next step with
    the same Jacobian is shorter (natural monotonicity).  Returns z."""
    try:                    # a shifted start: the other unknowns follow the states first
        z = solve_consistent(ev, point.t, point.z, point.d, states, point.z[states])
    except NoConvergence:
        return point.z
    held = {int(j): float(z[j]) for j in invariant_nodes(ev.system)}
    for _ in range(max_iter):
        try:
            _, states, deriv = index1_states(compiled, ev, OperatingPoint(
                point.t, z, point.d, point.p))
        except SimulationError:
            break
        newton = _Step(ev, point, z, deriv, held)
        dz = newton.solve(z) if newton.ok else None
        if dz is None or np.max(np.abs(dz)) < 1e-14:
            break
        dx, fraction = _limited(ev, states, dz)
        z_next = _damped(ev, point, z, states, dx, newton, np.linalg.norm(dz), fraction)
        if z_next is None:
            break
        z = z_next
    return z


def _damped(ev, point, z, states, dx, newton, size, fraction):
    """The consistent point at z[states] + lambda dx for the largest lambda
    (1, 1/2, ...) whose next Newton step (same Jacobian) is shorter than
    (1 - lambda fraction / 4) ``size`` (Deuflhard's natural monotonicity
    test; ``fraction``: the share of the full step dx is); None."""
    lam = 1.0
    while lam > 1e-6:
        try:
            zn = solve_consistent(ev, point.t, z, point.d, states, z[states] + lam * dx)
            nxt = newton.solve(zn)
            if nxt is not None and np.linalg.norm(nxt) < (1 - lam * fraction / 4) * size:
                return zn
        except NoConvergence:
            pass
        lam *= 0.5
    return None


def _solve_from(compiled, ev, point, states, deriv):
    """Newton from ``point`` with der(x) = 0 (relations re-settled up to
    three times); (point, scaled residual), or (None, inf)."""
    z, d = point.z, point.d
    for _ in range(3):
        z = _newton(compiled, ev, OperatingPoint(point.t, z, d, point.p), states, deriv)
        new_d = relation_values(compiled, point.t, z, point.p)
        if np.array_equal(new_d, d):
            break
        d = new_d
    found = OperatingPoint(point.t, z, d, point.p, "equilibrium")
    res = scaled_residual(ev, found, deriv)
    return (found, res) if np.isfinite(res) else (None, float("inf"))


def _starts(compiled, point, states):
    """The start point, then each position state shifted by +-SHIFTS."""
    s = compiled.system
    yield point
    positions = [j for j in states if s.structure.var_level[j] == 0]
    for shift in SHIFTS:
        for j in positions:
            for sign in (-1.0, 1.0):
                z = point.z.copy()
                z[j] += sign * shift * max(s.nominal[j], 1.0)
                yield OperatingPoint(point.t, z, point.d, point.p, "equilibrium")


def _stable(compiled, point):
    """No eigenvalue of the linearisation with a positive real part."""
    try:
        A = linearize_point(compiled, point).A
    except SimulationError:
        return False
    lam = np.linalg.eigvals(A) if A.size else np.zeros(0)
    scale = max(1.0, float(np.max(np.abs(lam)))) if lam.size else 1.0
    return bool(np.all(lam.real <= 1e-7 * scale))


def _search(compiled, first):
    """(Equilibrium or None, best (point, residual), evaluator, deriv) of the
    starts from the point ``first`` (see the module docstring)."""
    ev = Evaluator(compiled.system, first.p)
    _, states, deriv = index1_states(compiled, ev, first)
    fallback, best = None, (None, float("inf"))
    for k, point in enumerate(_starts(compiled, first, states)):
        if k >= MAX_STARTS:
            break
        found, res = _solve_from(compiled, ev, point, states, deriv)
        if res < best[1]:
            best = (found, res)
        if res > RESIDUAL_TOL:
            continue
        if _stable(compiled, found):
            return Equilibrium(found, res, True, k + 1), best, ev, deriv
        fallback = fallback or Equilibrium(found, res, False, k + 1)
    return fallback, best, ev, deriv


def _continuation(compiled, first, p0):
    """Equilibria along the parameters from the model's own values ``p0`` to
    ``first.p`` in :data:`CONTINUATION_STEPS` steps, each the start of the
    next; the last one, or None where a step finds none."""
    z, d = first.z, first.d
    for k in range(1, CONTINUATION_STEPS + 1):
        p = p0 + (first.p - p0) * k / CONTINUATION_STEPS
        found = _search(compiled, OperatingPoint(first.t, z, d, p, "equilibrium"))[0]
        if found is None:
            return None
        z, d = found.point.z, found.point.d
    return found


def find_equilibrium(compiled: CompiledData, t: float = 0.0, params: Params | None = None,
                     start: Start | None = None) -> Equilibrium:
    """The static equilibrium of ``compiled`` at time ``t`` for the
    parameter values ``params``, searched from the model's start values
    (``start``: {node name: value} overrides); see the module docstring.
    Where no start leads to one and ``params`` change the model's values,
    the search follows the equilibrium from those values in steps
    (parameter continuation).  Raises :class:`NoEquilibrium` naming the
    equations that stay unbalanced when no start leads to one."""
    first = _start_point(compiled, float(t), params, start)
    found, best, ev, deriv = _search(compiled, first)
    p0 = compiled.parameter_values()
    if found is None and not np.array_equal(p0, first.p):
        found = _continuation(compiled, first, p0)
    if found is None:
        raise NoEquilibrium(_not_found(compiled, ev, best, deriv))
    return found


def _not_found(compiled, ev, best, deriv):
    """The message of a failed search: the largest residuals left."""
    name = type(compiled.model).__name__
    point, res = best
    if point is None:
        return "%s has no equilibrium: Newton found no finite point" % name
    s = compiled.system
    r = np.abs(np.concatenate([ev.residual(point.t, point.z, point.d), point.z[deriv]]))
    worst = []
    for i in np.argsort(-r)[:3]:
        worst.append(s.describe_equation(i) if i < s.structure.n_eq else
                     "%s = 0" % s.node_names[deriv[i - s.structure.n_eq]])
    return ("%s has no equilibrium at t=%g for these inputs: no start reached all state "
            "derivatives zero (smallest scaled residual %.3g, needed %.0e); unbalanced:\n%s\n"
            "Change the loads or the parameters, or give start values nearer an equilibrium."
            % (name, point.t, res, RESIDUAL_TOL, "\n".join("  - " + w for w in worst)))


def operating_point(compiled, at=None, equilibrium=False, params=None, start=None, rtol=None):
    """The point to linearise at: time ``at`` of a run (the start point by
    default, see :func:`~acausal2d.analysis.linearize.point_at`) or, with
    ``equilibrium=True``, the static equilibrium at time ``at`` (default
    0) found from the start values (``start``: {node name: value})."""
    if equilibrium:
        return find_equilibrium(compiled, t=at or 0.0, params=params, start=start).point
    if start:
        raise Acausal2dError("start values are for the equilibrium search; a point of a run "
                             "starts from the model's own start values")
    return point_at(compiled, at, params, rtol)
