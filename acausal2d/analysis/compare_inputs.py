"""The inputs of :func:`acausal2d.compare`: the two tables (CSV paths,
Result objects, ``(time, columns)`` tuples), the options, and which
signals are compared.

Every reference signal is either compared or reported: a reference column
is matched to ours by its own name, by the user's ``mapping``, or by the
Modelica array-name aliases the component classes declare (Body's
``r[1]``/``r[2]``/``v[1]``/``v[2]`` are our ``x``/``y``/``vx``/``vy``, a
sensor's ``r[1]`` its output ``r_x.u``, see
:func:`acausal2d.language.dsl.modelica_aliases`).  The rest is returned as
*unmatched*; :func:`compare` names them and fails unless
``only_common=True``.  Wrong-typed arguments and NaN/inf values are errors
that name the argument, the file, the signal and the row.
"""
import numbers
import os

import numpy as np
import json

from ..errors import Acausal2dError
from ..io.tables import _check_time, _few, check_finite, read_csv
from ..language.dsl import modelica_aliases
from ..io.files import MANIFEST

__all__ = ["load_table", "table_units", "check_options", "select_signals",
           "modelica_counterpart"]


def load_table(source, role):
    """``(time, columns)`` of the ``role`` argument ("result" or
    "reference"): a CSV path, a Dymola result file (``.mat``, see
    :mod:`acausal2d.io.dymola_mat`), a Result (result only) or a ``(time,
    columns)`` tuple with ``columns`` a dict of 1-D sequences."""
    if isinstance(source, (str, os.PathLike)):
        if os.fspath(source).lower().endswith(".mat"):
            from ..io.dymola_mat import read_mat
            t, cols = read_mat(source)
            _check_time(t, os.fspath(source))
            check_finite(cols, t, os.fspath(source))
            return t, cols
        return read_csv(source)
    if hasattr(source, "names") and hasattr(source, "time") and role == "result":
        t = np.asarray(source.time, dtype=float)
        cols = {n: np.asarray(source[n], dtype=float) for n in source.names}
        check_finite(cols, t, "the result")
        return t, cols
    if isinstance(source, tuple):
        return _tuple_table(source, role)
    raise Acausal2dError("compare: %s must be a %sCSV file path or a (time, columns) tuple, "
                         "not %s" % (role, "Result, a " if role == "result" else "",
                                     type(source).__name__))


def table_units(source):
    """{signal: unit} a table carries: a Result's declarations, a ``.mat``
    file's descriptions, or the ``units`` of the run manifest that
    ``acausal2d simulate`` wrote beside a result CSV; {} if none."""
    if hasattr(source, "names") and hasattr(source, "unit"):
        return {n: source.unit(n) for n in source.names}
    if not isinstance(source, (str, os.PathLike)):
        return {}
    path = os.fspath(source)
    if path.lower().endswith(".mat"):
        from ..io.dymola_mat import mat_units
        return mat_units(path)
    try:
        with open(os.path.join(os.path.dirname(os.path.abspath(path)), MANIFEST),
                  encoding="utf-8") as fh:
            units = json.load(fh).get("units", {})
    except (OSError, ValueError, AttributeError):
        return {}
    return units if isinstance(units, dict) else {}


def _floats(values, what):
    try:
        v = np.asarray(values, dtype=float)
    except (TypeError, ValueError) as exc:
        raise Acausal2dError("compare: %s must be numbers (%s)" % (what, exc)) from None
    if v.ndim > 1 and sum(n > 1 for n in v.shape) > 1:
        raise Acausal2dError("compare: %s must be one-dimensional, got shape %s"
                             % (what, v.shape))
    return v.ravel()


def _tuple_table(source, role):
    """A ``(time, {name: values})`` tuple, each part checked."""
    if len(source) != 2:
        raise Acausal2dError("compare: %s as a tuple must be (time, columns), got %d items"
                             % (role, len(source)))
    t = _floats(source[0], "the %s's time (first item of the tuple)" % role)
    if t.size == 0:
        raise Acausal2dError("compare: the %s has no time points" % role)
    if not isinstance(source[1], dict):
        raise Acausal2dError("compare: the %s's columns (second item of the tuple) must be a "
                             "dict of name: values, not %s" % (role, type(source[1]).__name__))
    columns = {}
    for name, values in source[1].items():
        v = _floats(values, "the %s column %r" % (role, name))
        if v.shape != t.shape:
            raise Acausal2dError("compare: the %s column %r has %d values but there are %d time "
                                 "points" % (role, name, v.size, t.size))
        columns[str(name)] = v
    _check_time(t, "the %s" % role)
    check_finite(columns, t, "the %s" % role)
    return t, columns


