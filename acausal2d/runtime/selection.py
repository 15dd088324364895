"""State selection at run time: the dummy derivatives chosen at a point,
how regular a chosen block is there, and which components take part in a
block that has become singular."""
from __future__ import annotations

from typing import TYPE_CHECKING, TypedDict

import numpy as np
from numpy.typing import NDArray

from ..compiler.dummy_derivatives import select_dummies
from ..errors import SimulationError
from .diagnose import non_finite

MONITOR_THRESHOLD = 0.25     # re-check the selection when a block's |det| drops 4x
SINGULAR_CONDITION = 1e-4    # relative smallest singular value of a singular block

if TYPE_CHECKING:
    from ..compiler.structure import Level, Selection
    from ..compiler.system import System
    from .evaluator import Evaluator


def select(system: System, ev: Evaluator, t: float, z: NDArray[np.float64],
           d: NDArray[np.float64]) -> Selection:
    """Dummy-derivative selection at the point z."""
    J = ev.jacobian(t, z, d, dense=not ev.sparse)    # dense below SPARSE_FROM: no scipy per block
    bad = ~np.isfinite(J if isinstance(J, np.ndarray) else J.data)
    if np.any(bad):
        _non_finite(system, ev, t, J)
    if isinstance(J, np.ndarray):
        def jac(eqs, nodes):
            return J[np.ix_(list(eqs), list(nodes))]
    else:
        J = J.tocsr()

        def jac(eqs, nodes):
            return J[list(eqs)][:, list(nodes)].toarray()
    return select_dummies(system.structure, system.priority, system.nominal, jac)


def _non_finite(system, ev, t, J):
    """Raise the error naming the equations whose derivatives are inf or NaN."""
    rows = np.unique(np.nonzero(~np.isfinite(J))[0]) if isinstance(J, np.ndarray) else \
        np.unique(J.tocsr().nonzero()[0][~np.isfinite(J.tocsr().data)])
    marks = np.zeros(system.structure.n_eq)
    marks[rows] = np.nan
    raise SimulationError("At t=%.6g the derivatives of %s" % (
        t, non_finite(system, marks, ev.E.args[2])), time=t)


def block_conditioning(system, ev, t, z, d, level):
    """How regular the dummy block of a selection level is at z: the
    smallest singular value of the nominal-scaled block (its equations
    against the chosen dummies) relative to the largest singular value of
    the equations against all candidates; and the left singular vector
    (weights of the equations in the near-singularity)."""
    eqs, chosen, cands = list(level.eqs), list(level.chosen), list(level.cands)
    if ev.sparse:
        J = ev.jacobian(t, z, d, dense=False).tocsr()[eqs]
        C = J[:, cands].toarray()
    else:
        C = ev.jacobian(t, z, d, dense=True)[np.ix_(eqs, cands)]
    C = C * system.nominal[cands][None, :]
    where = {j: k for k, j in enumerate(cands)}
    u, sv, _ = np.linalg.svd(C[:, [where[j] for j in chosen]])
    top = np.linalg.norm(C, 2)
    return float(sv[-1]) / max(float(top), 1e-300), u[:, -1]


def worst_level(system, ev, selection, t, z, d, levels=None):
    """(conditioning, level, weights) of the worst-conditioned dummy block
    among ``levels`` (default: all) at z, or None without dummy blocks."""
    worst = None
    for lv in (selection.levels if levels is None else levels):
        cond, u = block_conditioning(system, ev, t, z, d, lv)
        if worst is None or cond < worst[0]:
            worst = (cond, lv, u)
    return worst


def singular_elements(system, eqs, weights):
    """Components whose equations take part in a singular block."""
    w = np.abs(weights)
    names = []
    for i in np.argsort(-w):
        if w[i] < 0.2 * w.max():
            break
        owner = system.owner_of_equation(eqs[i])
        name = owner.describe() if owner is not None else \
            system.equations[system.structure.eq_origin[eqs[i]]].origin
        if name not in names:
            names.append(name)
    return names


class Singularity(TypedDict):
    """A singular position met in a run: its time, the components taking
    part, its kind ("singular position passed", ...) and the block's
    relative smallest singular value."""
    time: float
    elements: list[str]
    kind: str
    condition: float


def singularity(system: System, t: float, kind: str,
                worst: tuple[float, Level, NDArray[np.float64]]) -> Singularity:
    """A record of a singular position: time, elements, kind, condition."""
    cond, lv, u = worst
    return {"time": t, "elements": singular_elements(system, lv.eqs, u), "kind": kind,
            "condition": cond}


def reselect(system, ev, selection, levels, t, z, d):
    """After watched dummy blocks decayed (``levels``; None: all): returns
    (selection, singularity) - a better-conditioned new selection and None,
    or the current selection with a singularity record if the mechanism
    itself is singular there (None if it is only less well conditioned
    than before)."""
    worst = worst_level(system, ev, selection, t, z, d, levels)
    if worst is None:            # no dummy derivatives: nothing to re-select
        return selection, None
    try:
        new = select(system, ev, t, z, d)
    except SimulationError:
        new = None
    if new is not None and new.dummies != selection.dummies:
        better = worst_level(system, ev, new, t, z, d)[0]
        if better > 2.0 * worst[0]:
            return new, None
    if worst[0] > SINGULAR_CONDITION:
        return selection, None      # decayed, but far from singular: keep watching
    return selection, singularity(system, t, "singular position", worst)
