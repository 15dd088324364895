"""Static equilibrium: the point where every state derivative is zero.

With the states x of the dummy selection at the start point and their
derivative nodes der(x), the equilibrium solves all index-reduced
equations together with der(x) = 0,

    E(t, z, p, d) = 0,   z[der(x)] = 0,

a square system in all node values z (every velocity and acceleration is
zero then, position constraints and force balances hold).  Newton's method
with a line search and a minimum-norm least-squares step where the Jacobian
is singular, its steps limited to :data:`MAX_MOVE` in every position, runs
from the start values; a start where the Jacobian is singular (a pendulum
started exactly horizontal) or that leads to an unstable equilibrium is
followed by starts with each position state shifted by +-:data:`SHIFTS`
times its nominal value, and the first stable equilibrium is taken (else
the first one found).  Success is judged by the residuals of the
equations at the point, never by the solver's flag.
"""
from dataclasses import dataclass

import numpy as np

from ..errors import Acausal2dError, SimulationError
from .linearize import (OperatingPoint, index1_states, linearize_point, point_at,
                        relation_values)

SHIFTS = (0.3, 1.5)
"""Shifts of a position state for further starts, in units of its nominal value (at least 1)."""
RESIDUAL_TOL = 1e-8
"""Largest residual (of equations scaled by their Jacobian rows) of an equilibrium."""
MAX_STARTS = 25
"""Starts tried at most (the start and 4 shifts of 6 position states)."""
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


def _newton_step(ev, point, z, deriv):
    """(residual, step) of E = 0, der(x) = 0 at z: the least-squares Newton
    step, shortened so that no position moves by more than :data:`MAX_MOVE`
    times its nominal value (Newton's first steps from a flat start would
    otherwise jump by whole turns)."""
    s = ev.system
    E = ev.residual(point.t, z, point.d)
    r = np.concatenate([E, z[deriv]])
    J = np.vstack([ev.jacobian(point.t, z, point.d, dense=True),
                   np.eye(len(z))[deriv]])
    if not (np.all(np.isfinite(J)) and np.all(np.isfinite(r))):
        return r, None
    with np.errstate(all="ignore"):
        dz = -np.linalg.lstsq(J * s.nominal[None, :], r, rcond=1e-12)[0] * s.nominal
    pos = [j for j in s.level0 if s.structure.var_to_diff[j] >= 0]     # differentiated
    move = np.max(np.abs(dz[pos]) / np.maximum(s.nominal[pos], 1.0)) if pos else 0.0
    return r, dz * min(1.0, MAX_MOVE / move) if move > 0 else dz


def _newton(ev, point, deriv, max_iter=100):
    """Damped least-squares Newton on E = 0, der(x) = 0 from ``point``."""
    z = point.z.copy()
    for _ in range(max_iter):
        r, dz = _newton_step(ev, point, z, deriv)
        norm = np.max(np.abs(r)) if r.size else 0.0
        if dz is None or norm < 1e-13:
            break
        step = 1.0
        while step > 1e-6:
            zn = z + step * dz
            rn = np.concatenate([ev.residual(point.t, zn, point.d), zn[deriv]])
            if np.all(np.isfinite(rn)) and np.max(np.abs(rn)) < (1 - 1e-4 * step) * norm:
                break
            step *= 0.5
        else:
            break
        z = zn
    return z


def _solve_from(compiled, ev, point, deriv):
    """Newton from ``point`` with der(x) = 0 (relations re-settled up to
    three times); (point, scaled residual), or (None, inf)."""
    z, d = point.z, point.d
    for _ in range(3):
        z = _newton(ev, OperatingPoint(point.t, z, d, point.p), deriv)
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


def find_equilibrium(compiled, t=0.0, params=None, start=None):
    """The static equilibrium of ``compiled`` at time ``t`` for the
    parameter values ``params``, searched from the model's start values
    (``start``: {node name: value} overrides); see the module docstring.
    Raises :class:`NoEquilibrium` naming the equations that stay unbalanced
    when no start leads to one."""
    from ..runtime.evaluator import Evaluator
    first = _start_point(compiled, float(t), params, start)
    ev = Evaluator(compiled.system, first.p)
    _, states, deriv = index1_states(compiled, ev, first)
    fallback, best = None, (None, float("inf"))
    for k, point in enumerate(_starts(compiled, first, states)):
        if k >= MAX_STARTS:
            break
        found, res = _solve_from(compiled, ev, point, deriv)
        if res < best[1]:
            best = (found, res)
        if res > RESIDUAL_TOL:
            continue
        if _stable(compiled, found):
            return Equilibrium(found, res, True, k + 1)
        fallback = fallback or Equilibrium(found, res, False, k + 1)
    if fallback is not None:
        return fallback
    raise NoEquilibrium(_not_found(compiled, ev, best, deriv))


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
