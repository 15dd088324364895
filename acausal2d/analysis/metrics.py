"""Run metrics for objectives and constraints: small expressions over a
run's signals, e.g. ``max(abs(drive.tau))``, ``rms(rope1.F)``,
``final(load.y) - 0.2``, ``integral(drive.tau * drive.w, 1, 2)``.

Grammar (Python syntax, checked before any run): numbers; signal names
(dotted, ``drive.tau``; ``time``); ``+ - * / **`` and unary minus; ``abs``
(elementwise); the reductions over time ``max``, ``min``, ``mean``,
``rms``, ``integral`` (trapezoidal) with an optional range ``(expr, t0,
t1)``; ``final(expr)``; ``at(expr, t)`` (linear interpolation).  The
result must be a number.

A top-level ``max(E[, t0, t1])`` (and ``min(E)`` on the large side of a
constraint) is kept as the vector ``E(t_i)`` so that the optimiser can
treat it smoothly (an objective in epigraph form, a constraint as one row,
its largest, with the rows at every time for the KKT check; see
:mod:`acausal2d.analysis.optimize`).  A division by zero gives inf or NaN
without a warning: the optimiser names the metric that is not a number.
"""
import ast

import numpy as np
from scipy.integrate import trapezoid

from ..errors import Acausal2dError

REDUCTIONS = ("max", "min", "mean", "rms", "integral")
FUNCTIONS = REDUCTIONS + ("abs", "final", "at")


def _signal_name(node):
    """Dotted name of an ast Name/Attribute chain, or None."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if isinstance(node, ast.Name):
        parts.append(node.id)
        return ".".join(reversed(parts))
    return None


class Expression:
    """A parsed metric expression: ``signals`` it reads, ``evaluate(time,
    values)`` its number, ``vector(time, values)`` the time series of a
    top-level ``max``/``min`` (``kind`` is ``"max"``, ``"min"`` or
    ``None``)."""

    def __init__(self, text, known=None):
        self.text = str(text).strip()
        try:
            self.tree = ast.parse(self.text, mode="eval").body
        except SyntaxError:
            raise Acausal2dError("expression %r is not valid: write e.g. max(abs(drive.tau)) "
                                 "or rms(rope1.F)" % self.text) from None
        self.signals = []
        self._check(self.tree)
        if known is not None:
            missing = [s for s in self.signals if s not in known and s != "time"]
            if missing:
                close = [n for n in known if missing[0].split(".")[-1] in n][:8]
                raise Acausal2dError("expression %r: no signal %s in the model%s" % (
                    self.text, missing[0], "; similar: " + ", ".join(close) if close else ""))
        top = self.tree
        self.kind = top.func.id if isinstance(top, ast.Call) and isinstance(top.func, ast.Name) \
            and top.func.id in ("max", "min") else None

    def _check(self, node):
        name = _signal_name(node)
        if name is not None:
            if name not in FUNCTIONS and name not in self.signals:
                self.signals.append(name)
            return
        if isinstance(node, ast.Call):
            fname = _signal_name(node.func)
            if fname not in FUNCTIONS or node.keywords:
                raise Acausal2dError("expression %r: unknown function %s; use %s"
                                     % (self.text, fname, ", ".join(FUNCTIONS)))
            for a in node.args:
                self._check(a)
            return
        allowed = (ast.BinOp, ast.UnaryOp, ast.Constant, ast.Add, ast.Sub, ast.Mult, ast.Div,
                   ast.Pow, ast.USub, ast.UAdd)
        if not isinstance(node, allowed) or \
                (isinstance(node, ast.Constant) and not isinstance(node.value, (int, float))):
            raise Acausal2dError("expression %r: %s is not allowed (numbers, signals, + - * / "
                                 "**, and %s)" % (self.text, type(node).__name__,
                                                  ", ".join(FUNCTIONS)))
        for child in ast.iter_child_nodes(node):
            if not isinstance(child, (ast.operator, ast.unaryop)):
                self._check(child)

    def evaluate(self, time, values):
        """The expression's number for a run (``values``: {signal: array})."""
        v = _Evaluator(time, values).eval(self.tree)
        if np.ndim(v) != 0:
            raise Acausal2dError("expression %r is a time series, not a number: reduce it with "
                                 "max, min, mean, rms, integral, final or at" % self.text)
        return float(v)

    def vector(self, time, values):
        """The series inside a top-level max/min (its range applied)."""
        ev = _Evaluator(time, values)
        args = self.tree.args
        series = np.broadcast_to(ev.eval(args[0]), np.shape(time)).astype(float)
        keep = ev.window(args[1:])
        return series[keep]


class _Evaluator:
    """Evaluates a checked expression tree on one run."""

    def __init__(self, time, values):
        self.time = np.asarray(time, dtype=float)
        self.values = values

    def window(self, bounds):
        """Mask of the times in [t0, t1] given by the optional arguments."""
        t0 = float(self.eval(bounds[0])) if len(bounds) > 0 else -np.inf
        t1 = float(self.eval(bounds[1])) if len(bounds) > 1 else np.inf
        keep = (self.time >= t0 - 1e-12) & (self.time <= t1 + 1e-12)
        if not keep.any():
            raise Acausal2dError("the time range %g .. %g contains no output point" % (t0, t1))
        return keep

    def eval(self, node):
        name = _signal_name(node)
        if name is not None:
            return self.time if name == "time" else np.asarray(self.values[name], dtype=float)
        if isinstance(node, ast.Constant):
            return float(node.value)
        if isinstance(node, ast.UnaryOp):
            v = self.eval(node.operand)
            return -v if isinstance(node.op, ast.USub) else v
        if isinstance(node, ast.BinOp):       # x/0 and 0/0 give inf and NaN, judged by the caller
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                return _BINARY[type(node.op)](self.eval(node.left), self.eval(node.right))
        return self.call(node.func.id, node.args)

    def call(self, fname, args):
        if fname == "abs":
            return np.abs(self.eval(args[0]))
        y = np.broadcast_to(self.eval(args[0]), self.time.shape).astype(float)
        if fname == "final":
            return float(y[-1])
        if fname == "at":
            return float(np.interp(float(self.eval(args[1])), self.time, y))
        keep = self.window(args[1:])
        return _reduce(fname, self.time[keep], y[keep])


_BINARY = {ast.Add: np.add, ast.Sub: np.subtract, ast.Mult: np.multiply,
           ast.Div: np.divide, ast.Pow: np.power}


def _reduce(fname, t, y):
    if fname == "max":
        return float(np.max(y))
    if fname == "min":
        return float(np.min(y))
    if fname == "mean":
        return float(np.mean(y))
    if fname == "rms":
        return float(np.sqrt(np.mean(y ** 2)))
    return float(trapezoid(y, t)) if t.size > 1 else 0.0


def parse_constraint(text, known=None):
    """``EXPR<=VALUE`` or ``EXPR>=VALUE`` -> (Expression, sense, value),
    sense +1 for <=, -1 for >=."""
    for op, sense in (("<=", 1.0), (">=", -1.0)):
        if op in text:
            left, right = text.split(op, 1)
            try:
                value = float(right)
            except ValueError:
                raise Acausal2dError("--constraint %r: the right side must be a number "
                                     "(EXPR<=VALUE or EXPR>=VALUE)" % text) from None
            return Expression(left, known), sense, value
    raise Acausal2dError("--constraint takes EXPR<=VALUE or EXPR>=VALUE (e.g. "
                         "'max(abs(rope1.F))<=500'), got %r" % text)
