"""acausal2d: acausal, equation-based simulation of planar mechanisms.

Write models as Python classes (:class:`Component`), then :func:`compile_model`
and :meth:`CompiledModel.simulate` them, or call :func:`simulate` directly.
"""
from __future__ import annotations

import os as _os
from typing import TYPE_CHECKING, Any, Union

__version__ = "0.1.0"
"""The package version (``acausal2d --version``; pyproject.toml reads it from here)."""

from casadi import (sin, cos, tan, asin, acos, atan, atan2, sqrt, exp, log, fabs,  # noqa: E402,F401
                    fmin, fmax, sign, if_else, pi)
import importlib

from .language.connectors import (BandPort, Connector, Frame, RealInput, RealOutput,  # noqa: E402,F401
                         RotationalFlange, TranslationalFlange, HydraulicPort)
from .language.dsl import Component, Outer, Parameter, Variable, start  # noqa: E402,F401
from .language.dsl import register_display as _register_display  # noqa: E402
from .errors import (Acausal2dError, InitializationError, ModelDefinitionError,  # noqa: E402,F401
                     SimulationError, StructuralError)
from .language.symbols import der, time, time_derivative  # noqa: E402,F401
from .analysis.check import check  # noqa: E402,F401
from .analysis.study import study  # noqa: E402,F401
from .io import loader as _loader  # noqa: E402
from .io.loader import load_model as _load
from .options import OPTION_NAMES, RunOptions  # noqa: E402,F401

if TYPE_CHECKING:
    from .analysis.compare import Comparison
    from .analysis.fit_report import FitResult
    from .analysis.optimize_report import OptimizeResult
    from .analysis.sweep import SweepResult
    from .compiled import CompiledModel
    from .result import Result

Model = Component
"""Alias of :class:`Component` for top-level models."""

ModelArgument = Union[str, "_os.PathLike[str]", Component, "type[Component]", "CompiledModel"]
"""What every public function takes as its model: a model file's path, a
Component subclass (made with its defaults), an instance or a CompiledModel."""


def compare(result: Any, reference: Any, signals: Any = None, **options: Any) -> Comparison:
    """Compare a result with a reference signal by signal, the planar
    library's Modelica aliases included (``body.r[1]`` is our ``body.x``);
    see :func:`acausal2d.analysis.compare.compare` for the options.
    Returns a Comparison."""
    import acausal2d.library.planar  # noqa: F401  (declares the aliases)
    from .analysis.compare import compare as _compare
    comparison: Comparison = _compare(result, reference, signals=signals, **options)
    return comparison


__all__ = [
    # modelling
    "Component", "Model", "Parameter", "Variable", "start", "Outer", "der", "time",
    "time_derivative", "Connector", "Frame", "RotationalFlange", "TranslationalFlange",
    "BandPort", "RealInput", "RealOutput", "HydraulicPort",
    # symbolic functions for equations
    "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt", "exp", "log", "fabs", "fmin",
    "fmax", "sign", "if_else", "pi",
    # running and analysing
    "load_model", "compile_model", "CompiledModel", "simulate", "RunOptions", "Result", "check",
    "compare", "sweep", "study", "fit", "optimize", "export_fmu",
    # errors
    "Acausal2dError", "ModelDefinitionError", "StructuralError", "InitializationError",
    "SimulationError",
    "__version__",
]

_LAZY = {"CompiledModel": "compiled", "Result": "result"}


def _read_mec2(path: str) -> Any:
    """A mec2 model file, read by the library's importer
    (:func:`acausal2d.library.nodes.mec2.load_mec2`; imported when one is read)."""
    from .library.nodes.mec2 import load_mec2
    return load_mec2(path)


_loader.register_reader(".json", "mec2", _read_mec2)


def _component_svg(component: Any) -> str:
    """A component's diagram as SVG (:func:`acausal2d.visual.diagram.diagram_svg`;
    imported when a notebook first shows one: its layout loads networkx)."""
    from .visual.diagram import diagram_svg
    return diagram_svg(component)


_register_display("svg", _component_svg)


