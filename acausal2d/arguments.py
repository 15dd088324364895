"""Type checks of the public API's arguments (``simulate``, ``sweep``,
``load_model``, ``compile_model``, ``check``; ``compare`` checks its own in
:mod:`acausal2d.analysis.compare_inputs`): an argument of the wrong type is
an :class:`~acausal2d.errors.Acausal2dError` that names the argument and
says what it takes, never a raw Python or numpy error from deep inside."""
import inspect
import os

import numpy as np

from .errors import Acausal2dError

__all__ = ["check_model", "check_simulate_options", "check_load", "check_sweep"]


def check_model(model, function):
    """``model`` must be a Component instance (or, for ``simulate`` and
    ``check``, a CompiledModel); a path or a class gets a hint how to make
    one."""
    from .compiled import CompiledModel
    from .language.dsl import Component
    takes_compiled = function in ("simulate", "check")
    if isinstance(model, Component) or (takes_compiled and isinstance(model, CompiledModel)):
        return
    if isinstance(model, (str, os.PathLike)):
        hint = "; for a model file use %s(acausal2d.load_model(%r))" % (function,
                                                                        os.fspath(model))
    elif isinstance(model, type) and issubclass(model, Component):
        hint = "; instantiate the class: %s(%s())" % (function, model.__name__)
    else:
        hint = ""
    raise Acausal2dError("%s: model must be a Component instance%s, not %s%s"
                         % (function, " or a CompiledModel" if takes_compiled else "",
                            type(model).__name__, hint))


def check_simulate_options(options):
    """Unknown keyword arguments of ``simulate`` are named with the known ones."""
    from .compiled import CompiledModel
    known = [p for p in inspect.signature(CompiledModel.simulate).parameters if p != "self"]
    unknown = sorted(set(options) - set(known))
    if unknown:
        raise Acausal2dError("simulate: unknown argument%s %s; it takes: %s"
                             % ("s" if len(unknown) > 1 else "", ", ".join(unknown),
                                ", ".join(known)))


def check_load(path, name, kwargs):
    """``load_model``: path a file path, name None or a class name."""
    if not isinstance(path, (str, os.PathLike)):
        raise Acausal2dError("load_model: path must be a model file path, not %s"
                             % type(path).__name__)
    if name is not None and not isinstance(name, str):
        raise Acausal2dError("load_model: name must be the name of a model class (a string), "
                             "not %r" % (name,))


def _check_vary(vary):
    if vary is None:
        return
    if not isinstance(vary, dict):
        raise Acausal2dError("sweep: vary must be a dict {'comp.param': values}, not %r"
                             % (vary,))
    for column, vals in vary.items():
        if isinstance(vals, str):
            continue
        try:
            np.asarray(vals, dtype=float)          # numbers, a list, an array, vector values
        except (TypeError, ValueError):
            raise Acausal2dError("sweep: vary[%r] must be numbers or 'start:stop:count', not %r"
                                 % (column, vals)) from None


def check_sweep(vary, points, options):
    """``sweep``: vary a dict, points a list of dicts, numeric options numbers."""
    from .compiled import number
    _check_vary(vary)
    if points is not None and (isinstance(points, (str, dict)) or not hasattr(points, "__iter__")
                               or not all(isinstance(p, dict) for p in points)):
        raise Acausal2dError("sweep: points must be a list of {'comp.param': value} dicts, "
                             "not %r" % (points,))
    for name in ("stop_time", "rtol", "intervals", "at"):
        if options.get(name) is not None:
            number("sweep: " + name, options[name])
    workers = options.get("workers")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise Acausal2dError("sweep: workers must be a whole number >= 1, not %r" % (workers,))
    params = options.get("params")
    if params is not None and not isinstance(params, dict):
        raise Acausal2dError("sweep: params must be a dict {'comp.param': value}, not %r"
                             % (params,))
