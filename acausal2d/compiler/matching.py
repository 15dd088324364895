"""Maximum bipartite matching of equations to unknowns (augmenting paths,
iterative depth-first search after a greedy start), shared by the balance
check and the choice of initial conditions."""


class Matching:
    """A matching between rows (equations) and columns (unknowns) of an
    incidence given as ``rows[i]`` = columns of row i.  Rows can be added
    one at a time (:meth:`add_row`), which is how the initial conditions
    are chosen; :meth:`match_all` matches every row."""

    def __init__(self, rows, n_cols):
        self.rows = [list(r) for r in rows]
        self.row_of = [-1] * n_cols          # column -> matched row
        self.col_of = [-1] * len(self.rows)  # row -> matched column

    def augment(self, r0):
        """Find an augmenting path from the unmatched row ``r0``; True if the
        matching grew."""
        rows, row_of = self.rows, self.row_of
        seen = set()
        stack = [(r0, iter(rows[r0]))]
        path = []
        while stack:
            r, it = stack[-1]
            for c in it:
                if c in seen:
                    continue
                seen.add(c)
                path.append((r, c))
                if row_of[c] < 0:
                    for rr, cc in path:
                        row_of[cc] = rr
                        self.col_of[rr] = cc
                    return True
                stack.append((row_of[c], iter(rows[row_of[c]])))
                break
            else:
                stack.pop()
                if path:
                    path.pop()
        return False

    def match_all(self):
        """Match every row that can be matched (greedy pass first)."""
        for r, cols in enumerate(self.rows):
            for c in cols:
                if self.row_of[c] < 0:
                    self.row_of[c] = r
                    self.col_of[r] = c
                    break
        for r in range(len(self.rows)):
            if self.col_of[r] < 0:
                self.augment(r)
        return self

    def add_row(self, cols):
        """Append a row; keep it (True) if it can be matched, else drop it."""
        self.rows.append(list(cols))
        self.col_of.append(-1)
        if self.augment(len(self.rows) - 1):
            return True
        self.rows.pop()
        self.col_of.pop()
        return False

    @property
    def perfect(self):
        """True if every row and every column is matched."""
        return all(c >= 0 for c in self.col_of) and all(r >= 0 for r in self.row_of)
