"""acausal2d: acausal, equation-based simulation of planar mechanisms.

Write models as Python classes (:class:`Component`), then :func:`compile_model`
and :meth:`CompiledModel.simulate` them, or call :func:`simulate` directly.
"""
import os as _os

__version__ = "0.1.0"
"""The package version (``acausal2d --version``; pyproject.toml reads it from here)."""

_os.environ.setdefault("OMP_NUM_THREADS", "1")  # before scikit-sundae is imported

from casadi import (sin, cos, tan, asin, acos, atan, atan2, sqrt, exp, log, fabs,  # noqa: E402,F401
                    fmin, fmax, sign, if_else, pi)
import importlib

from .language.connectors import (BandPort, Connector, Frame, RealInput, RealOutput,  # noqa: E402,F401
                         RotationalFlange, TranslationalFlange, HydraulicPort)
from .language.dsl import Component, Outer, Parameter, Variable, start  # noqa: E402,F401
from .errors import (Acausal2dError, InitializationError, ModelDefinitionError,  # noqa: E402,F401
                     SimulationError, StructuralError)
from .language.symbols import der, time, time_derivative  # noqa: E402,F401
from .analysis.check import check  # noqa: E402,F401
from .analysis.compare import compare as _compare  # noqa: E402
from .analysis.study import study  # noqa: E402,F401
from .io import loader as _loader  # noqa: E402
from .io.loader import load_model as _load

Model = Component
"""Alias of :class:`Component` for top-level models."""


def compare(result, reference, signals=None, **options):
    """Compare a result with a reference signal by signal, the planar
    library's Modelica aliases included (``body.r[1]`` is our ``body.x``);
    see :func:`acausal2d.analysis.compare.compare` for the options.
    Returns a Comparison."""
    import acausal2d.library.planar  # noqa: F401  (declares the aliases)
    return _compare(result, reference, signals=signals, **options)

__all__ = [
    # modelling
    "Component", "Model", "Parameter", "Variable", "start", "Outer", "der", "time",
    "time_derivative", "Connector", "Frame", "RotationalFlange", "TranslationalFlange",
    "BandPort", "RealInput", "RealOutput", "HydraulicPort",
    # symbolic functions for equations
    "sin", "cos", "tan", "asin", "acos", "atan", "atan2", "sqrt", "exp", "log", "fabs", "fmin",
    "fmax", "sign", "if_else", "pi",
    # running and analysing
    "load_model", "compile_model", "CompiledModel", "simulate", "Result", "check", "compare",
    "sweep", "study", "fit", "optimize", "export_fmu",
    # errors
    "Acausal2dError", "ModelDefinitionError", "StructuralError", "InitializationError",
    "SimulationError",
    "__version__",
]

_LAZY = {"CompiledModel": "compiled", "Result": "result"}


def _read_mec2(path):
    """A mec2 model file, read by the library's importer
    (:func:`acausal2d.library.nodes.mec2.load_mec2`; imported when one is read)."""
    from .library.nodes.mec2 import load_mec2
    return load_mec2(path)


_loader.register_reader(".json", "mec2", _read_mec2)


def __getattr__(name):
    """``CompiledModel`` and ``Result`` on first use: they import the
    runtime (IDA, scikit-sundae), which ``import acausal2d`` alone does not
    need."""
    if name in _LAZY:
        value = getattr(importlib.import_module("." + _LAZY[name], __name__), name)
        globals()[name] = value
        return value
    raise AttributeError("module 'acausal2d' has no attribute %r" % name)


def compile_model(model, name=None):
    """Flatten, index-reduce and prepare ``model`` (a model file's path with
    ``name`` choosing its class, a Component subclass or instance) for
    simulation; returns a :class:`~acausal2d.compiled.CompiledModel` that
    simulates many times with different parameter values without
    recompiling.  The model itself is not changed."""
    from .compiled import CompiledModel, compile_model as _compile
    from .arguments import model_argument
    model = model_argument(model, "compile_model", name)
    return model if isinstance(model, CompiledModel) else _compile(model)


def simulate(model, stop_time=None, **options):
    """Compile (if needed) and simulate ``model`` (a model file's path, a
    Component subclass or instance, or a CompiledModel); returns a
    :class:`~acausal2d.result.Result`.  See
    :meth:`~acausal2d.compiled.CompiledModel.simulate`."""
    from .compiled import CompiledModel
    from .arguments import model_argument, check_simulate_options
    model = model_argument(model, "simulate")
    check_simulate_options(options)
    compiled = model if isinstance(model, CompiledModel) else compile_model(model)
    return compiled.simulate(stop_time=stop_time, **options)


def sweep(model, vary=None, points=None, **options):
    """Parameter study on Dask: simulate ``model`` (a model file) for every
    combination of the ``vary`` values (or every dict of ``points``) and
    return the table (see :func:`acausal2d.analysis.sweep.sweep`)."""
    from .analysis.sweep import sweep as _sweep
    from .arguments import check_sweep
    check_sweep(vary, points, options)
    return _sweep(model, vary=vary, points=points, **options)


def load_model(path, name=None, **kwargs):
    """Instantiate the model of a model file (see :func:`acausal2d.io.loader.load_model`)."""
    from .arguments import check_load
    check_load(path, name, kwargs)
    return _load(path, name, **kwargs)


def fit(model, data, free, **options):
    """Fit the parameters ``free`` of ``model`` to measured curves ``data``
    (see :func:`acausal2d.analysis.fit.fit`); returns a FitResult."""
    from .analysis.fit import fit as _fit
    return _fit(model, data, free, **options)


def optimize(model, vary, objective, **options):
    """Minimise a run metric ``objective`` over the parameters ``vary``
    (see :func:`acausal2d.analysis.optimize.optimize`); returns an
    OptimizeResult."""
    from .analysis.optimize import optimize as _optimize
    return _optimize(model, vary, objective, **options)


def export_fmu(model, kind="me", out=None, inputs=None, fixed_states=False):
    """Export a model (an instance, or the path of a model file) as an FMI
    2.0 FMU with native binaries; kind ``"me"`` (Model Exchange) or ``"cs"``
    (Co-Simulation); see :func:`acausal2d.fmu.export_fmu`.  Returns the path."""
    from .fmu import export_fmu as _export
    from .arguments import model_argument
    model = model_argument(model, "export_fmu")
    if not isinstance(model, Component):
        model = model.model          # a CompiledModel: the model it was compiled from
    return _export(model, kind=kind, out=out, inputs=inputs, fixed_states=fixed_states)
