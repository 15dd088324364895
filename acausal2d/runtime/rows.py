"""The output rows of a run, kept as the blocks they arrive in.

A segment of a run delivers thousands of output points at once (times T,
node values Z as one array); events and passages add single points.  The
rows were a Python list of (t, z) pairs: per output point a tuple and an
array view on the way in, and one more pass over all of them to stack the
result (piston engine, 5000 points: 2-3 ms of a 15 ms warm run; chain of 20
links: 20 ms and two extra 16 MB copies).  :class:`OutputRows` keeps the
blocks and stacks them once, in :meth:`OutputRows.arrays`; single points
are blocks of one row.
"""
import numpy as np


class OutputRows:
    """Output points (time, node values) in time order, stored by blocks.

    ``rows[k]`` is the k-th point as a (t, z) pair (``rows[-1]`` the last),
    ``rows[a:b]`` a list of such pairs; :meth:`append` and :meth:`extend`
    take (t, z) pairs, :meth:`add_block` a block (T, Z)."""

    def __init__(self, n_var):
        self.n_var = n_var
        self._T, self._Z = [], []       # blocks: times (m,), values (m, n_var)
        self._starts = [0]              # index of each block's first row; last entry = len

    def __len__(self):
        return self._starts[-1]

    def __bool__(self):
        return len(self) > 0

    def add_block(self, T, Z):
        """Append the rows Z (one per time of T, in time order); the arrays
        are kept, not copied: the caller hands them over."""
        if len(T):
            self._T.append(np.asarray(T, dtype=float))
            self._Z.append(np.asarray(Z, dtype=float).reshape(len(T), self.n_var))
            self._starts.append(self._starts[-1] + len(T))

    def append(self, row):
        """Append one point ``(t, z)`` (z is copied)."""
        t, z = row
        self.add_block(np.array([float(t)]), np.array(z, dtype=float).reshape(1, self.n_var))

    def extend(self, rows):
        """Append points ``(t, z)`` from an iterable."""
        rows = list(rows)
        if rows:
            self.add_block(np.array([float(t) for t, _ in rows]),
                           np.array([np.asarray(z, dtype=float) for _, z in rows]))

    def _locate(self, k):
        """(block, row in block) of the point with index ``k`` (0 <= k < len)."""
        b = int(np.searchsorted(self._starts, k, side="right")) - 1
        return b, k - self._starts[b]

    def __getitem__(self, k):
        n = len(self)
        if isinstance(k, slice):
            return [self[i] for i in range(*k.indices(n))]
        if k < 0:
            k += n
        if not 0 <= k < n:
            raise IndexError("output row %d of %d" % (k, n))
        b, i = self._locate(k)
        return float(self._T[b][i]), self._Z[b][i]

    def truncate(self, n):
        """Keep the first ``n`` points."""
        if n >= len(self):
            return
        b, i = self._locate(n)
        keep = b + (1 if i else 0)
        if i:
            self._T[b], self._Z[b] = self._T[b][:i], self._Z[b][:i]
        del self._T[keep:], self._Z[keep:]
        self._starts = self._starts[:keep] + [n]

    def keep_until(self, t, start):
        """Drop the points from index ``start`` on whose time is after ``t``
        (those of one segment: times ascending)."""
        rows = self[start:]
        self.truncate(start + sum(1 for s, _ in rows if s <= t))

    def arrays(self):
        """(T, Z): every point's time and node values as two arrays."""
        if not self._T:
            return np.zeros(0), np.zeros((0, self.n_var))
        if len(self._T) == 1:
            return self._T[0], self._Z[0]
        return np.concatenate(self._T), np.concatenate(self._Z)
