"""Where the C projector of output rows (``native_project.c``) puts each
nonzero of dE/dz: the block lower-triangular form of dE/dz_free
(:func:`~acausal2d.runtime.blt.blt`) as one int array, computed once per
system and set of free unknowns (a :class:`~acausal2d.runtime.projection.Projector`
is made per simulate call; the analysis is not repeated per run).

The array holds, one after the other: the number of blocks nb; the block
starts (nb + 1 positions); the equation at each position; the unknown
(index into z) at each position; the slot of each nonzero of dE/dz (all
columns, in CasADi's compressed-column order): its index among the
diagonal blocks' entries, -2 - its index among the below-block entries,
or -1 for a state's column; the diagonal blocks' entries by column
position (n + 1 starts) and their rows within their block; the
below-block entries by column position (n + 1 starts) and their row
positions.
"""
import weakref

import numpy as np

from .blt import blt

MAX_FILL = 4_000_000
"""Most entries that L (and U) of the diagonal blocks' LUs could reach (s(s +
1)/2 for a block of size s > 1; 2.8 blocks of 2000 unknowns): beyond, no C
projector (the Python path with sparse LU)."""
_LAYOUTS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()    # system -> {free unknowns (bytes): array or None}


def layout(system, free):
    """The int array (see module docstring) of ``system`` with the unknowns
    ``free`` solved for, or None where dE/dz_free is not square or is
    structurally singular (no perfect matching), or its diagonal blocks
    are too large (:data:`MAX_FILL`)."""
    free = np.asarray(free, dtype=np.intc)
    per_system = _LAYOUTS.setdefault(system, {})
    key = free.tobytes()
    if key not in per_system:
        per_system[key] = _layout(system, free)
    return per_system[key]


def _layout(system, free):
    n_var, n = system.structure.n_var, system.structure.n_eq
    if len(free) != n or not n:
        return None
    sp = system.jacobian_fn.sparsity_out(0)
    rows, cols = (np.asarray(a, dtype=np.intc) for a in sp.get_triplet())
    col_of = np.full(n_var, -1, dtype=np.intc)
    col_of[free] = np.arange(n, dtype=np.intc)
    f = col_of[cols]
    keep = f >= 0
    pattern = [[] for _ in range(n)]
    for r, c in zip(rows[keep].tolist(), f[keep].tolist()):
        pattern[r].append(c)
    form = blt(pattern, n)
    if form is None:
        return None
    return _arrays(form, rows, f, free, n)


def _arrays(form, rows, f, free, n):
    """The int array of a :class:`~acausal2d.runtime.blt.BLT` ``form``, for
    nonzeros at equation ``rows`` and free column ``f`` (-1: a state)."""
    start = np.asarray(form.starts, dtype=np.int64)
    sizes = np.diff(start)
    if np.sum(np.where(sizes > 1, sizes * (sizes + 1) // 2, 0)) > MAX_FILL:
        return None
    block = np.repeat(np.arange(len(sizes)), sizes)          # position -> block
    pos_row = np.empty(n, dtype=np.int64)
    pos_row[form.rows] = np.arange(n)
    pos_col = np.empty(n, dtype=np.int64)
    pos_col[form.cols] = np.arange(n)
    where = np.nonzero(f >= 0)[0]
    pr, pc = pos_row[rows[where]], pos_col[f[where]]
    if np.any(block[pr] < block[pc]):
        raise AssertionError("a nonzero above the block diagonal")
    slot = np.full(len(rows), -1, dtype=np.int64)
    parts = [[len(sizes)], start, form.rows, np.asarray(free)[form.cols], slot]
    for inside, code in ((block[pr] == block[pc], 0), (block[pr] > block[pc], -2)):
        k = np.nonzero(inside)[0]
        k = k[np.lexsort((pr[k], pc[k]))]                    # by column, then row
        slot[where[k]] = np.arange(len(k)) if code == 0 else -2 - np.arange(len(k))
        rows_k = pr[k] - start[block[pc[k]]] if code == 0 else pr[k]
        parts += [np.searchsorted(pc[k], np.arange(n + 1)), rows_k]
    return np.ascontiguousarray(np.concatenate([np.asarray(a, dtype=np.int64) for a in parts + [[0]]])
                                .astype(np.intc))
