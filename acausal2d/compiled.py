"""The user's handle on a compiled model: :func:`compile_model` and
:class:`CompiledModel`, which simulates many times with other parameter
values without recompiling and returns :class:`~acausal2d.result.Result`
objects."""
from __future__ import annotations

import copy as _copy
import difflib
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING
import time as _time

import warnings

import numpy as np
from numpy.typing import NDArray

from .compiler.connectors import loose_connectors_first
from .compiler.gc_pause import cyclic_gc_paused
from .compiler.pipeline import compile_system
from .errors import (Acausal2dError, ModelDefinitionError, SimulationError, StructuralError,
                      translated)
from .runtime.notices import notice
from .runtime.evaluator import Evaluator
from .runtime.initialize import initial_point
from .runtime.selection import select
from .runtime.simulation import Simulation
from .result import Result
from .run_checks import (MAX_RESULT_BYTES, _check_atol, _check_clock, _check_size,  # noqa: F401
                         _experiment)
from .derived import derived_columns, derived_signals
from .language.dsl import Parameter, compile_reads
from .options import RunOptions, number
from .protocols import ParameterValue, Params, Start
from .progress import time_progress
from .threads import our_threads

if TYPE_CHECKING:
    from .analysis.equilibrium import Equilibrium
    from .analysis.linearize import Linearization
    from .analysis.modes import Modes
    from .compiler.system import ParameterEntry, System
    from .derived import DerivedSignal
    from .language.declarations import Parameter as Declaration
    from .language.dsl import Component
    from .options import Atol, Progress
    from .runtime.initialize import InitialPoint
    from .runtime.simulation import RunLog
    from .visual.diagram import DiagramView


def compile_model(model: Component) -> "CompiledModel":
    """Compile a model instance into a :class:`CompiledModel`.  The model
    itself is left as it was: the compiler works on its own copy."""
    return CompiledModel(model)


def own_copy(model: Component) -> Component:
    """A deep copy of ``model`` for the compiler to bind its symbols, the
    parameters' values and the resolved ``world`` into, so that compiling
    never writes into the user's objects (compiling twice, or after a change
    of a parameter, starts from the model as the user made it).  An
    attribute that cannot be copied is named in a
    :class:`~acausal2d.errors.ModelDefinitionError`."""
    try:
        return _copy.deepcopy(model)
    except (TypeError, _copy.Error, RecursionError) as exc:
        where = _uncopyable(model)
        raise ModelDefinitionError(
            "%s cannot be compiled: the compiler works on a copy of the model, and %s "
            "cannot be copied (%s). Keep such objects out of the components (e.g. pass "
            "numbers or functions instead of open files, locks or modules)."
            % (model.describe(), where, exc)) from None


def _uncopyable(model: Component) -> str:
    """'component.attribute' of the first attribute deepcopy refuses."""
    for comp in model.components():
        for name, value in vars(comp).items():
            if name.startswith("_"):
                continue
            try:
                _copy.deepcopy(value)
            except (TypeError, _copy.Error, RecursionError):
                return "%s.%s" % (comp.describe(), name)
    return "an attribute"


def _with_values(model: Component, values: Mapping[str, float | tuple[float, ...]]) -> Component:
    """A copy of ``model`` (as given to the compiler, not its compiled copy)
    with the parameters ``values`` ({dotted name: value checked by
    :meth:`CompiledModel.parameter_values`}) given as if by keyword (the
    model is not changed)."""
    copy = own_copy(model)
    by_path = {c.path: c for c in copy.components()}
    for name, value in values.items():
        path, _, pname = name.rpartition(".")
        comp = by_path[path]
        comp._param_values[pname] = value
        comp._given.add(pname)
    return copy


