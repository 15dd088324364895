"""Derived signals: columns of a result that a component declares as another
column of the index-reduced system under its own name (Body's ``ax`` is
``der(der(x))``).  They are read from the derivative nodes index reduction
already made, exactly (no differencing of the output grid) and without
adding equations or unknowns to the DAE.

A component declares them by the class attribute ``derived_signals``: a dict
from the new name to the source name, or to a tuple of alternative source
names tried in order (all relative to the component, ``der(...)`` allowed),
e.g. ``{"z": ("der(w)", "der(der(phi))")}``.
"""
from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Optional

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from .language.dsl import Component
    from .protocols import ResultData

__all__ = ["DerivedSignal", "derived_signals", "derived_columns"]

DerivedSignal = tuple[str, Optional[str], tuple[str, int]]
"""(name, source column or None for a constant's derivative, (base variable,
derivative order)) of a derived signal."""


def _split(expr):
    """(base name, derivative order) of ``der(der(x))``-style names."""
    order = 0
    while expr.startswith("der(") and expr.endswith(")"):
        expr, order = expr[4:-1], order + 1
    return expr, order


def qualify(path, expr):
    """``der(der(x))`` of the component at ``path`` as a full column name
    (``der(der(body.x))``)."""
    base, order = _split(expr)
    name = "%s.%s" % (path, base) if path else base
    for _ in range(order):
        name = "der(%s)" % name
    return name


def _source(path, sources, names):
    """The first of ``sources`` that is a column in ``names``; None when the
    quantity is the derivative of a column without any derivative (a
    variable the equations hold constant: the signal is zero); False if
    neither."""
    sources = (sources,) if isinstance(sources, str) else tuple(sources)
    for name in (qualify(path, s) for s in sources):
        if name in names:
            return name
    for s in sources:
        base, order = _split(qualify(path, s))
        if order and base in names and "der(%s)" % base not in names:
            return None
    return False


def derived_signals(model: Component, names: Iterable[str]) -> list[DerivedSignal]:
    """[(name, source, (base, order))] of the derived signals the components
    of ``model`` declare (class attribute ``derived_signals``): the source
    column among ``names`` (the system's columns), None for a constant's
    derivative (zero), and the base variable and derivative order of the
    first declared source (for the unit).  Signals without a source column
    are left out, as are names that are already columns."""
    names = set(names)
    out: list[DerivedSignal] = []
    for comp in model.components():
        for own, sources in (getattr(type(comp), "derived_signals", None) or {}).items():
            name = qualify(comp.path, own)
            src = _source(comp.path, sources, names)
            first = sources if isinstance(sources, str) else sources[0]
            if src is not False and name not in names:
                out.append((name, src, _split(qualify(comp.path, first))))
    return out


def derived_columns(result: ResultData, signals: Iterable[DerivedSignal]
                    ) -> list[tuple[str, NDArray[np.float64]]]:
    """Values of ``signals`` (from :func:`derived_signals`) in ``result``:
    a list of (name, array over result.time)."""
    n = len(result.time)
    return [(name, np.zeros(n) if src is None else np.array(result[src]))
            for name, src, _ in signals]
