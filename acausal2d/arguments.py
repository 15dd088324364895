"""Type checks of the public API's arguments (``simulate``, ``sweep``,
``load_model``, ``compile_model``, ``check``; ``compare`` checks its own in
:mod:`acausal2d.analysis.compare_inputs`): an argument of the wrong type is
an :class:`~acausal2d.errors.Acausal2dError` that names the argument and
says what it takes, never a raw Python or numpy error from deep inside."""
from __future__ import annotations

import inspect
import os
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import Acausal2dError
from .compiled import CompiledModel
from .language.dsl import Component
from .options import number
from .io.loader import load_model

if TYPE_CHECKING:
    from .compiled import CompiledModel
    from .language.dsl import Component

__all__ = ["model_argument", "check_model", "check_simulate_options", "check_load", "check_sweep"]


def model_argument(model: Any, function: str, name: str | None = None) -> Component | CompiledModel:
    """The model a public function was given, as a Component instance or a
    CompiledModel: every public function takes a model file's path (with
    ``name`` choosing the class in it), a Component subclass (instantiated
    with its defaults), an instance or a CompiledModel.  Anything else is an
    :class:`~acausal2d.errors.Acausal2dError` naming ``function``."""
    if isinstance(model, (Component, CompiledModel)):
        return model
    if isinstance(model, (str, os.PathLike)):
        check_load(model, name, {})
        return load_model(model, name)
    if isinstance(model, type) and issubclass(model, Component):
        try:
            return model()
        except TypeError as exc:
            raise Acausal2dError("%s: the model class %s cannot be made with its defaults (%s); "
                                 "give an instance: %s(%s(...))"
                                 % (function, model.__name__, exc, function,
                                    model.__name__)) from None
    raise Acausal2dError("%s: model must be a model file's path, a Component subclass, an "
                         "instance or a CompiledModel, not %s" % (function, type(model).__name__))


def check_model(model: Any, function: str) -> Component | CompiledModel:
    """:func:`model_argument` for functions that take an instance only
    (kept for the callers that resolve paths and classes themselves)."""
    return model_argument(model, function)


def check_simulate_options(options: dict[str, Any]) -> None:
    """Unknown keyword arguments of ``simulate`` are named with the known ones."""
    known = [p for p in inspect.signature(CompiledModel.simulate).parameters if p != "self"]
    unknown = sorted(set(options) - set(known))
    if unknown:
        raise Acausal2dError("simulate: unknown argument%s %s; it takes: %s"
                             % ("s" if len(unknown) > 1 else "", ", ".join(unknown),
                                ", ".join(known)))


def check_load(path: Any, name: Any, kwargs: dict[str, Any]) -> None:
    """``load_model``: path a file path, name None or a class name."""
    if not isinstance(path, (str, os.PathLike)):
        raise Acausal2dError("load_model: path must be a model file path, not %s"
                             % type(path).__name__)
    if name is not None and not isinstance(name, str):
        raise Acausal2dError("load_model: name must be the name of a model class (a string), "
                             "not %r" % (name,))


def _check_vary(vary: Any) -> None:
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


def check_sweep(vary: Any, points: Any, options: dict[str, Any]) -> None:
    """``sweep``: vary a dict, points a list of dicts, numeric options numbers."""
    _check_vary(vary)
    if points is not None and (isinstance(points, (str, dict)) or not hasattr(points, "__iter__")
                               or not all(isinstance(p, dict) for p in points)):
        raise Acausal2dError("sweep: points must be a list of {'comp.param': value} dicts, "
                             "not %r" % (points,))
    if options.get("at") is not None:                 # the run options: RunOptions checks them
        number("sweep: at", options["at"])
    workers = options.get("workers")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int)
                                or workers < 1):
        raise Acausal2dError("sweep: workers must be a whole number >= 1, not %r" % (workers,))
    params = options.get("params")
    if params is not None and not isinstance(params, dict):
        raise Acausal2dError("sweep: params must be a dict {'comp.param': value}, not %r"
                             % (params,))