class CompiledModel:
    """A model ready to simulate; reusable with other parameter values.

    ``system`` is the frozen :class:`~acausal2d.compiler.system.System`."""

    model: Component
    """The compiler's own copy of the model it was given."""
    system: System
    derived: list[DerivedSignal]
    """The components' derived signals (:func:`acausal2d.derived.derived_signals`)."""
    compile_time: float
    """Wall seconds the compilation took."""

    def __init__(self, model: Component) -> None:
        t0 = _time.perf_counter()
        given, model = model, own_copy(model)
        self.model = model
        with compile_reads() as reads:
            with loose_connectors_first(model), \
                    translated("compiling %s" % type(model).__name__, StructuralError):
                self.system = compile_system(model)
            self.system.model_name = type(model).__name__  # named in the native runtime's notices
            self._whole = self._whole_parameters()
            self._units: dict[str, str] | None = None
            self.derived = derived_signals(model, self.system.names)
        self.structural = self._read_while_compiling(reads)
        self._recompiled: dict[tuple[tuple[str, str], ...], CompiledModel] = {}
        self._said_recompiled: set[tuple[str, ...]] = set()    # parameters named in a notice
        self._source = given if self.structural else None     # compiled again from it
        self.compile_time = _time.perf_counter() - t0

    structural: frozenset[str]
    """Parameters (vectors as a whole) whose value the compiler read: the
    compiled model depends on them beyond their symbol (a pulley's ``m``
    decides whether it has mass), so a run refuses a changed value of one
    (:meth:`parameter_values`) and the live page offers no slider for it."""

    def is_structural(self, name: str) -> bool:
        """True where the scalar parameter ``name`` (``B0.r[0]``, ``spring.k``)
        is, or is an element of, a :attr:`structural` parameter."""
        return self._whole_name(name) in self.structural

    def _read_while_compiling(self, reads: list[tuple[Component, str]]) -> frozenset[str]:
        found = set()
        ours = {id(c) for c in self.model.components()}     # not a class's throwaway instance
        for comp, name in reads:
            if id(comp) not in ours:
                continue
            path = comp.path
            full = "%s.%s" % (path, name) if path else name
            if full in self._whole:
                found.add(full)
        return frozenset(found)

    # ------------------------------------------------------------ parameters
    @property
    def parameters(self) -> tuple[ParameterEntry, ...]:
        """(name, symbol, value, declaration) of every scalar parameter."""
        return self.system.parameters

    @property
    def names(self) -> tuple[str, ...]:
        """Names of all time-varying columns a result of this model holds
        (the system's and the components' derived signals)."""
        return self.system.names + tuple(d[0] for d in self.derived)

    @property
    def signal_names(self) -> dict[str, str]:
        """{signal connector: its column}: ``close.y`` for ``close.y.u``, the
        name a signal is written by (a result reads both)."""
        known = set(self.names)
        out = {}
        for comp in self.model.components():
            for conn in comp._connectors.values():
                if conn.signal is not None:
                    full = conn.path + ".u"
                    if full in known and conn.path not in known:
                        out[conn.path] = full
        return out

    @property
    def outputs(self) -> list[str]:
        """The signals the model declares as its outputs."""
        return self.system.outputs

    @property
    def parameter_names(self) -> list[str]:
        """Names of all parameters: vectors as a whole and by element."""
        return list(self._whole) + [n for n, *_ in self.system.parameters if n not in self._whole]

    @property
    def units(self) -> dict[str, str]:
        """{column or parameter name: unit} from the declarations; the
        k-th derivative of ``x`` gets x's unit divided by s^k."""
        if self._units is None:
            s = self.system
            units: dict[str, str] = {}
            for j, name in enumerate(s.node_names):
                units[name] = derivative_unit(s.node_info[j].unit, s.structure.var_level[j])
            for a in s.aliases:
                units[a.var.name] = a.var.unit
            for name in s.alias_der_names:
                base = name
                order = 0
                while base.startswith("der("):
                    base, order = base[4:-1], order + 1
                units[name] = derivative_unit(units.get(base, ""), order)
            for name, _, (base, order) in self.derived:
                units[name] = derivative_unit(units.get(base, ""), order)
            for name, (decl, _) in self._whole.items():
                units[name] = decl.unit
            for name, _, _, decl in s.parameters:
                units.setdefault(name, decl.unit)
            self._units = units
        return self._units

    @property
    def parameter_declarations(self) -> dict[str, tuple[Declaration, list[int]]]:
        """{parameter name (vectors as a whole): (its declaration, indices
        of its elements in :meth:`parameter_values`)}, in declaration order."""
        return dict(self._whole)

    def parameters_table(self) -> str:
        """Every parameter (vectors as a whole) with its value, unit, rule
        and description, as a fixed-width text table (``acausal2d params``)."""
        vals = self.parameter_values()
        rows = [("parameter", "value", "unit", "rule", "description")]
        for name, (decl, idx) in self._whole.items():
            v = vals[idx]
            text = "%.6g" % v[0] if len(v) == 1 else "(%s)" % ", ".join("%.6g" % x for x in v)
            rows.append((name, text, decl.unit or "-", decl.rule or "-", decl.doc))
        widths = [max(len(r[i]) for r in rows) for i in range(4)]
        lines = ["  ".join(c.ljust(w) for c, w in zip(r, widths)) + "  " + r[4] for r in rows]
        lines.insert(1, "  ".join("-" * w for w in widths) + "  " + "-" * 11)
        return "\n".join(line.rstrip() for line in lines)

    def _whole_parameters(self) -> dict[str, tuple[Declaration, list[int]]]:
        """{parameter name (vectors as a whole): (declaration, indices)}."""
        whole: dict[str, tuple[Declaration, list[int]]] = {}
        for k, (name, _, _, decl) in enumerate(self.system.parameters):
            base = name.rsplit("[", 1)[0] if name.endswith("]") else name
            whole.setdefault(base, (decl, []))[1].append(k)
        return whole

    def parameter_values(self, params: Params | None = None, structural: bool = False,
                         rules: bool = True) -> NDArray[np.float64]:
        """Numeric parameter vector with overrides ``{dotted name: value}``
        (vector parameters as a whole, ``"rod.r": (1, 0)``, or by element,
        ``"rod.r[0]"``); every value is checked against its declaration, and
        the rules between parameters of each component changed
        (:meth:`~acausal2d.language.dsl.Component.check_parameters`) on the
        final values.  A changed :attr:`structural` parameter is refused,
        naming it (:meth:`simulate` compiles the model again instead),
        unless ``structural`` (values checked only); ``rules`` False leaves
        the rules between parameters to a later call with all the values."""
        vals = np.array([v for _, _, v, _ in self.system.parameters], dtype=float)
        if params is None:
            return vals
        if not isinstance(params, dict):
            raise ModelDefinitionError("params must be a dict {'comp.param': value}, got %r"
                                       % (params,))
        base = vals.copy()
        for name, value in params.items():
            index = self._indices(name)
            vals[index] = np.atleast_1d(self._checked(name, value))
        changed = [n for n in params if not np.array_equal(vals[self._indices(n)],
                                                             base[self._indices(n)])]
        if rules:
            self._check_components(changed, vals)
        if not structural:
            self._refuse_structural(changed)
        return vals

    def _whole_name(self, name: str) -> str:
        return name.rsplit("[", 1)[0] if name not in self._whole and name.endswith("]") else name

    def _check_components(self, changed: list[str], vals: NDArray[np.float64]) -> None:
        """The rules between parameters of each component with a changed
        parameter, on the values ``vals``."""
        paths = {self._whole_name(n).rsplit(".", 1)[0] if "." in n else "" for n in changed}
        if not paths:
            return
        for comp in self.model.components():
            if comp.path not in paths:
                continue
            prefix = comp.path + "." if comp.path else ""

            def value(pname: str, prefix: str = prefix) -> float | tuple[float, ...]:
                return self._whole_value(prefix + pname, vals)
            comp.check_parameters(value)

    def _whole_value(self, name: str, vals: NDArray[np.float64]) -> float | tuple[float, ...]:
        """The value of parameter ``name`` (a whole vector) in ``vals``."""
        decl, idx = self._whole[name]
        return float(vals[idx[0]]) if decl.size == 1 else tuple(float(vals[k]) for k in idx)

    def for_values(self, params: Params | None) -> "CompiledModel":
        """This model, or, where ``params`` change a :attr:`structural`
        parameter, the model compiled again with the new values (kept for
        the next run with the same values).  One line on stderr names the
        parameters and their first new values, once per model and set of
        parameters: an optimisation over them is not a line per trial."""
        if not params or not isinstance(params, dict) or not self.structural:
            return self
        vals = self.parameter_values(params, structural=True)
        base = self.parameter_values()
        names = sorted({self._whole_name(n) for n in params} & self.structural)
        new = {n: self._whole_value(n, vals) for n in names
               if not np.array_equal(vals[self._whole[n][1]], base[self._whole[n][1]])}
        if not new:
            return self
        key = tuple(sorted((n, repr(v)) for n, v in new.items()))
        cache = self._recompiled
        if key not in cache:
            if tuple(new) not in self._said_recompiled:      # a study: said once, not per trial
                self._said_recompiled.add(tuple(new))
                notice("%s %s read while %s is compiled; it is compiled again with %s (and for "
                       "each new value)" % (", ".join(new), "is" if len(new) == 1 else "are",
                                            type(self.model).__name__,
                                            ", ".join("%s = %s" % (n, v) for n, v in new.items())))
            if len(cache) >= 8:
                cache.pop(next(iter(cache)))
            assert self._source is not None              # kept where a parameter is structural
            cache[key] = CompiledModel(_with_values(self._source, new))
        return cache[key]

    def _refuse_structural(self, changed: list[str]) -> None:
        hit = sorted({self._whole_name(n) for n in changed} & self.structural)
        if hit:
            raise ModelDefinitionError(
                "parameter %s is read while the model is compiled (it decides the model's "
                "structure or start layout), so a new value would change nothing in this "
                "compiled model; give it in the model file, or run the model through "
                "simulate(), which compiles it again for it" % ", ".join(hit))

    def _indices(self, name: str) -> list[int]:
        if name in self._whole:
            return self._whole[name][1]
        if name in self.system.param_index:
            return [self.system.param_index[name]]
        known = list(self._whole)
        close = difflib.get_close_matches(str(name), known, n=3, cutoff=0.85)
        close += [n for n in known if str(name).split(".")[-1] in n and n not in close]
        if close:
            raise ModelDefinitionError("unknown parameter %r; did you mean %s?" % (
                name, ", ".join(close[:6])))
        raise ModelDefinitionError("unknown parameter %r; parameters: %s%s" % (
            name, ", ".join(known[:20]), " ... (acausal2d params lists all %d)" % len(known)
            if len(known) > 20 else ""))

    def _checked(self, name: str, value: ParameterValue) -> float | tuple[float, ...]:
        comp = name.rsplit(".", 1)[0] if "." in name else "<model>"
        if name in self._whole:
            decl = self._whole[name][0]
            return decl.validated(value, comp)
        decl = self.system.parameters[self.system.param_index[name]][3]
        return _Scalar(decl).validated(value, comp)

    # ------------------------------------------------------------ analysis
    def initial_point(self, t0: float = 0.0, params: Params | None = None,
                      start: Start | None = None) -> InitialPoint:
        """Consistent values at t0: an
        :class:`~acausal2d.runtime.initialize.InitialPoint` with the
        selection made there; ``start`` as for :meth:`simulate`."""
        p = self.parameter_values(params)
        held = self.start_indices(start)
        with loose_connectors_first(self.model), \
                translated("initializing %s" % type(self.model).__name__), cyclic_gc_paused():
            ev = Evaluator(self.system, p)
            point = initial_point(self.system, ev, t0, p, held)
            if point.selection is None:
                point.selection = select(self.system, ev, t0, point.z, point.d)
        return point

    @property
    def start_names(self) -> list[str]:
        """Names of the unknowns whose start values a run may replace
        (``simulate(start=...)``): those of level 0 (no derivative of
        another unknown), with the fixed ones."""
        s = self.system
        return [s.node_names[j] for j in s.level0]

    def start_indices(self, start: Start | None) -> dict[int, float] | None:
        """``start`` ({unknown: value}) as {node index: value}, checked: the
        names among :attr:`start_names`, the values finite numbers."""
        if not start:
            return None
        if not isinstance(start, dict):
            raise Acausal2dError("start must be a dict {'joint.phi': value}, got %r" % (start,))
        index = {self.system.node_names[j]: int(j) for j in self.system.level0}
        out: dict[int, float] = {}
        for name, value in start.items():
            if name not in index:
                raise Acausal2dError("start %r: not an unknown that takes a start value; those "
                                     "are %s" % (name, ", ".join(list(index)[:12])))
            out[index[name]] = float(number("start %s" % name, value))
        return out

    def linearize(self, at: float | None = None, equilibrium: bool = False,
                  params: Params | None = None, inputs: Sequence[str] = (),
                  outputs: Sequence[str] | None = None, start: Start | None = None) -> Linearization:
        """State-space matrices A, B, C, D at time ``at`` of a run or at the
        static equilibrium: a
        :class:`~acausal2d.analysis.linearize.Linearization` (see
        :func:`acausal2d.analysis.modes.linearize`)."""
        from .analysis.modes import linearize
        return linearize(self, at, equilibrium, params, inputs, outputs, start)

    def modes(self, at: float | None = None, equilibrium: bool = False,
              params: Params | None = None, start: Start | None = None) -> Modes:
        """Natural frequencies, damping ratios and mode shapes: a
        :class:`~acausal2d.analysis.modes.Modes` (see
        :func:`acausal2d.analysis.modes.modes`)."""
        from .analysis.modes import modes
        return modes(self, at, equilibrium, params, start)

    def equilibrium(self, t: float = 0.0, params: Params | None = None,
                    start: Start | None = None) -> Equilibrium:
        """The static equilibrium (all state derivatives zero) at time t: an
        :class:`~acausal2d.analysis.equilibrium.Equilibrium` (see
        :func:`acausal2d.analysis.equilibrium.find_equilibrium`)."""
        from .analysis.equilibrium import find_equilibrium
        with translated("searching the equilibrium of %s" % type(self.model).__name__):
            return find_equilibrium(self, t, params, start)

    def describe_equation(self, i: int) -> str:
        """Text of index-reduced equation i with its origin and order."""
        return self.system.describe_equation(i)

    def diagram(self) -> "DiagramView":
        """The model drawn from its code (a box per component, a line per
        ``connect``, the unconnected connectors marked): a notebook shows
        it; ``.svg`` is its text, ``.save(path)`` writes it (SVG, or HTML
        in which sub-models open)."""
        from .visual.diagram import DiagramView
        return DiagramView(self.model)

    def _repr_svg_(self) -> str:
        return self.diagram().svg

    # ------------------------------------------------------------ simulate
    def run_options(self, options: RunOptions | None = None, **keywords: object) -> RunOptions:
        """The :class:`~acausal2d.options.RunOptions` of a run of this model:
        ``options`` or the keywords (not both), resolved with the model's
        ``experiment`` and checked against the model (atol, output times)."""
        opts = RunOptions.of(options, "simulate", **keywords).resolved(_experiment(self.model))
        _check_atol(opts.atol, self.system.node_names)
        if opts.output_times is None:                   # before the grid is made
            assert opts.intervals is not None           # resolved() fills it
            _check_size(opts.intervals, len(self.names))
        _check_clock(opts.times())
        return opts

    def simulate(self, stop_time: float | None = None, params: Params | None = None,
                 rtol: float | None = None, atol: Atol = None, intervals: int | None = None,
                 start_time: float | None = None,
                 output_times: Sequence[float] | NDArray[np.float64] | None = None,
                 progress: Progress | None = None, max_steps: int | None = None,
                 max_wall_time: float | None = None, start: Start | None = None,
                 options: RunOptions | None = None, native: str | None = None) -> Result:
        """Simulate and return a :class:`~acausal2d.result.Result`.

        params: {dotted parameter name: value}; start: {unknown: value}
        replacing start values of the model (a fixed one stays fixed, a
        guess moves the assembly guess; names from :attr:`start_names`);
        options: a :class:`~acausal2d.options.RunOptions`, or its settings
        as keywords (stop_time, rtol, atol, intervals, start_time,
        output_times, progress, max_steps, max_wall_time, native; see
        there; not both).  A run that uses up a budget stops early with the
        data so far (``result.stopped`` says why).  A changed
        :attr:`structural` parameter compiles the model again
        (:meth:`for_values`).
        """
        opts = self.run_options(options, stop_time=stop_time, rtol=rtol, atol=atol,
                                intervals=intervals, start_time=start_time,
                                output_times=output_times, progress=progress,
                                max_steps=max_steps, max_wall_time=max_wall_time,
                                native=native)
        other = self.for_values(params)
        if other is not self:                  # a structural parameter changed: compiled again
            return other.simulate(params=params, start=start, options=opts)
        p = self.parameter_values(params)
        held = self.start_indices(start)
        self.system.check_fixed_values(p)
        self._warn_far_angles(held, opts.rtol)
        tol = np.asarray(opts.atol) if isinstance(opts.atol, tuple) else opts.atol
        times = opts.times()
        assert opts.rtol is not None                    # resolved() fills it
        try:
            with loose_connectors_first(self.model), \
                    translated("simulating %s" % type(self.model).__name__), our_threads(), \
                    time_progress(opts.progress, times[0], times[-1]) as progress:
                log = Simulation(self.system, p, times, opts.rtol, tol, progress,
                                 opts.max_steps, opts.max_wall_time, held, opts.native).run()
        except SimulationError as exc:
            partial = getattr(exc, "partial", None)
            if partial is not None:
                setattr(exc, "result", self._result(partial, p))
            raise
        return self._result(log, p)

    ANGLE_RESOLUTION = 0.1
    """rad: a start angle whose integrator tolerance (rtol |phi|) is coarser
    than this is warned about (:meth:`_warn_far_angles`)."""

    def _warn_far_angles(self, held: dict[int, float] | None, rtol: float | None) -> None:
        """A warning for each angle (unit rad) that starts so far from one
        turn that the run's tolerance on it, rtol |phi|, exceeds
        :data:`ANGLE_RESOLUTION`: its motion would be lost in rounding (1e17
        rad: no step changes it).  Its start is best given modulo 2 pi."""
        s, rtol = self.system, float(rtol or 1e-6)
        for j in s.level0:
            info = s.node_info[j]
            value = (held or {}).get(int(j), info.start)
            if info.unit != "rad" or isinstance(value, bool) or \
                    not isinstance(value, (int, float, np.floating)):
                continue
            if rtol * abs(float(value)) > self.ANGLE_RESOLUTION:
                warnings.warn("%s starts at %.6g rad, far outside one turn: with rtol %g the "
                              "run resolves it only to %.3g rad, and its motion is lost in "
                              "rounding; give its start modulo 2 pi (math.remainder(phi, "
                              "2 * math.pi))" % (s.node_names[j], float(value), rtol,
                                                rtol * abs(float(value))), stacklevel=3)

    def _result(self, log: RunLog, p: NDArray[np.float64]) -> Result:
        """The :class:`Result` of a run log."""
        log.stats.compile_time = self.compile_time
        s = self.system
        res = Result(log.times, s.node_names, log.nodes,
                     s.alias_names + s.alias_der_names, s.alias_columns(log.nodes, p),
                     [name for name, *_ in s.parameters], p, log.events,
                     log.stats.as_dict(), self.outputs, self)
        res.add_columns(derived_columns(res, self.derived))
        res.singularities = log.singularities
        res.stopped = log.stopped
        res.states = log.states
        res.native_notes = getattr(log, "native_notes", [])
        res.event_texts = list(getattr(log, "event_texts", log.events))
        res.short_names = self.signal_names
        return res


