"""Structural incidence of equations, computed in bulk with CasADi."""
import casadi as ca
import numpy as np
import scipy.sparse as sp

from ..language import symbols


def variable_incidence(exprs):
    """For scalar SX ``exprs``: (list of variable symbols appearing, CSR 0/1
    matrix equations x those symbols).  Parameters, time and discrete values
    are left out."""
    if not exprs:
        return [], sp.csr_matrix((0, 0))
    F = ca.vertcat(*exprs)
    syms = [s for s in ca.symvar(F) if symbols.kind(s) == symbols.VAR]
    if not syms:
        return [], sp.csr_matrix((len(exprs), 0))
    pattern = ca.jacobian_sparsity(F, ca.vertcat(*syms))
    rows, cols = pattern.get_triplet()
    m = sp.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(len(exprs), len(syms)))
    return syms, m
