"""Structural incidence of equations, computed in bulk with CasADi."""
import casadi as ca
import numpy as np

from ..language.symbols import VAR


class Incidence:
    """A 0/1 matrix (equations x symbols) in compressed rows: the symbols of
    row i are ``indices[indptr[i]:indptr[i + 1]]``."""

    def __init__(self, n_rows, rows, cols):
        order = np.lexsort((cols, rows))
        rows, cols = np.asarray(rows, dtype=int)[order], np.asarray(cols, dtype=int)[order]
        self.indices = cols
        self.indptr = np.searchsorted(rows, np.arange(n_rows + 1))
        self.shape = (n_rows, int(cols.max()) + 1 if len(cols) else 0)

    def row(self, i):
        return self.indices[self.indptr[i]:self.indptr[i + 1]]


def variable_incidence(exprs, table):
    """For scalar SX ``exprs``: (list of variable symbols appearing, their
    :class:`Incidence`).  Parameters, time and discrete values are left out."""
    if not exprs:
        return [], Incidence(0, [], [])
    F = ca.vertcat(*exprs)
    syms = [s for s in ca.symvar(F) if table.kind(s) == VAR]
    if not syms:
        return [], Incidence(len(exprs), [], [])
    rows, cols = ca.jacobian_sparsity(F, ca.vertcat(*syms)).get_triplet()
    return syms, Incidence(len(exprs), rows, cols)
