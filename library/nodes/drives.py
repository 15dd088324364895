"""Drive laws of the node/constraint front end: the prescribed value of a
constraint's length or angle as a CasADi expression of time.

* ``speed``: ``z0 + om t`` - Schnabel and Gössner's drives, which add a constant
  increment to the crank angle on every tick (``crank.ang += pi/180``).
* ``mec2``: the drive functions of mec2 (mec.drive.js, goessner/mec2 v0.9.5,
  MIT): ``z(t) = z0 + Dz f(q)`` with ``q = clamp((t - t0)/Dt_total, 0, 1)``
  and the normalized function ``f`` of VDI 2145 / web easing: ``linear``,
  ``quadratic``, ``harmonic``, ``sinoid``, ``poly5``, ``const``,
  ``static`` (positions as ``linear``), ``seq`` (a sequence of segments
  ``{func, dt, dz}``, normalized as mec2 does by the smallest and largest
  value reached after each segment) and Penner's potentials (``inQuad``,
  ``outCubic``, ``inOutQuint``, ...).  ``bounce`` runs the function forth
  and back (the duration doubles), ``repeat`` n times (duration times n).
  mec2 repeats by ``f((q n) mod 1)``, a saw tooth; for an angle whose
  range is a whole number of turns the teeth are joined into one
  continuous (unwrapped) angle, which is the same position.  Other saw
  teeth jump, as in mec2 (the runtime reports the jump).

Every switch of a law is a relation of time alone, so the runtime steps
exactly onto it (time events)."""
import math

import casadi as ca

from acausal2d.errors import ModelDefinitionError

__all__ = ["BASE_FUNCTIONS", "mec2_law", "seq_law", "is_full_turn"]


def _quadratic(q):
    return ca.if_else(q <= 0.5, 2 * q * q, -2 * q * q + 4 * q - 1)


def _pot(n):
    return lambda q: q ** n


def _out_pot(n):
    return lambda q: 1 - (1 - q) ** n


def _in_out_pot(n):
    c = 2.0 ** (n - 1)
    return lambda q: ca.if_else(q < 0.5, c * q ** n, 1 - c * (1 - q) ** n)


BASE_FUNCTIONS = {
    "const": lambda q: 0 * q,
    "linear": lambda q: q,
    "static": lambda q: q,
    "quadratic": _quadratic,
    "harmonic": lambda q: (1 - ca.cos(ca.pi * q)) / 2,
    "sinoid": lambda q: q - ca.sin(2 * ca.pi * q) / (2 * ca.pi),
    "poly5": lambda q: (10 - 15 * q + 6 * q * q) * q ** 3,
}
"""The normalized drive functions f(q), f(0) = 0, f(1) = 1 (mec.drive.js)."""
for _n, _name in ((2, "Quad"), (3, "Cubic"), (4, "Quart"), (5, "Quint")):
    BASE_FUNCTIONS["in" + _name] = _pot(_n)
    BASE_FUNCTIONS["out" + _name] = _out_pot(_n)
    BASE_FUNCTIONS["inOut" + _name] = _in_out_pot(_n)


def seq_law(segments, where="seq"):
    """The normalized function of a mec2 ``seq`` drive: ``segments`` is a
    list of ``{"func": name, "dt": > 0, "dz": number}``; returns f(q)."""
    if not segments:
        raise ModelDefinitionError("%s: a 'seq' drive needs a non-empty list 'args'" % where)
    total, z, lo, hi, parts = 0.0, 0.0, math.inf, -math.inf, []
    for k, seg in enumerate(segments):
        func = seg.get("func")
        if func not in BASE_FUNCTIONS:
            raise ModelDefinitionError("%s[%d].func: unknown drive function %r (known: %s)"
                                       % (where, k, func, ", ".join(sorted(BASE_FUNCTIONS))))
        dt, dz = seg.get("dt"), seg.get("dz", 0.0)
        if not isinstance(dt, (int, float)) or isinstance(dt, bool) or not dt > 0:
            raise ModelDefinitionError("%s[%d].dt must be a number > 0, got %r" % (where, k, dt))
        if not isinstance(dz, (int, float)) or isinstance(dz, bool):
            raise ModelDefinitionError("%s[%d].dz must be a number, got %r" % (where, k, dz))
        parts.append((total, float(dt), z, float(dz), BASE_FUNCTIONS[func]))
        total += dt
        z += dz
        lo, hi = min(lo, z), max(hi, z)
    span = hi - lo
    if span == 0:
        raise ModelDefinitionError("%s: the segments' dz give no motion (all cumulative "
                                   "values equal)" % where)

    def f(q):
        s = q * total
        value = None
        for t_a, dt, z_a, dz, func in reversed(parts):
            piece = z_a + func((s - t_a) / dt) * dz
            value = piece if value is None else ca.if_else(s < t_a + dt, piece, value)
        return (value - lo) / span
    return f


def is_full_turn(func, Dz):
    """True if one run of ``func`` over the range ``Dz`` (rad) is a whole
    number (not 0) of turns, so that repetitions can be joined."""
    span = float(Dz) * float(ca.evalf(func(ca.DM(1.0)) - func(ca.DM(0.0))))
    turns = span / (2 * math.pi)
    return abs(turns) > 0.5 and abs(turns - round(turns)) < 1e-9


def _segment(func, s, bounce):
    if not bounce:
        return func(s)
    return ca.if_else(s < 0.5, func(2 * s), func(2 - 2 * s))


def mec2_law(t, z0, Dz, t0, Dt, func, repeat=None, bounce=False, join_turns=False):
    """z(t) of a mec2 drive as a CasADi expression (see module doc);
    ``func`` is a normalized function f(q); ``join_turns`` joins the teeth
    of a repeated full-turn angle drive into one continuous angle."""
    n = 1 if repeat is None else int(repeat)
    seg_time = Dt * (2 if bounce else 1)
    total = seg_time * n
    if repeat is None:
        inner = _segment(func, (t - t0) / total, bounce)
        end = _segment(func, ca.DM(1.0), bounce)
    else:
        inner = None
        for k in range(n - 1, -1, -1):
            s = (t - t0 - k * seg_time) / seg_time
            piece = _segment(func, s, bounce) + (k if join_turns and not bounce else 0)
            inner = piece if inner is None else ca.if_else(t < t0 + (k + 1) * seg_time,
                                                           piece, inner)
        end = _segment(func, ca.DM(0.0), bounce) + (n if join_turns and not bounce else 0)
    start = _segment(func, ca.DM(0.0), bounce)
    value = ca.if_else(t < t0, start, ca.if_else(t < t0 + total, inner, end))
    return z0 + Dz * value
