"""Instantaneous poles, ratio and Drehschubstrecke (dissertation ch. 2.6,
eq. 2.5-2.10, Bild 2.10-2.14) and transfer functions of order 0, 1, 2
(eq. 2.2-2.4), all from a run's own derivatives.

The velocities and accelerations come from the result's ``der(...)``
columns, which the index reduction produced and the integrator solved
together with the positions, and for variables without such a column
from the total time derivative of the model's equations
(:mod:`acausal2d.analysis.rates`); nothing here differences the output
grid.

A *link* is named by

* a frame with ``.x``, ``.y``, ``.phi`` columns (``"crank.frame_b"``), or
* a constraint of a node model (``"A0A"``: its first node ``A0A.a.x``,
  ``A0A.a.y`` and its angle ``A0A.w``), or
* a tuple ``(x_name, y_name, phi_name)`` of signals, or
* ``"ground"`` (or None): the frame link.

Poles are handled in homogeneous coordinates ``(X, Y, W)``: the point
``(X/W, Y/W)``, or for ``W = 0`` the direction ``(X, Y)`` of a pole at
infinity (a prismatic pair).  The velocity field of link i is
``v(P) = c_i + w_i k x P`` with ``c_i = v_i - w_i k x r_i``; the pole of
links i and j is where both fields agree,
``(w_i - w_j) k x P = c_j - c_i``.  :func:`kennedy_poles` builds the poles
not at joints from those at joints by the theorem of Aronhold and Kennedy
(three poles of three links lie on one line), as the dissertation's figures do.
"""
import itertools

import numpy as np

from ..errors import Acausal2dError
from .rates import Rates

GROUND = "ground"
"""Name of the frame link (velocity zero)."""

_INFINITE = 1e-12
"""A pole with |W| <= _INFINITE * |(X, Y)| (farther than 1e12 length
units) is at infinity."""


# ------------------------------------------------------------- derivatives
def derivative(res, name, order=1):
    """The ``order``-th (1 or 2) time derivative of the signal ``name``:
    the run's ``der(...)`` column where the index reduction made one, else
    the total time derivative of the model's equations at each output
    point (:class:`acausal2d.analysis.rates.Rates`); zero for parameters."""
    col = name
    for _ in range(order):
        col = "der(%s)" % col
    if col in res.names:
        return np.asarray(res[col], dtype=float)
    if name == "time":
        return np.ones_like(res.time) if order == 1 else np.zeros_like(res.time)
    if name in res.parameters:
        return np.zeros_like(res.time)
    res[name]                                      # an unknown name raises here
    if order not in (1, 2):
        raise Acausal2dError("derivatives of order 1 and 2 only, not %r" % (order,))
    rates = res.__dict__.get("_rates")
    if rates is None:
        rates = res.__dict__["_rates"] = Rates(res)
    return rates.of(name, order)


# ------------------------------------------------------------------ links
def link_columns(res, spec):
    """(x, y, phi) signal names of the link ``spec`` (see the module doc),
    or None for the ground."""
    if spec is None or spec == GROUND:
        return None
    if isinstance(spec, (tuple, list)) and len(spec) == 3:
        for name in spec:
            res[name]
        return tuple(spec)
    if isinstance(spec, str):
        for cols in ((spec + ".x", spec + ".y", spec + ".phi"),
                     (spec + ".a.x", spec + ".a.y", spec + ".w")):
            if all(c in res for c in cols):
                return cols
    raise Acausal2dError(
        "%r is no link of the result: give a frame with .x, .y, .phi (e.g. 'crank.frame_b'), "
        "a node-model constraint id (e.g. 'A0A'), a tuple (x, y, phi) of signal names or "
        "'ground'" % (spec,))


class _Names:
    """Signal names standing in for a result when links are checked before
    a run (``in`` and ``[]`` as on a result)."""

    def __init__(self, names):
        self.names = set(names)

    def __contains__(self, name):
        return name in self.names

    def __getitem__(self, name):
        if name not in self.names:
            raise Acausal2dError("no signal %r in the model" % (name,))


def check_links(links, names):
    """Raise :class:`~acausal2d.errors.Acausal2dError` unless every link of
    ``links`` ({label: link}) names signals among ``names``."""
    for spec in links.values():
        link_columns(_Names(names), spec)


