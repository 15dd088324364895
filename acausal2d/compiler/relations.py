"""Relations pass: comparisons in equations become event-driven discrete values.

Every relation that depends on unknowns or time (``a < b``, ``a <= b`` and the
relations hidden in ``sign``, ``fmin`` and ``fmax``) is replaced by a discrete
symbol ``d`` that holds 0 or 1 between events, and a zero-crossing function
``g`` (positive while the relation is true).  The runtime locates the zeros
of ``g`` (or, for relations of time alone, schedules them), flips ``d`` and
re-initializes consistently (Modelica event semantics).  Relations among
parameters only stay as they are.  ``fabs`` is kept continuous.

Latches (:func:`~acausal2d.language.symbols.latch`) are relations whose
crossing function a component gives and which may depend on the latch
values themselves; their crossing functions are scanned with the
equations (a relation in them becomes a relation of its own) and they come
after the relations found in the equations.
"""
from dataclasses import dataclass, replace

import casadi as ca

from ..language.symbols import TIME, VAR

_REL_OPS = (ca.OP_LT, ca.OP_LE, ca.OP_SIGN, ca.OP_FMIN, ca.OP_FMAX)


@dataclass(frozen=True)
class Relation:
    """A discrete relation value ``sym`` with zero-crossing function ``g``
    (relation true where g > 0, or g >= 0 when not ``strict``); ``text``
    shows it as written, ``equation`` is the index of the first equation
    using it and ``time_only`` says that ``g`` depends on time, parameters
    and relation values alone (a time event where it is affine in time and
    free of relation values; else decided on its exact value)."""
    sym: object
    g: object
    strict: bool
    text: str
    equation: int = -1
    time_only: bool = False
    g_start: object = None

    @property
    def start_g(self):
        """The crossing function that decides the value at the start."""
        return self.g if self.g_start is None else self.g_start

    def value(self, g_value):
        """Relation value (0.0 or 1.0) for a crossing-function value."""
        return 1.0 if (g_value > 0 if self.strict else g_value >= 0) else 0.0

    def with_g(self, g, g_start=None):
        """The same relation with crossing function ``g`` (and ``g_start``
        for a latch)."""
        return Relation(self.sym, g, self.strict, self.text, self.equation, self.time_only,
                        g_start if self.g_start is not None else None)


def _short(e):
    s = str(e)
    return s if len(s) <= 80 else s[:77] + "..."


class _Scan:
    """Rebuilds the equations instruction by instruction, replacing relations."""

    def __init__(self, table, dynamic):
        self.table, self.dyn = table, dynamic
        self.found = []      # (symbol, g, strict, text, time_only)

    def depends(self, e):
        return self.dyn is not None and ca.depends_on(e, self.dyn)

    def relation(self, g, strict, text):
        d = self.table.new_discrete("rel%d" % len(self.found))
        variables = [s for s in ca.symvar(g) if self.table.kind(s) == VAR]
        self.found.append((d, g, strict, text, not variables))
        return d

    def op(self, op, args):
        a = args[0]
        b = args[1] if len(args) > 1 else None
        if op in (ca.OP_LT, ca.OP_LE) and self.depends(b - a):
            sign = "<" if op == ca.OP_LT else "<="
            return self.relation(b - a, op == ca.OP_LT, "%s %s %s" % (_short(a), sign, _short(b)))
        if op == ca.OP_SIGN and self.depends(a):
            return 2 * self.relation(a, True, "sign(%s)" % _short(a)) - 1
        if op == ca.OP_FMIN and self.depends(b - a):
            d = self.relation(b - a, True, "min(%s, %s)" % (_short(a), _short(b)))
            return ca.if_else(d, a, b)
        if op == ca.OP_FMAX and self.depends(a - b):
            d = self.relation(a - b, True, "max(%s, %s)" % (_short(a), _short(b)))
            return ca.if_else(d, a, b)
        return ca.SX.unary(op, a) if b is None else ca.SX.binary(op, a, b)


def extract_relations(exprs, table):
    """Replace relations in the list of scalar SX ``exprs``; returns
    (new_exprs, relations), the latches of ``table`` last.  ``table``: the
    compilation's symbol table."""
    latches = table.latch_list()
    n, m = len(exprs), len(latches)
    extra = [g for _, g, _, _ in latches] + [g0 for _, _, g0, _ in latches]
    out, found = _replace(list(exprs) + extra, table)
    rels = _with_equations(found, out[:n])
    for k, (sym, _, _, text) in enumerate(latches):
        rels.append(Relation(sym, out[n + k], True, text, _first_use(out[:n], sym), False,
                             out[n + m + k]))
    return out[:n], rels


def _first_use(exprs, sym):
    """Index of the first expression that uses ``sym`` (-1: none)."""
    return next((i for i, e in enumerate(exprs) if ca.depends_on(e, sym)), -1)


def _replace(exprs, table):
    """(new_exprs, found) with the relations of ``exprs`` replaced.  Only
    the expressions that contain a relation are rebuilt, and of their
    expression graphs only the instructions they need (:func:`_needed`);
    the others are returned as they are."""
    if not exprs:
        return list(exprs), []
    allexpr = ca.vertcat(*exprs)
    syms = ca.symvar(allexpr)
    f = ca.Function("rel_scan", [ca.vertcat(*syms)] if syms else [ca.SX(0, 1)], [allexpr])
    ops = [f.instruction_id(k) for k in range(f.n_instructions())]
    if not any(op in _REL_OPS for op in ops):
        return list(exprs), []
    args = [(f.instruction_input(k), f.instruction_output(k)) for k in range(len(ops))]
    dynamic = [s for s in syms if table.kind(s) in (VAR, TIME)]
    scan = _Scan(table, ca.vertcat(*dynamic) if dynamic else None)
    work, out = {}, list(exprs)
    for k in _needed(ops, args):
        op, (ins, outs) = ops[k], args[k]
        if op == ca.OP_INPUT:
            work[outs[0]] = syms[ins[1]]
        elif op == ca.OP_OUTPUT:
            out[outs[1]] = work[ins[0]]
        elif op == ca.OP_CONST:
            work[outs[0]] = ca.SX(f.instruction_constant(k))
        else:
            work[outs[0]] = scan.op(op, [work[i] for i in ins])
    return out, scan.found