def _number(name, v, nonnegative=True):
    if v is None:
        return
    if isinstance(v, bool) or not isinstance(v, numbers.Real) or not np.isfinite(v) \
            or (nonnegative and v < 0):
        raise Acausal2dError("compare: %s must be a %sfinite number, not %r"
                             % (name, "non-negative " if nonnegative else "", v))


def check_options(abs_tol=None, rel_tol=None, time_tol=None, until=None, event_tol=None,
                  signals=None, mapping=None, plot_dir=None, only_common=False):
    """Refuse options of the wrong type or value, naming the argument."""
    for name, v in (("abs_tol", abs_tol), ("rel_tol", rel_tol), ("time_tol", time_tol),
                    ("event_tol", event_tol)):
        _number(name, v)
    _number("until", until, nonnegative=False)
    if signals is not None and not isinstance(signals, str) and not (
            isinstance(signals, (list, tuple)) and all(isinstance(s, str) for s in signals)):
        raise Acausal2dError("compare: signals must be a name or a list of names, not %r"
                             % (signals,))
    if mapping is not None and not (isinstance(mapping, dict) and all(
            isinstance(k, str) and isinstance(v, str) for k, v in mapping.items())):
        raise Acausal2dError("compare: mapping must be a dict of reference name: our name, "
                             "not %r" % (mapping,))
    if plot_dir is not None and not isinstance(plot_dir, (str, os.PathLike)):
        raise Acausal2dError("compare: plot_dir must be a folder path, not %r" % (plot_dir,))
    if not isinstance(only_common, bool):
        raise Acausal2dError("compare: only_common must be True or False, not %r"
                             % (only_common,))


def modelica_counterpart(name, our_cols, table=None):
    """Our column for the reference column ``name`` by the library's
    Modelica aliases (``body.r[1]`` -> ``body.x``), or None (also when two
    of our columns would fit)."""
    if table is None:
        table = modelica_aliases()
    found = []
    for key, ours in table.items():
        if name.endswith("." + key):
            prefix = name[:-len(key)]
            found += [prefix + o for o in ours if prefix + o in our_cols]
    return found[0] if len(set(found)) == 1 else None


def select_signals(ref_cols, our_cols, signals, mapping):
    """``(pairs, unmatched)``: the (reference name, our name) pairs to
    compare and the reference columns without a counterpart (only when
    ``signals`` is None; named signals must all exist)."""
    mapping = dict(mapping or {})
    if signals is not None:
        signals = [signals] if isinstance(signals, str) else list(signals)
        _require(signals, ref_cols, "signal", "reference")
        pairs = [(s, mapping.get(s) or _ours(s, our_cols)) for s in signals]
        missing = [(s, mapping.get(s, s)) for s, o in pairs if o not in our_cols]
        _require_ours(missing, our_cols, "signal",
                      lambda s, o: o if o == s else "%s (mapped from %s)" % (o, s))
        return pairs, []
    _require(list(mapping), ref_cols, "mapped signal", "reference")
    _require_ours([(k, v) for k, v in mapping.items() if v not in our_cols], our_cols,
                  "mapped signal", lambda s, o: "%s -> %s" % (s, o))
    pairs, unmatched = [], []
    for n in ref_cols:
        ours = mapping.get(n) or _ours(n, our_cols)
        (pairs.append((n, ours)) if ours in our_cols else unmatched.append(n))
    if not pairs:
        raise Acausal2dError(
            "the result and the reference have no signal in common; the reference has: "
            "%s; the result has: %s (pair differently named signals with --map REF=OURS, or "
            "mapping= in Python)" % (_few(ref_cols), _few(our_cols)))
    return pairs, unmatched


def _ours(name, our_cols):
    return name if name in our_cols else (modelica_counterpart(name, our_cols) or name)


def _require(names, columns, what, role):
    """Refuse ``names`` missing from ``columns`` (of the ``role`` file)."""
    missing = [n for n in names if n not in columns]
    if missing:
        raise Acausal2dError("%s%s not in the %s: %s; the %s has: %s" % (
            what, "s" if len(missing) > 1 else "", role, ", ".join(missing), role,
            _few(columns, missing[0])))


def _require_ours(missing, our_cols, what, show):
    """Refuse (reference, our name) pairs whose name is not in the result."""
    if missing:
        raise Acausal2dError("%s%s not in the result: %s; the result has: %s" % (
            what, "s" if len(missing) > 1 else "", ", ".join(show(s, o) for s, o in missing),
            _few(our_cols, missing[0][1])))
