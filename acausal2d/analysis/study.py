"""Model-declared studies: the analyses a model's author wants run, beyond
the plain simulation, such as a sweep over a friction coefficient or plots
over a drive angle with a closed-form comparison.

A study is a function of a :class:`StudyContext` declared in the model class
with the :func:`study` decorator::

    class PulleyBlock(Component):
        @study
        def efficiency(ctx):
            '''Efficiency over the bearing friction mu (Bild 7.24).'''
            table = ctx.sweep(vary={"U1.mu,L2.mu": "0:0.5:11"}, metrics=eta)
            ctx.save(table.plot(), "efficiency")

``acausal2d study MODEL.py [NAME ...] --out DIR`` runs them (all by
default; ``--list`` lists them) and writes their figures and tables into
DIR.  The context gives the model's default run (``ctx.result``, simulated
once), further runs (``ctx.simulate(...)``), parameter studies on Dask bound
to the model file (``ctx.sweep(...)``, with the command's ``--scheduler`` and
``--workers``), new matplotlib figures (``ctx.figure()``, object API) and
atomic writes of figures and tables into the output folder (``ctx.save``).
"""
import inspect
from collections.abc import Callable
from typing import Any
import os

from ..errors import Acausal2dError
from ..usercode import user_error_text


class Study:
    """A declared study (made by :func:`study`): ``name``, ``doc`` (first
    paragraph of the function's docstring, one line) and the function."""

    def __init__(self, fn):
        self.fn = fn
        self.name = fn.__name__
        self.doc = " ".join((inspect.getdoc(fn) or "").split("\n\n")[0].split())

    def __set_name__(self, owner, name):
        self.name = name

    def __get__(self, obj, objtype=None):
        return self

    def __call__(self, context):
        return self.fn(context)

    def __repr__(self):
        return "Study(%s)" % self.name


def study(fn: Callable[..., Any]) -> "Study":
    """Decorator declaring a study of a model class; the function takes a
    :class:`StudyContext`."""
    return Study(fn)


def declared_studies(model_cls):
    """{name: Study} of a model class (inherited ones included), in
    declaration order."""
    found = {}
    for klass in reversed(model_cls.__mro__):
        for name, attr in vars(klass).items():
            if isinstance(attr, Study):
                found[name] = attr
    return found


class StudyContext:
    """What a study works with.  ``model`` is the model instance (built from
    ``model_file``), ``out`` the output folder, ``files`` the paths written
    so far; ``sweep_options`` (scheduler, workers, progress) go to every
    :meth:`sweep` (progress also to :meth:`simulate`)."""

    def __init__(self, model_file, model, out, sweep_options=None, stream=None):
        self.model_file = os.path.abspath(model_file)
        self.model = model
        self.out = out
        self.sweep_options = dict(sweep_options or {})
        self.files = []
        self.stream = stream
        self._compiled = None
        self._result = None

    @property
    def compiled(self):
        """The model compiled once (a CompiledModel)."""
        if self._compiled is None:
            from ..compiled import compile_model
            self._compiled = compile_model(self.model)
        return self._compiled

    @property
    def result(self):
        """The model's default run (its ``experiment``), simulated once."""
        if self._result is None:
            self._result = self.simulate()
        return self._result

    def simulate(self, **options):
        """A further run of the compiled model (options of
        :meth:`CompiledModel.simulate`; its progress bar as the command's
        ``--quiet`` says, unless ``options`` say otherwise)."""
        if "options" not in options:
            options.setdefault("progress", self.sweep_options.get("progress", True))
        return self.compiled.simulate(**options)

    def sweep(self, **options):
        """:func:`acausal2d.analysis.sweep.sweep` of this model file and class
        on the command's cluster (``scheduler``/``workers``)."""
        from .sweep import sweep
        kwargs = dict(self.sweep_options)
        if "options" in options:            # a RunOptions carries its own progress
            kwargs.pop("progress", None)
        kwargs.update(options)
        kwargs.setdefault("model_name", type(self.model).__name__)
        return sweep(self.model_file, **kwargs)

    def figure(self, rows=1, cols=1, size=(8, 4.5), **kwargs):
        """A new matplotlib Figure (Agg canvas attached) and its axes
        (``fig.subplots(rows, cols, **kwargs)``)."""
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
        fig = Figure(figsize=size)
        FigureCanvasAgg(fig)
        return fig, fig.subplots(rows, cols, **kwargs)

    def save(self, obj, name):
        """Write a Figure (``name.png``), a SweepResult (``name.csv``) or a
        Result (``name.csv``) into the output folder, atomically; returns the
        path."""
        from ..visual.plotting import save_figure
        from ..result import Result
        from .sweep import SweepResult
        if isinstance(obj, (SweepResult, Result)):
            path = obj.to_csv(os.path.join(self.out, name + ".csv"))
        elif hasattr(obj, "savefig"):
            obj.tight_layout()
            path = save_figure(obj, os.path.join(self.out, name + ".png"))
        else:
            raise Acausal2dError("a study saves figures, sweep tables or results, not %s"
                                 % type(obj).__name__)
        self.files.append(path)
        return path

    def note(self, text):
        """Print a line of the study's report."""
        print("  " + text, file=self.stream)


def run_studies(model_file, model, names=None, out="out", sweep_options=None, stream=None):
    """Run the declared studies ``names`` (default all) of ``model`` (an
    instance built from ``model_file``); returns the paths written."""
    studies = declared_studies(type(model))
    if not studies:
        raise Acausal2dError("%s declares no studies (methods decorated with @acausal2d.study)"
                             % type(model).__name__)
    unknown = [n for n in names or () if n not in studies]
    if unknown:
        raise Acausal2dError("%s has no study %s; its studies: %s" % (
            type(model).__name__, ", ".join(repr(n) for n in unknown), ", ".join(studies)))
    os.makedirs(out, exist_ok=True)
    ctx = StudyContext(model_file, model, out, sweep_options, stream)
    for name in names or list(studies):
        print("%s.%s: %s" % (type(model).__name__, name, studies[name].doc), file=stream)
        _run_study(studies[name], ctx, "%s.%s" % (type(model).__name__, name))
    return ctx.files


def _run_study(st, ctx, label):
    """Run one study; an error it raises is reported with its name
    (``label``, e.g. ``PulleyBlock.efficiency``) and the exception's type,
    without a traceback."""
    try:
        st(ctx)
    except Acausal2dError as exc:       # the same kind of error, with the study's name
        try:
            named = type(exc)("study %s: %s" % (label, exc))
        except TypeError:
            named = Acausal2dError("study %s: %s" % (label, exc))
        raise named from None
    except (KeyboardInterrupt, SystemExit, MemoryError):
        raise
    except Exception as exc:           # noqa: BLE001 - the model author's code
        raise Acausal2dError(user_error_text("study %s" % label, exc)) from exc