def _needed(ops, args):
    """Indices (in order) of the instructions of the scan function that the
    outputs containing a relation depend on, those outputs included.  A
    forward pass marks the work slots whose value contains a relation and
    records which instruction last wrote each slot; a backward search from
    the marked outputs collects their instructions.  Running the subsequence
    in order is safe: no instruction left out writes a slot between its
    writer and its reader, since the full sequence does not either."""
    marked, writer, sources, starts = {}, {}, [], []
    for k, op in enumerate(ops):
        ins, outs = args[k]
        if op == ca.OP_OUTPUT:
            sources.append([writer[ins[0]]])
            if marked[ins[0]]:
                starts.append(k)
            continue
        leaf = op in (ca.OP_INPUT, ca.OP_CONST)
        sources.append([] if leaf else [writer[i] for i in ins])
        marked[outs[0]] = op in _REL_OPS or (not leaf and any(marked[i] for i in ins))
        writer[outs[0]] = k
    need, stack = set(), starts
    while stack:
        k = stack.pop()
        if k not in need:
            need.add(k)
            stack.extend(sources[k])
    return sorted(need)


def _with_equations(found, exprs):
    """Relations with the index of the first equation that uses each."""
    if not found:
        return []
    rows, cols = ca.jacobian_sparsity(ca.vertcat(*exprs),
                                      ca.vertcat(*[d for d, *_ in found])).get_triplet()
    first = {}
    for r, c in zip(rows, cols):
        first[c] = min(first.get(c, r), r)
    return [Relation(d, g, strict, text, first.get(k, -1), time_only)
            for k, (d, g, strict, text, time_only) in enumerate(found)]


def explicit_in_time(exprs, table):
    """The unknowns that the residuals ``exprs`` give explicitly as
    functions of time, parameters and relation values alone (a source
    block's output, a gain or a feedback of such outputs, an input), as
    (symbols, expressions): an equation whose unknowns but one are such
    functions, affine in that one with a constant nonzero coefficient,
    gives it.  A relation of such unknowns is decided on the exact value of
    the function (:func:`exact_crossings`): the Newton solution of them
    (``1 - ramp`` solved as +-1e-32 where it is 0) must not make events."""
    eq_vars, var_eqs = _incidence(exprs, table)
    known, syms = {}, {}
    missing = [len(vs) for vs in eq_vars]
    queue = [i for i, n in enumerate(missing) if n == 1]
    while queue:
        i = queue.pop()
        solved = _solve_single(exprs[i], eq_vars[i], known, table)
        if solved is None:
            continue
        v, value = solved
        known[v.element_hash()], syms[v.element_hash()] = value, v
        for j in var_eqs[v.element_hash()]:
            missing[j] -= 1
            if missing[j] == 1:
                queue.append(j)
    return [syms[h] for h in known], [known[h] for h in known]


def _incidence(exprs, table):
    """({hash: symbol} of the unknowns of each expression, {hash: indices
    of the expressions using it})."""
    eq_vars, var_eqs = [], {}
    for i, e in enumerate(exprs):
        vs = {s.element_hash(): s for s in ca.symvar(e) if table.kind(s) == VAR}
        eq_vars.append(vs)
        for h in vs:
            var_eqs.setdefault(h, []).append(i)
    return eq_vars, var_eqs


def _solve_single(expr, unknowns, known, table):
    """(v, value) if ``expr`` = 0 has one unknown ``v`` left after the
    ``known`` ones, at derivative level 0 and affine with a constant
    nonzero coefficient; else None."""
    left = [s for h, s in unknowns.items() if h not in known]
    if len(left) != 1 or table.base_and_level(left[0])[1] != 0:
        return None
    v = left[0]
    done = [h for h in unknowns if h in known]
    if done:
        expr = ca.substitute(expr, ca.vertcat(*[unknowns[h] for h in done]),
                             ca.vertcat(*[known[h] for h in done]))
    a = ca.jacobian(expr, v)
    if not a.is_constant() or float(a) == 0.0:
        return None
    return v, ca.substitute(expr, v, ca.SX(0.0)) / -float(a)


def exact_crossings(relations, exprs, table):
    """``relations`` with the unknowns their crossing functions use that
    are explicit in time (:func:`explicit_in_time` of the residuals
    ``exprs``) replaced by their functions of time, parameters and
    relation values."""
    if not relations:
        return list(relations)
    used = {s.element_hash() for r in relations for s in ca.symvar(r.g)}
    src, dst = explicit_in_time(exprs, table)
    pairs = [(s, e) for s, e in zip(src, dst) if s.element_hash() in used]
    if not pairs:
        return list(relations)
    src = ca.vertcat(*[s for s, _ in pairs])
    dst = ca.vertcat(*[e for _, e in pairs])
    n = len(relations)
    gs = ca.substitute([r.g for r in relations] + [r.start_g for r in relations], [src], [dst])
    out = []
    for r, g, g0 in zip(relations, gs[:n], gs[n:]):
        r = r.with_g(g, g0)
        explicit = not any(table.kind(s) == VAR for s in ca.symvar(g))
        out.append(replace(r, time_only=True) if explicit and not r.time_only else r)
    return out