def derivative_unit(unit: str, order: int = 1) -> str:
    """Unit of the ``order``-th time derivative of a quantity of ``unit``:
    ``m`` -> ``m/s`` -> ``m/s2``, ``rad/s`` -> ``rad/s2``, ``""`` -> ``1/s``,
    ``N/m`` -> ``N/(m.s)``."""
    for _ in range(order):
        if not unit:
            unit = "1/s"
        elif "/" not in unit:
            unit += "/s"
        else:
            num, den = unit.split("/", 1)
            if den == "s":
                den = "s2"
            elif den[:1] == "s" and den[1:].isdigit():
                den = "s%d" % (int(den[1:]) + 1)
            elif den.startswith("(") and den.endswith(".s)"):
                den = den[:-3] + ".s2)"
            else:
                den = "(%s.s)" % den
            unit = num + "/" + den
    return unit


class _Scalar:
    """The rules of a vector parameter's declaration applied to one element."""

    def __init__(self, decl: Declaration) -> None:
        self.decl = decl

    def validated(self, value: ParameterValue, where: str) -> float | tuple[float, ...]:
        """``value`` checked by the declaration's rules (see
        :meth:`acausal2d.language.declarations.Parameter.validated`)."""
        d = self.decl
        one = Parameter(0.0, d.unit, d.doc, d.min, d.max, d.positive)
        one.name = d.name
        return one.validated(value, where)