def link_motion(res, spec):
    """Position r (n, 2), velocity v (n, 2) and angular velocity w (n,) of
    a point of the link ``spec``."""
    cols = link_columns(res, spec)
    n = len(res.time)
    if cols is None:
        z = np.zeros((n, 2))
        return z, z.copy(), np.zeros(n)
    x, y, phi = cols
    r = np.column_stack([res[x], res[y]]).astype(float)
    v = np.column_stack([derivative(res, x), derivative(res, y)])
    return r, v, derivative(res, phi)


def _field_offset(res, spec):
    """(c, w) of the link's velocity field v(P) = c + w k x P."""
    r, v, w = link_motion(res, spec)
    c = v - w[:, None] * np.column_stack([-r[:, 1], r[:, 0]])
    return c, w


def angular_velocity(res, link, ref=GROUND):
    """phi_dot of ``link`` relative to ``ref`` (Ebert 2015: phi_dot_ij = w_i - w_j)."""
    return link_motion(res, link)[2] - link_motion(res, ref)[2]


# ------------------------------------------------------------------ poles
def pole_homogeneous(res, link_i, link_j=GROUND):
    """Homogeneous coordinates (n, 3) of the relative pole P_ij from the
    links' velocity fields: (u_y, -u_x, w_i - w_j), u = c_j - c_i."""
    ci, wi = _field_offset(res, link_i)
    cj, wj = _field_offset(res, link_j)
    u = cj - ci
    return np.column_stack([u[:, 1], -u[:, 0], wi - wj])


