"""Dummy-derivative state selection (Mattsson & Soederlind 1993).

Starting from the highest differentiated equations, each level picks as many
derivative unknowns as there are differentiated equations such that their
Jacobian block is regular; those become *dummy* derivatives (algebraic).
The choice honours state priorities (``state_select``: never < avoid <
default < prefer < always) and, inside one priority class, takes the best
conditioned columns at the current point (QR with column pivoting on
nominal-scaled columns).  A level falls apart into independent blocks (the
connected parts of its equations-by-candidates graph), which are chosen one
by one, so the dense factorizations stay small.  Where a class offered a
real choice, the level is *dynamic*: the runtime watches the determinant of
the chosen block and re-selects when it decays (a slider-crank passing a
dead centre).

A variable declared ``state_select="always"`` must become a state: if its
derivative is chosen as a dummy, or no equation is ever differentiated so
that it could be one, selection raises an error naming it.
"""
import numpy as np

from ..errors import ModelDefinitionError, SimulationError
from ..language.dsl import STATE_SELECT
from ..language.unionfind import UnionFind
from .pivoted_qr import qr_pivoted
from .structure import Level, Selection

_ALWAYS = STATE_SELECT.index("always")
LARGE_BLOCK = 400     # equations of a block above which the sparse choice is tried first


def _pick(H, prio, need):
    """Choose ``need`` columns of H (rows x cands) giving a regular block,
    lowest priority class first; returns (indices, choice_made) or None if
    the block is singular."""
    chosen, Q = [], None
    scale = max(float(np.max(np.abs(H))) if H.size else 0.0, 1e-300)
    choice = False
    for cls in range(len(STATE_SELECT)):
        if len(chosen) == need:
            break
        idx = [c for c in range(H.shape[1]) if prio[c] == cls]
        if not idx:
            continue
        M = H[:, idx] if Q is None else H[:, idx] - Q @ (Q.T @ H[:, idx])
        r, piv = qr_pivoted(M)
        d = np.abs(np.diag(r)) if r.size else np.zeros(0)
        k = min(int(np.sum(d > 1e-9 * scale)), need - len(chosen))
        if k == 0:
            continue
        choice = choice or len(idx) > k
        chosen.extend(idx[p] for p in piv[:k])
        if len(chosen) < need:
            Q, _ = np.linalg.qr(H[:, chosen])
    return (chosen, choice) if len(chosen) == need else None


def _pick_large(H, prio, need):
    """:func:`_pick` for a large block (more than ``LARGE_BLOCK`` equations,
    e.g. the 2n equations of a chain of n links), where dense QR would cost
    O(n^3): a transversal of H with lexicographically fewest high-priority
    columns and, among those, the largest product of scaled magnitudes
    (minimum-weight bipartite matching, as in MC64), accepted if its square
    block factors (sparse LU) with all pivots above 1e-9 of H's largest
    entry.  Returns what :func:`_pick` returns, or None to fall back to it."""
    import scipy.sparse as sp
    from scipy.sparse.csgraph import min_weight_full_bipartite_matching
    from scipy.sparse.linalg import splu
    A = sp.csc_matrix(H)
    A.eliminate_zeros()
    if A.nnz == 0:
        return None
    mag = np.abs(A.data)
    scale = float(mag.max())
    logw = np.log(scale) - np.log(mag) + 1.0                  # >= 1, small = large entry
    big = (need + 1) * float(logw.max())
    cls = np.asarray(prio, dtype=float)[np.repeat(np.arange(A.shape[1]), np.diff(A.indptr))]
    W = sp.csc_matrix((logw + big * cls, A.indices, A.indptr), shape=A.shape)
    try:
        rows, cols = min_weight_full_bipartite_matching(W.tocsr())
        lu = splu(sp.csc_matrix(A[:, cols[np.argsort(rows)]]), permc_spec="COLAMD")
    except (ValueError, RuntimeError):
        return None
    if len(cols) != need or np.min(np.abs(lu.U.diagonal())) <= 1e-9 * scale:
        return None
    chosen = [int(c) for c in cols]
    counts = np.bincount(np.asarray(prio)[chosen], minlength=len(STATE_SELECT))
    offered = np.bincount(np.asarray(prio), minlength=len(STATE_SELECT))
    return chosen, bool(np.any((counts > 0) & (offered > counts)))


