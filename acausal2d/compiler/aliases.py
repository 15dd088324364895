"""Alias elimination pass.

Equations of the form ``a = ±b + c`` and ``a = c`` (``c`` built from
parameters only) are removed and ``a`` is replaced everywhere, including its
derivatives (``der(a) = ±der(b)``, ``der(a) = 0``).  One representative is
kept per alias set, chosen by state priority, fixed start value and short
name; it inherits the start attributes of the set.  Connection equations are
the main source of aliases.
"""
import casadi as ca

import copy

from ..language.dsl import STATE_SELECT
from ..language.symbols import PARAM, as_sx

_MAX_NODES = 12


class Alias:
    """``var = sign * rep + offset`` (rep None: ``var = offset``)."""

    __slots__ = ("var", "rep", "sign", "offset")

    def __init__(self, var, rep, sign, offset):
        self.var, self.rep, self.sign, self.offset = var, rep, sign, offset


def _param_only(e, table):
    return all(table.kind(s) == PARAM for s in ca.symvar(e))


_ADD, _SUB, _NEG = ca.OP_ADD, ca.OP_SUB, ca.OP_NEG


def _terms(e, sign, vs, rest, table, depth=0):
    """Split e into +-1 * symbols and other terms; False if too complex."""
    if e.is_symbolic():
        if table.kind(e) == PARAM:
            rest.append(sign * e)
        else:
            vs.append((sign, e))
        return True
    if e.is_constant():
        rest.append(sign * float(e))
        return True
    if depth > 6:
        return False
    op = e.op()
    if op == _ADD:
        return _terms(e.dep(0), sign, vs, rest, table, depth + 1) and \
            _terms(e.dep(1), sign, vs, rest, table, depth + 1)
    if op == _SUB:
        return _terms(e.dep(0), sign, vs, rest, table, depth + 1) and \
            _terms(e.dep(1), -sign, vs, rest, table, depth + 1)
    if op == _NEG:
        return _terms(e.dep(0), -sign, vs, rest, table, depth + 1)
    if ca.n_nodes(e) <= _MAX_NODES and _param_only(e, table):
        rest.append(sign * e)
        return True
    return False


def _alias_form(expr, varkeys, table):
    """Return (vars, coefficients, remainder) if expr is +-v1 (+- v2) + rest
    with rest built from parameters only; else None."""
    vs, rest = [], []
    if not _terms(expr, 1.0, vs, rest, table):
        return None
    if not 1 <= len(vs) <= 2:
        return None
    keys = [v.element_hash() for _, v in vs]
    if len(set(keys)) != len(keys) or any(k not in varkeys for k in keys):
        return None
    total = 0.0
    for r in rest:
        total = total + r
    return [v for _, v in vs], [c for c, _ in vs], total


def _score(info):
    """Lower is a better representative."""
    prio = -STATE_SELECT.index(info.state_select)
    return (prio, 0 if info.fixed else 1, info.name.count("."), len(info.name), info.name)


class _AliasSets:
    """Union-find of ``var = sign * parent + offset`` relations (parent None:
    ``var = offset``), keyed by symbol hashes."""

    def __init__(self, info):
        self.info = info
        self.parent = {}

    def find(self, k):
        """(representative or None, sign, offset) with var = sign * rep + offset."""
        p, s, o = self.parent.get(k, (k, 1.0, 0.0))
        if p is None or p == k:
            return p, s, o
        rp, rs, ro = self.find(p)
        res = (rp, s * rs, s * ro + o) if rp is not None else (None, 0.0, s * ro + o)
        self.parent[k] = res
        return res

    def bind(self, v, coef, rest):
        """coef * v + rest = 0; False if v's set is bound already."""
        ra, sa, oa = self.find(v.element_hash())
        if ra is None:
            return False                     # redundant or conflicting: reported later
        self.parent[ra] = (None, 0.0, (-rest / coef - oa) * sa)   # sa*ra + oa = -rest/coef
        return True

    def join(self, vs, cs, rest):
        """cs[0]*a + cs[1]*b + rest = 0; False if redundant or conflicting."""
        s, c = -cs[1] / cs[0], -rest / cs[0]              # a = s*b + c
        ra, sa, oa = self.find(vs[0].element_hash())
        rb, sb, ob = self.find(vs[1].element_hash())
        if ra is not None and ra == rb or (ra is None and rb is None):
            return False
        if ra is None:                                      # rb = (oa - s*ob - c)/(s*sb)
            self.parent[rb] = (None, 0.0, (oa - s * ob - c) * (s * sb))
        elif rb is None:                                    # ra = (s*ob + c - oa)/sa
            self.parent[ra] = (None, 0.0, (s * ob + c - oa) * sa)
        else:
            self._link(ra, rb, s * sb * sa, (s * ob + c - oa) * sa)   # ra = sign*rb + off
        return True

    def _link(self, ra, rb, sign, off):
        info = self.info
        if _score(info[ra]) < _score(info[rb]):
            self.parent[rb] = (ra, sign, -off * sign)       # rb = sign*ra - sign*off
            _merge_attrs(info[ra], info[rb], sign, -off * sign)
        else:
            self.parent[ra] = (rb, sign, off)
            _merge_attrs(info[rb], info[ra], sign, off)

    def aliases(self):
        """The :class:`Alias` of every eliminated variable."""
        out = []
        for k in list(self.parent):
            rep, sign, off = self.find(k)
            if rep == k:
                continue
            var = self.info[k]
            if rep is None:
                out.append(Alias(var, None, 0.0, off))
                continue
            out.append(Alias(var, self.info[rep], sign, off))
            if var.fixed and not self.info[rep].fixed:
                _merge_attrs(self.info[rep], var, sign, off)
        return out


