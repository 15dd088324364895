"""Where the C projector of output rows (``native_project.c``) puts each
nonzero of dE/dz: the block lower-triangular form of dE/dz_free
(:func:`~acausal2d.compiler.blt.blt`) as one int array, computed once per
system and set of free unknowns (a :class:`~acausal2d.runtime.projection.Projector`
is made per simulate call; the analysis is not repeated per run).

The array holds, one after the other: the number of blocks nb; the block
starts (nb + 1 positions); the offsets of the blocks' dense storage (nb +
1, block b of size s takes s * s doubles, column-major); the equation at
each position; the unknown (index into z) at each position; the slot of
each nonzero of dE/dz (all columns, CasADi's compressed-column order):
its index in the dense blocks, -2 - its index among the below-block
entries, or -1 for a state's column; the below-block entries by column
position (n + 1 starts) and their row positions.
"""
import weakref

import numpy as np

from ..compiler.blt import blt

MAX_DENSE = 4_000_000
"""Most doubles in the dense diagonal blocks (32 MB, one block of 2000
unknowns); beyond, no C projector (the Python path with sparse LU)."""
_LAYOUTS = weakref.WeakKeyDictionary()    # system -> {free unknowns (bytes): array or None}


def layout(system, free):
    """The int array (see module docstring) of ``system`` with the unknowns
    ``free`` solved for, or None where dE/dz_free is not square or is
    structurally singular (no perfect matching), or its diagonal blocks
    are too large (:data:`MAX_DENSE`)."""
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
    """The int array of a :class:`~acausal2d.compiler.blt.BLT` ``form``, for
    nonzeros at equation ``rows`` and free column ``f`` (-1: a state)."""
    start = np.asarray(form.starts, dtype=np.intc)
    sizes = np.diff(start)
    off = np.r_[0, np.cumsum(sizes.astype(np.int64) ** 2)]
    if off[-1] > MAX_DENSE:
        return None
    block = np.repeat(np.arange(len(sizes)), sizes)          # position -> block
    pos_row = np.empty(n, dtype=np.int64)
    pos_row[form.rows] = np.arange(n)
    pos_col = np.empty(n, dtype=np.int64)
    pos_col[form.cols] = np.arange(n)
    keep = f >= 0
    pr, pc = pos_row[rows[keep]], pos_col[f[keep]]
    br, bc = block[pr], block[pc]
    if np.any(br < bc):
        raise AssertionError("a nonzero above the block diagonal")
    inside = br == bc
    slot = np.full(len(rows), -1, dtype=np.int64)
    where = np.nonzero(keep)[0]
    s0 = start[bc]
    slot[where[inside]] = (off[bc] + (pc - s0) * sizes[bc] + (pr - s0))[inside]
    below = np.nonzero(~inside)[0]
    order = below[np.lexsort((pr[below], pc[below]))]
    slot[where[order]] = -2 - np.arange(len(order))
    bptr = np.searchsorted(pc[order], np.arange(n + 1))
    parts = [[len(sizes)], start, off, form.rows, np.asarray(free)[form.cols], slot, bptr,
             pr[order], [0]]
    return np.ascontiguousarray(np.concatenate([np.asarray(a, dtype=np.int64) for a in parts])
                                .astype(np.intc))