def _blocks(s, eqs, cands):
    """Connected parts of the graph equations ``eqs`` x nodes ``cands``:
    list of (equation list, candidate list)."""
    cset = set(cands)
    uf = UnionFind()
    for i in eqs:
        uf.add(("e", i))
        for j in s.eq_vars[i]:
            if j in cset:
                uf.union(("e", i), ("v", j))
    parts = {}
    for i in eqs:
        parts.setdefault(uf.find(("e", i)), ([], []))[0].append(i)
    for j in cands:
        key = uf.find(("v", j))
        if key in parts:
            parts[key][1].append(j)
    return list(parts.values())


def _choose_level(s, eqs, cands, priority, nominal, jacobian):
    """Dummies of one level, block by block; returns (chosen, dynamic)."""
    chosen, dynamic = [], False
    for beqs, bcands in _blocks(s, eqs, cands):
        H = jacobian(beqs, bcands) * np.array([nominal[j] for j in bcands])[None, :]
        prio = [priority[j] for j in bcands]
        picked = _pick_large(H, prio, len(beqs)) if len(beqs) > LARGE_BLOCK else None
        picked = picked or _pick(H, prio, len(beqs))
        if picked is None:
            what = ", ".join(sorted({"'%s'" % s.var_sym[s.var_base[j]].name()
                                     for j in bcands})[:6])
            raise SimulationError(
                "State selection failed: the derivative equations of the unknowns %s are "
                "singular here (the mechanism is at a singular position or a constraint is "
                "redundant)." % what)
        chosen.extend(bcands[k] for k in picked[0])
        dynamic = dynamic or picked[1]
    return chosen, dynamic


def select_dummies(s, priority, nominal, jacobian):
    """Select dummy derivatives for the structure ``s`` (after Pantelides).

    priority[j], nominal[j]: per variable node; jacobian(eq_ids, node_ids)
    -> dense numpy matrix at the current point.  Returns a
    :class:`~acausal2d.compiler.structure.Selection`.
    """
    A, lower = s.var_to_diff, s.var_to_diff.from_diff
    pred = s.eq_to_diff.from_diff
    h = [c[-1] for c in s.chains() if len(c) > 1]
    z, dummies, levels = None, set(), []
    while h:
        if z is None:
            z = sorted({j for i in h for j in s.eq_vars[i]
                        if A[j] < 0 and s.var_level[j] >= 1})
        chosen, dynamic = _choose_level(s, h, z, priority, nominal, jacobian)
        dummies.update(chosen)
        levels.append(Level(tuple(h), tuple(z), tuple(chosen), dynamic))
        h = [pred[i] for i in h if s.eq_level[i] >= 2]
        z = sorted(lower[j] for j in chosen if s.var_level[j] >= 2)
    _check_always(s, priority, dummies)
    return Selection(frozenset(dummies), tuple(levels))


def _check_always(s, priority, dummies):
    """Every node declared ``always`` must be a state (see module docstring)."""
    A = s.var_to_diff
    for j in range(s.n_var):
        if priority[j] != _ALWAYS or s.var_level[j] != 0:
            continue
        if A[j] < 0:
            raise ModelDefinitionError(
                "%s has state_select='always', but no equation contains its derivative, so "
                "it cannot be a state: it is determined by algebraic equations alone. Use "
                "'prefer', or give an equation with der(%s)." % (s.var_sym[j].name(),
                                                                  s.var_sym[j].name()))
        if A[j] in dummies:
            raise ModelDefinitionError(
                "%s has state_select='always', but the states of its loop had to be chosen "
                "elsewhere: its derivative is determined by the constraints (a dummy "
                "derivative). Give 'always' to fewer variables of the loop, or use 'prefer'."
                % s.var_sym[j].name())
