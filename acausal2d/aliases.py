"""Alias elimination pass.

Equations of the form ``a = ±b + c`` and ``a = c`` (``c`` built from
parameters only) are removed and ``a`` is replaced everywhere, including its
derivatives (``der(a) = ±der(b)``, ``der(a) = 0``).  One representative is
kept per alias set, chosen by state priority, fixed start value and short
name; it inherits the start attributes of the set.  Connection equations are
the main source of aliases.
"""
import casadi as ca

from . import symbols
from .dsl import STATE_SELECT

_MAX_NODES = 12


class Alias:
    """``var = sign * rep + offset`` (rep None: ``var = offset``)."""

    __slots__ = ("var", "rep", "sign", "offset")

    def __init__(self, var, rep, sign, offset):
        self.var, self.rep, self.sign, self.offset = var, rep, sign, offset


def _param_only(e):
    for s in ca.symvar(e):
        if symbols.kind(s) != symbols.PARAM:
            return False
    return True


def _alias_form(expr, varkeys):
    """Return (vars, coefficients, remainder) if expr is c1*v1 (+ c2*v2) + rest
    with |ci| = 1 and rest parameter-only; else None."""
    if ca.n_nodes(expr) > _MAX_NODES:
        return None
    vs = []
    for s in ca.symvar(expr):
        k = symbols.kind(s)
        if k == symbols.PARAM:
            continue
        if k != symbols.VAR or symbols.key(s) not in varkeys:
            return None
        vs.append(s)
    if not 1 <= len(vs) <= 2:
        return None
    v = ca.vertcat(*vs)
    jac = ca.jacobian(expr, v)
    if not jac.is_constant():
        return None
    coeffs = [float(jac[i]) for i in range(len(vs))]
    if any(abs(abs(c) - 1.0) > 0 for c in coeffs):
        return None
    rest = ca.simplify(expr - ca.mtimes(jac, v))
    if not _param_only(rest):
        return None
    return vs, coeffs, rest


def _score(info):
    """Lower is a better representative."""
    prio = -STATE_SELECT.index(info.state_select)
    return (prio, 0 if info.fixed else 1, info.name.count("."), len(info.name), info.name)


def eliminate_aliases(equations, variables):
    """Run alias elimination.

    equations: list of flatten.Equation; variables: list of VarInfo.
    Returns (equations, variables, aliases) with the eliminated variables
    removed and ``aliases`` a list of :class:`Alias`.
    """
    info = {symbols.key(v.sym): v for v in variables}
    parent = {}   # key -> (parent key or None, sign, offset)  var = sign*parent + offset

    def find(k):
        p, s, o = parent.get(k, (k, 1.0, ca.SX(0)))
        if p is None or p == k:
            return p, s, o
        rp, rs, ro = find(p)
        res = (rp, s * rs, s * ro + o) if rp is not None else (None, 0.0, s * ro + o)
        parent[k] = res
        return res

    kept = []
    for eq in equations:
        form = _alias_form(eq.expr, info)
        if form is None:
            kept.append(eq)
            continue
        vs, cs, rest = form
        if len(vs) == 1:
            ka = symbols.key(vs[0])
            ra, sa, oa = find(ka)
            value = -rest / cs[0]            # a = value
            if ra is None:
                kept.append(eq)              # already bound: redundant, reported later
                continue
            # sa*ra + oa = value  ->  ra = (value - oa)/sa
            parent[ra] = (None, 0.0, (value - oa) * sa)
            continue
        ka, kb = symbols.key(vs[0]), symbols.key(vs[1])
        # cs[0]*a + cs[1]*b + rest = 0  ->  a = s*b + c
        s = -cs[1] / cs[0]
        c = -rest / cs[0]
        ra, sa, oa = find(ka)
        rb, sb, ob = find(kb)
        if ra is not None and ra == rb or (ra is None and rb is None):
            kept.append(eq)                  # redundant or conflicting: reported later
            continue
        # sa*ra + oa = s*(sb*rb + ob) + c
        if ra is None:                        # rb = (oa - s*ob - c) / (s*sb)
            parent[rb] = (None, 0.0, (oa - s * ob - c) * (s * sb))
        elif rb is None:                      # ra = (s*ob + c - oa)/sa
            parent[ra] = (None, 0.0, (s * ob + c - oa) * sa)
        else:
            sign = s * sb * sa
            off = (s * ob + c - oa) * sa     # ra = sign*rb + off
            if _score(info[ra]) < _score(info[rb]):
                parent[rb] = (ra, sign, -off * sign)   # rb = sign*ra - sign*off
                _merge_attrs(info[ra], info[rb], sign, -off * sign)
            else:
                parent[ra] = (rb, sign, off)
                _merge_attrs(info[rb], info[ra], sign, off)

    aliases = []
    src, dst = [], []
    for k in list(parent):
        rep, sign, off = find(k)
        if rep == k:
            continue
        var = info[k]
        if rep is None:
            aliases.append(Alias(var, None, 0.0, off))
        else:
            aliases.append(Alias(var, info[rep], sign, off))
            if var.fixed and not info[rep].fixed:
                _merge_attrs(info[rep], var, sign, off)
        sym = var.sym
        level = 0
        while True:
            if level == 0:
                src.append(sym)
                dst.append(off if rep is None else sign * info[rep].sym + off)
            else:
                src.append(sym)
                if rep is None:
                    dst.append(ca.SX(0))
                else:
                    r = info[rep].sym
                    for _ in range(level):
                        r = symbols.derivative_symbol(r)
                    dst.append(sign * r)
            if not symbols.has_derivative(sym):
                break
            sym = symbols.derivative_symbol(sym)
            level += 1
    eliminated = {symbols.key(a.var.sym) for a in aliases}
    if src:
        exprs = ca.substitute([eq.expr for eq in kept], src, dst)
        for eq, e in zip(kept, exprs):
            eq.expr = e
    remaining = [v for v in variables if symbols.key(v.sym) not in eliminated]
    return kept, remaining, aliases


def _merge_attrs(rep, member, sign, off):
    """member = sign*rep + off: let rep inherit member's start attributes."""
    if STATE_SELECT.index(member.state_select) > STATE_SELECT.index(rep.state_select):
        rep.state_select = member.state_select
    rep.nominal = max(rep.nominal, member.nominal)
    if member.fixed and not rep.fixed:
        rep.fixed = True
        rep.start = (member.start - off) * sign
    elif not rep.fixed and _is_zero(rep.start) and not _is_zero(member.start):
        rep.start = (member.start - off) * sign


def _is_zero(v):
    try:
        return float(v) == 0.0
    except (TypeError, RuntimeError):
        return False