def _substitute(kept, aliases, table):
    """Equations with the aliases substituted (new Equation objects where
    something changed) and the ids of those changed."""
    src, dst = substitution(aliases, table)
    changed = set()
    if not src or not kept:
        return kept, changed
    touched = ca.jacobian_sparsity(ca.vertcat(*[eq.expr for eq in kept]),
                                   ca.vertcat(*src)).get_triplet()[0]
    rows = sorted(set(touched))
    if rows:
        exprs = ca.substitute([kept[i].expr for i in rows], src, [as_sx(x) for x in dst])
        for i, e in zip(rows, exprs):
            kept[i] = kept[i].with_expr(e)
            changed.add(id(kept[i]))
    return kept, changed


def eliminate_aliases(equations, variables, table, examine=None):
    """Run one pass of alias elimination.

    equations: list of flatten.Equation; variables: list of VarInfo;
    examine: ids (``id(eq)``) of the equations to inspect (default: all).
    Returns (equations, variables, aliases, changed) with the eliminated
    variables removed, ``aliases`` a list of :class:`Alias` and ``changed``
    the ids of the equations the substitution touched.
    """
    info = {v.sym.element_hash(): v for v in variables}
    sets, kept = _AliasSets(info), []
    for eq in equations:
        form = None if examine is not None and id(eq) not in examine else \
            _alias_form(eq.expr, info, table)
        if form is None:
            kept.append(eq)
            continue
        vs, cs, rest = form
        used = sets.bind(vs[0], cs[0], rest) if len(vs) == 1 else sets.join(vs, cs, rest)
        if not used:
            kept.append(eq)
    aliases = sets.aliases()
    kept, changed = _substitute(kept, aliases, table)
    eliminated = {a.var.sym.element_hash() for a in aliases}
    remaining = [v for v in variables if v.sym.element_hash() not in eliminated]
    return kept, remaining, aliases, changed


def substitution(aliases, table):
    """(symbols, replacements) that remove the aliased variables and their
    derivatives from expressions: der^k(var) -> sign * der^k(rep) (+ offset
    for k = 0)."""
    src, dst = [], []
    for a in aliases:
        sym, level = a.var.sym, 0
        while True:
            src.append(sym)
            if a.rep is None:
                dst.append(a.offset if level == 0 else 0.0)
            else:
                r = a.rep.sym
                for _ in range(level):
                    r = table.derivative_symbol(r)
                dst.append(a.sign * r + (a.offset if level == 0 else 0.0))
            if not table.has_derivative(sym):
                break
            sym = table.derivative_symbol(sym)
            level += 1
    return src, dst


def eliminate_all_aliases(equations, variables, table):
    """Alias passes until none is left (a substitution can turn an equation
    into a new alias); returns (equations, variables, aliases) with every
    alias expressed in a remaining variable.  The inputs are not changed:
    representatives are copies that inherit the start attributes of their
    alias sets."""
    aliases = []
    examine = None
    equations, variables = list(equations), [copy.copy(v) for v in variables]
    while True:
        equations, variables, new, examine = eliminate_aliases(equations, variables, table,
                                                               examine)
        if not new:
            return equations, variables, aliases
        by_var = {b.var.sym.element_hash(): b for b in new}
        for a in aliases:
            b = by_var.get(a.rep.sym.element_hash()) if a.rep is not None else None
            if b is not None:       # a.var = a.sign*(b.sign*b.rep + b.offset) + a.offset
                a.offset = a.sign * b.offset + a.offset
                a.sign = a.sign * b.sign
                a.rep = b.rep
        aliases.extend(new)


def _merge_attrs(rep, member, sign, off):
    """member = sign*rep + off: let rep inherit member's start attributes.
    The nominal is the smallest of the set: the tolerance of the node must
    resolve its smallest member (a relative speed of 1e-6 rad/s with its
    nominal 1e-4 that is an alias of a housing's speed)."""
    if STATE_SELECT.index(member.state_select) > STATE_SELECT.index(rep.state_select):
        rep.state_select = member.state_select
    rep.nominal = min(rep.nominal, member.nominal)
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