def cartesian(hom):
    """Points (n, 2) of homogeneous poles; NaN for poles at infinity."""
    hom = np.atleast_2d(hom)
    W = hom[:, 2]
    far = np.abs(W) <= _INFINITE * np.hypot(hom[:, 0], hom[:, 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        pts = hom[:, :2] / W[:, None]
    pts[far] = np.nan
    return pts


def _unit(hom):
    norm = np.linalg.norm(hom, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return hom / norm[:, None]


def kennedy(p_ik, p_jk, p_il, p_jl):
    """Pole P_ij by Aronhold-Kennedy: the intersection of the line through
    P_ik and P_jk with the line through P_il and P_jl (homogeneous, (n, 3)
    each; poles at infinity allowed).  Rows where the two lines coincide
    come out as NaN."""
    a = np.cross(_unit(p_ik), _unit(p_jk))
    b = np.cross(_unit(p_il), _unit(p_jl))
    p = np.cross(_unit(a), _unit(b))
    bad = np.linalg.norm(p, axis=1) < 1e-9
    p[bad] = np.nan
    return p


def _pair(i, j):
    return (i, j) if i < j else (j, i)


def kennedy_poles(labels, known):
    """All poles of the links ``labels`` from the ``known`` ones ({(i, j):
    homogeneous (n, 3)}, e.g. the poles at the joints) by repeated
    Aronhold-Kennedy constructions; returns the completed dict.  A pole
    that no pair of known lines fixes is left out."""
    poles = {_pair(i, j): p for (i, j), p in known.items()}
    progress = True
    while progress:
        progress = False
        for i, j in itertools.combinations(sorted(labels), 2):
            if (i, j) not in poles:
                p = _construct(labels, poles, i, j)
                if p is not None:
                    poles[(i, j)] = p
                    progress = True
    return poles


def _construct(labels, poles, i, j):
    """P_ij from two other links k, l whose poles with i and j are known."""
    for k, l in itertools.combinations([m for m in labels if m not in (i, j)], 2):
        keys = [_pair(i, k), _pair(j, k), _pair(i, l), _pair(j, l)]
        if all(key in poles for key in keys):
            p = kennedy(*(poles[key] for key in keys))
            if not np.isnan(p).all():
                return p
    return None


def poles(res, links, joints=None):
    """Instantaneous poles P_ij of the links ``links`` ({label: link spec},
    see the module doc; include the ground, e.g. ``{"1": "ground", "2":
    "A0A", ...}`` as the dissertation numbers them) at every output time.

    Returns {(i, j): points (n, 2)} for every pair i < j, NaN where the
    pole is at infinity.  Without ``joints`` every pole comes from the two
    links' velocity fields; with ``joints`` (pairs of labels joined by a
    revolute, prismatic or rolling joint) only those poles do and the
    others are constructed by Aronhold-Kennedy (:func:`kennedy_poles`).
    ``joints`` may also map pairs to the joint's point (a frame or node
    name, or (x_name, y_name); None: from the velocities): the pole of a
    revolute joint is its centre, also where the two links happen to turn
    at the same rate and the velocity fields leave it undetermined."""
    labels = list(links)
    if joints is None:
        known = {(i, j): pole_homogeneous(res, links[i], links[j])
                 for i, j in itertools.combinations(sorted(labels), 2)}
        return {key: cartesian(p) for key, p in sorted(known.items())}
    at = joints if isinstance(joints, dict) else dict.fromkeys(map(tuple, joints))
    known = {_pair(i, j): pole_homogeneous(res, links[i], links[j]) if point is None
             else _joint_point(res, point) for (i, j), point in at.items()}
    return {key: cartesian(p) for key, p in sorted(kennedy_poles(labels, known).items())}


def _joint_point(res, point):
    """Homogeneous pole (x, y, 1) of a revolute joint at the point ``point``:
    a frame or node name (its .x, .y) or a pair (x_name, y_name)."""
    x, y = (point + ".x", point + ".y") if isinstance(point, str) else point
    return np.column_stack([res[x], res[y], np.ones_like(res.time)])


# ------------------------------------------------------- ratio, Drehschub
def ratio(res, out, inp, ref=GROUND, in_ref=None):
    """Ratio i = phi_dot_(out, ref) / phi_dot_(inp, in_ref) (eq. 2.5: simple
    ratio i_41-21 with a common reference; eq. 2.6/2.7: diagonal ratio
    i_34-21 with ``in_ref`` another link).  NaN where the input stands."""
    num = angular_velocity(res, out, ref)
    den = angular_velocity(res, inp, ref if in_ref is None else in_ref)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(den != 0, num / den, np.nan)


def turn_slide(res, slide, crank, crank_ref=GROUND):
    """Drehschubstrecke r = x_dot / phi_dot (eq. 2.8; diagonal eq. 2.9,
    2.10): ``slide`` is the signal of the slide coordinate of the sliding
    link on its guide (``prismatic.s``, a node constraint's length
    ``AB0B.r``; for the diagonal form a guide that turns itself), ``crank``
    the turning link and ``crank_ref`` its reference link.  NaN where the
    crank stands."""
    xd = derivative(res, slide)
    w = angular_velocity(res, crank, crank_ref)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(w != 0, xd / w, np.nan)


def directed_ratio(p_a, p_b, p_c):
    """lambda with (p_c - p_a) = lambda (p_c - p_b): the ratio of the directed
    pole distances a->c over b->c of three collinear poles (eq. 2.5:
    i_41-21 = 12-24 / 14-24 with a = P12, b = P14, c = P24)."""
    u, v = p_c - p_a, p_c - p_b
    return np.sum(u * v, axis=-1) / np.sum(v * v, axis=-1)


# ------------------------------------------------------ transfer functions
def transfer(res, q, p, orders=(0, 1, 2)):
    """Transfer functions of the signal ``q`` over the drive coordinate
    ``p`` (eq. 2.2-2.4): order 0 is q itself, order 1 q' = q_dot / p_dot
    (eq. 2.3), order 2 q'' = (q_ddot - q' p_ddot) / p_dot^2 (eq. 2.4), from
    the run's first and second time derivatives.  Returns {order: array};
    NaN where the drive stands (p_dot = 0).  A drive coordinate that does
    not move over the run is an error naming it (nothing to plot over)."""
    bad = [o for o in orders if o not in (0, 1, 2)]
    if bad:
        raise Acausal2dError("transfer function orders are 0, 1 and 2; got %s"
                             % ", ".join(map(str, bad)))
    drive = np.asarray(res[p], dtype=float)
    if not np.ptp(drive) > 0:
        raise Acausal2dError("transfer functions of %s over %s: %s stays at %g over the whole "
                             "run, so there is nothing to take them over; give a drive "
                             "coordinate that moves (--x, e.g. the crank angle)"
                             % (q, p, p, drive[0]))
    out = {0: np.asarray(res[q], dtype=float)} if 0 in orders else {}
    if any(o > 0 for o in orders):
        pd = derivative(res, p)
        with np.errstate(divide="ignore", invalid="ignore"):
            q1 = np.where(pd != 0, derivative(res, q) / pd, np.nan)
            if 1 in orders:
                out[1] = q1
            if 2 in orders:
                out[2] = (derivative(res, q, 2) - q1 * derivative(res, p, 2)) / pd ** 2
    return out
