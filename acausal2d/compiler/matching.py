"""Maximum bipartite matching of equations to unknowns, shared by the
balance check and the choice of initial conditions.

Augmenting paths by iterative depth-first search with lookahead (a row
reached first takes a free column of its own if it has one) after a greedy
start; :meth:`Matching.match_all` runs the searches in passes that share
their visited columns (Pothen and Fan 1990), so one pass costs O(edges)
and a chain of 50k equations is matched in linear time instead of the
O(rows x edges) of independent searches."""


class Matching:
    """A matching between rows (equations) and columns (unknowns) of an
    incidence given as ``rows[i]`` = columns of row i.  Rows can be added
    one at a time (:meth:`add_row`), which is how the initial conditions
    are chosen; :meth:`match_all` matches every row."""

    def __init__(self, rows, n_cols):
        self.rows = [list(r) for r in rows]
        self.row_of = [-1] * n_cols          # column -> matched row
        self.col_of = [-1] * len(self.rows)  # row -> matched column
        self._look = [0] * len(self.rows)    # row -> first column that may still be free

    def _free_column(self, r):
        """A free column of row ``r``, or -1.  A matched column stays matched,
        so the scan goes on from where the last one stopped (O(edges) in all)."""
        cols, k, row_of = self.rows[r], self._look[r], self.row_of
        while k < len(cols) and row_of[cols[k]] >= 0:
            k += 1
        self._look[r] = k
        return cols[k] if k < len(cols) else -1

    def _flip(self, path):
        """Match the (row, column) pairs of an augmenting path."""
        for r, c in path:
            self.row_of[c] = r
            self.col_of[r] = c

    def augment(self, r0, seen=None):
        """Find an augmenting path from the unmatched row ``r0``; True if the
        matching grew.  ``seen``: the columns already visited by the searches
        of this pass of :meth:`match_all` (they share them; a pass that finds
        no path proves the matching maximum), or None for a search of its own."""
        seen = set() if seen is None else seen
        rows, row_of = self.rows, self.row_of
        path = []      # (row, column it takes) from r0 down to the row being searched
        stack = []     # (row, iterator over its columns) of the rows being searched
        r = r0
        while True:
            c = self._free_column(r)
            if c >= 0:
                self._flip(path + [(r, c)])
                return True
            stack.append((r, iter(rows[r])))
            r = self._descend(stack, path, seen, row_of)
            if r < 0:
                return False

    @staticmethod
    def _descend(stack, path, seen, row_of):
        """The next row of the search: through the first unseen column of the
        top row (which is matched, since lookahead found no free one), else
        back up.  -1 when the search is exhausted."""
        while stack:
            top, cols = stack[-1]
            for c in cols:
                if c not in seen:
                    seen.add(c)
                    path.append((top, c))
                    return row_of[c]
            stack.pop()
            if path:
                path.pop()
        return -1

    def match_all(self):
        """Match every row that can be matched: a greedy pass, then passes of
        augmenting searches sharing one visited set until a pass finds none."""
        for r in range(len(self.rows)):
            c = self._free_column(r)
            if c >= 0:
                self._flip([(r, c)])
        grew = True
        while grew:
            grew, seen = False, set()
            for r in range(len(self.rows)):
                if self.col_of[r] < 0 and self.augment(r, seen):
                    grew = True
        return self

    def add_row(self, cols):
        """Append a row; keep it (True) if it can be matched, else drop it."""
        self.rows.append(list(cols))
        self.col_of.append(-1)
        self._look.append(0)
        if self.augment(len(self.rows) - 1):
            return True
        self.rows.pop()
        self.col_of.pop()
        self._look.pop()
        return False

    @property
    def perfect(self):
        """True if every row and every column is matched."""
        return all(c >= 0 for c in self.col_of) and all(r >= 0 for r in self.row_of)