def __getattr__(name: str) -> Any:
    """``CompiledModel`` and ``Result`` on first use: they import the
    runtime (IDA, scikit-sundae), which ``import acausal2d`` alone does not
    need."""
    if name in _LAZY:
        value = getattr(importlib.import_module("." + _LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError("module 'acausal2d' has no attribute %r" % name)


def compile_model(model: ModelArgument, name: str | None = None) -> CompiledModel:
    """Flatten, index-reduce and prepare ``model`` (a model file's path with
    ``name`` choosing its class, a Component subclass or instance) for
    simulation; returns a :class:`~acausal2d.compiled.CompiledModel` that
    simulates many times with different parameter values without
    recompiling.  The model itself is not changed."""
    from .compiled import CompiledModel, compile_model as _compile
    from .arguments import model_argument
    model = model_argument(model, "compile_model", name)
    return model if isinstance(model, CompiledModel) else _compile(model)


def simulate(model: ModelArgument, stop_time: float | None = None,
             options: RunOptions | None = None, **keywords: Any) -> Result:
    """Compile (if needed) and simulate ``model`` (a model file's path, a
    Component subclass or instance, or a CompiledModel); returns a
    :class:`~acausal2d.result.Result`.  ``options``: a
    :class:`RunOptions`, or its settings as keywords (not both); further
    keywords (params, start) as for
    :meth:`~acausal2d.compiled.CompiledModel.simulate`."""
    from .compiled import CompiledModel
    from .arguments import model_argument, check_simulate_options
    check_simulate_options(keywords)
    settings = {k: keywords.pop(k) for k in OPTION_NAMES if k in keywords}
    opts = RunOptions.of(options, "simulate", stop_time=stop_time, **settings)  # before compiling
    model = model_argument(model, "simulate")
    compiled = model if isinstance(model, CompiledModel) else compile_model(model)
    result: Result = compiled.simulate(options=opts, **keywords)
    return result


def sweep(model: ModelArgument, vary: dict[str, Any] | None = None,
          points: list[dict[str, Any]] | None = None, **options: Any) -> SweepResult:
    """Parameter study on Dask: simulate ``model`` for every combination of
    the ``vary`` values (or every dict of ``points``) and return the table
    (see :func:`acausal2d.analysis.sweep.sweep`; ``options=`` a
    :class:`RunOptions` for every point)."""
    from .analysis.sweep import sweep as _sweep
    from .arguments import check_sweep
    check_sweep(vary, points, options)
    table: SweepResult = _sweep(model, vary=vary, points=points, **options)
    return table


def load_model(path: str | _os.PathLike[str], name: str | None = None,
               **kwargs: Any) -> Component:
    """Instantiate the model of a model file (see :func:`acausal2d.io.loader.load_model`)."""
    from .arguments import check_load
    check_load(path, name, kwargs)
    model: Component = _load(path, name, **kwargs)
    return model


def fit(model: ModelArgument, data: Any, free: dict[str, Any], **options: Any) -> FitResult:
    """Fit the parameters ``free`` of ``model`` to measured curves ``data``
    (see :func:`acausal2d.analysis.fit.fit`; ``options=`` a
    :class:`RunOptions` for its runs); returns a FitResult."""
    from .analysis.fit import fit as _fit
    result: FitResult = _fit(model, data, free, **options)
    return result


def optimize(model: ModelArgument, vary: dict[str, Any], objective: Any,
             **options: Any) -> OptimizeResult:
    """Minimise a run metric ``objective`` over the parameters ``vary``
    (see :func:`acausal2d.analysis.optimize.optimize`; ``options=`` a
    :class:`RunOptions` for its runs); returns an OptimizeResult."""
    from .analysis.optimize import optimize as _optimize
    result: OptimizeResult = _optimize(model, vary, objective, **options)
    return result


def export_fmu(model: ModelArgument, kind: str = "me", out: str | None = None,
               inputs: dict[str, float] | None = None, fixed_states: bool = False,
               options: RunOptions | None = None, params: dict[str, Any] | None = None) -> str:
    """Export a model as an FMI 2.0 FMU with native binaries; kind ``"me"``
    (Model Exchange) or ``"cs"`` (Co-Simulation); ``options``: a
    :class:`RunOptions` whose stop_time and rtol become the FMU's default
    experiment; ``params``: parameter values exported instead of the
    model's (as for simulate); see :func:`acausal2d.fmu.export_fmu`.
    Returns the path."""
    from .fmu import export_fmu as _export
    from .arguments import model_argument
    given = model_argument(model, "export_fmu")
    # a CompiledModel: the model it was compiled from
    instance = given if isinstance(given, Component) else given.model
    path: str = _export(instance, kind=kind, out=out, inputs=inputs, fixed_states=fixed_states,
                        options=options, params=params)
    return path
