"""The compiler driver: flatten -> relations -> aliases -> balance ->
Pantelides -> (at run time) consistent initialization, dummy-derivative
selection and IDA integration.

Parameters stay symbolic inputs of every generated function, so
:meth:`CompiledModel.simulate` with new parameter values never recompiles.
"""
import time as _time

import casadi as ca
import numpy as np

from ..language import symbols
from .aliases import eliminate_all_aliases
from .aliases import substitution as alias_substitution
from .balance import check_balance
from ..language.dsl import STATE_SELECT
from .dummy_derivatives import Formulation, select_dummies
from ..errors import Acausal2dError, InitializationError, ModelDefinitionError
from .flatten import flatten
from ..runtime.initialize import InitialSystem, choose_initial_conditions, solve_consistent
from .pantelides import pantelides
from .relations import extract_relations
from ..tools.result import Result


def compile_model(model):
    """Compile a model instance into a :class:`CompiledModel`."""
    return CompiledModel(model)


def _as_function_of_params(exprs, p):
    """Numeric evaluator for a list of numbers / parameter expressions."""
    e = ca.vertcat(*[ca.SX(x) for x in exprs]) if exprs else ca.SX(0, 1)
    return ca.Function("pfun", [p], [e])


class CompiledModel:
    """A model ready to simulate; reusable with other parameter values."""

    def __init__(self, model):
        t0 = _time.perf_counter()
        self.model = model
        flat = flatten(model)
        self.all_variables = flat.variables
        self.n_flat_equations = len(flat.equations)
        self.parameters = flat.parameters
        self.param_index = {name: k for k, (name, _, _, _) in enumerate(flat.parameters)}
        self.p = ca.vertcat(*[s for _, s, _, _ in flat.parameters]) if flat.parameters \
            else ca.SX(0, 1)
        self.t = symbols.time
        exprs, self.relations = extract_relations([e.expr for e in flat.equations])
        for eq, e in zip(flat.equations, exprs):
            eq.expr = e
        self.d = ca.vertcat(*[r.sym for r in self.relations]) if self.relations \
            else ca.SX(0, 1)
        equations, variables = flat.equations, list(flat.variables)
        check_balance(equations, variables)
        equations, variables, self.aliases = eliminate_all_aliases(equations, variables)
        self.equations = equations
        self.variables = variables
        check_balance(equations, variables)
        self.R = R = pantelides(equations, variables)
        self.n_original = len(equations)
        self.init_system = InitialSystem(R, self.t, self.p, self.d)
        info = {symbols.key(v.sym): v for v in variables}
        self.node_info = [info[symbols.key(symbols.base_and_level(s)[0])] for s in R.var_sym]
        self.priority = [STATE_SELECT.index(v.state_select) for v in self.node_info]
        self.priority_names = [v.state_select for v in self.node_info]
        self.nominal = [float(v.nominal) for v in self.node_info]
        self.node_names = [s.name() for s in R.var_sym]
        level0 = [j for j in range(R.n_var) if R.var_level[j] == 0]
        self.start_fn = _as_function_of_params(
            [self.node_info[j].start for j in level0], self.p)
        self.level0 = np.array(level0, dtype=int)
        self.fixed_nodes = [j for j in level0 if self.node_info[j].fixed]
        self.has_start = [False] * R.n_var
        for j in level0:
            st = self.node_info[j].start
            self.has_start[j] = not (isinstance(st, (int, float)) and st == 0.0)
        z = ca.vertcat(*R.var_sym)
        if self.relations and self.aliases:    # crossing functions in the remaining unknowns
            src, dst = alias_substitution(self.aliases)
            for r, g in zip(self.relations, ca.substitute([r.g for r in self.relations], src,
                                                          [ca.SX(x) for x in dst])):
                r.g = g
        crossings = ca.vertcat(*[r.g for r in self.relations]) if self.relations else None
        self.crossings = crossings
        self.g_nodes_fn = ca.Function("g_nodes", [self.t, z, self.p, self.d], [crossings]) \
            if crossings is not None else None
        # eliminated variables: value = sign * node value + offset(parameters)
        self.alias_names = [a.var.name for a in self.aliases]
        self.alias_node = np.array([-1 if a.rep is None else R.var_index[symbols.key(a.rep.sym)]
                                    for a in self.aliases], dtype=int)
        self.alias_sign = np.array([float(a.sign) for a in self.aliases])
        self.alias_offset_fn = _as_function_of_params([a.offset for a in self.aliases], self.p)
        # derivatives of eliminated variables: der^k(var) = sign * der^k(rep)
        self.alias_der_names, self.alias_der_node, self.alias_der_sign = [], [], []
        for a, j, sign in zip(self.aliases, self.alias_node, self.alias_sign):
            name = a.var.name
            while j >= 0 and R.A[j] >= 0:
                j = R.A[j]
                name = "der(%s)" % name
                self.alias_der_names.append(name)
                self.alias_der_node.append(j)
                self.alias_der_sign.append(sign)
        self.alias_der_node = np.array(self.alias_der_node, dtype=int)
        self.alias_der_sign = np.array(self.alias_der_sign)
        self._formulations = {}
        self.outputs = list(getattr(model, "outputs", ()))
        self.compile_time = _time.perf_counter() - t0

    # ------------------------------------------------------------ helpers
    @property
    def names(self):
        """Names of all time-varying columns a result of this model holds
        (unknowns, aliases, derivatives), known before simulating."""
        return self.node_names + self.alias_names + self.alias_der_names

    def parameter_values(self, params=None):
        """Numeric parameter vector with overrides ``{dotted name: value}``."""
        vals = np.array([v for _, _, v, _ in self.parameters], dtype=float)
        for name, value in (params or {}).items():
            if name in self.param_index:
                vals[self.param_index[name]] = float(value)
                continue
            # vector parameter given as a whole: "rod.r" = (1, 0)
            arr = np.atleast_1d(np.asarray(value, dtype=float))
            keys = ["%s[%d]" % (name, i) for i in range(arr.size)]
            if all(k in self.param_index for k in keys) and \
                    "%s[%d]" % (name, arr.size) not in self.param_index:
                for k, v in zip(keys, arr):
                    vals[self.param_index[k]] = v
                continue
            close = [n for n in self.param_index if name.split(".")[-1] in n][:8]
            raise ModelDefinitionError("unknown parameter %r%s" % (
                name, "; parameters with a similar name: " + ", ".join(close) if close else ""))
        return vals

    def describe_equation(self, i):
        """Text of index-reduced equation i with its origin and order."""
        R = self.R
        eq = self.equations[R.eq_origin[i]]
        lvl = R.eq_level[i]
        return eq.describe() + ("" if lvl == 0 else "  [differentiated %d times]" % lvl)

    def node_name(self, j):
        return self.node_names[j]

    def formulation(self, selection):
        """Index-1 formulation for a dummy selection (cached)."""
        f = self._formulations.get(selection.dummies)
        if f is None:
            f = Formulation(self.R, selection, self.t, self.p, self.d, self.crossings)
            self._formulations[selection.dummies] = f
        return f

    def select(self, t, z, p, d):
        """Dummy-derivative selection at the point z."""
        J = self.init_system.jacobian(t, z, p, d).tocsr()

        def jac(eqs, nodes):
            return J[eqs][:, nodes].toarray()
        return select_dummies(self.R, self.n_original, self.priority, self.nominal, jac)

    def block_conditioning(self, t, z, p, d, level):
        """How regular the dummy block of a selection level is at z: the
        smallest singular value of the nominal-scaled block (its equations
        against the chosen dummies) relative to the largest singular value of
        the equations against all candidates; and the left singular vector
        (weights of the equations in the near-singularity)."""
        J = self.init_system.jacobian(t, z, p, d).tocsr()[level.eqs]
        scale = np.array(self.nominal)

        def scaled(nodes):
            return J[:, nodes].toarray() * scale[nodes][None, :]
        u, sv, _ = np.linalg.svd(scaled(level.chosen))
        top = np.linalg.norm(scaled(level.cands), 2)
        return float(sv[-1]) / max(float(top), 1e-300), u[:, -1]

    def singular_elements(self, eqs, weights):
        """Components whose equations take part in a singular block."""
        w = np.abs(weights)
        names = []
        for i in np.argsort(-w):
            if w[i] < 0.2 * w.max():
                break
            eq = self.equations[self.R.eq_origin[eqs[i]]]
            name = eq.owner.describe() if eq.owner is not None else eq.origin
            if name not in names:
                names.append(name)
        return names

    def relation_values(self, t, z, p, d):
        if not self.relations:
            return d
        g = self.g_nodes_fn(t, z, p, d).full().ravel()
        return np.array([r.value(gv) for r, gv in zip(self.relations, g)])

    def _held_at_start(self, t0, z, p):
        """Nodes held at initialization (see choose_initial_conditions); ties
        are broken by the states a selection at the start guess integrates."""
        R = self.R
        states = ()
        if len(self.fixed_nodes) < R.n_var - R.n_eq:
            try:
                sel = self.select(t0, z, p, np.zeros(len(self.relations)))
                states = [j for j in range(R.n_var) if R.A[j] >= 0 and R.A[j] not in sel.dummies]
            except Acausal2dError:
                states = ()
        return choose_initial_conditions(R, self.fixed_nodes, self.priority_names,
                                         self.has_start, states)

    def initial_values(self, t0, p):
        """Consistent node values and relation values at t0."""
        z = np.zeros(self.R.n_var)
        z[self.level0] = self.start_fn(p).full().ravel()
        held = self._held_at_start(t0, z, p)
        d = np.zeros(len(self.relations))
        d = self.relation_values(t0, z, p, d)
        error = None
        for _ in range(10):
            try:
                zc = solve_consistent(self.init_system, t0, z, p, d, held, z[held],
                                      self.describe_equation, self.node_name)
            except InitializationError as exc:
                # the relations guessed from the start values may be the wrong ones:
                # take them from where Newton ended and try again
                error = exc
                dn = self.relation_values(t0, exc.last, p, d)
                if np.array_equal(dn, d):
                    raise
                d = dn
                continue
            dn = self.relation_values(t0, zc, p, d)
            if np.array_equal(dn, d):
                return zc, d
            d = dn
        if error is not None:
            raise error
        return zc, d

    # ------------------------------------------------------------ simulate
    def simulate(self, stop_time=None, params=None, rtol=None, atol=None, intervals=None,
                 start_time=0.0, output_times=None, progress=None):
        """Simulate and return a :class:`~acausal2d.tools.result.Result`.

        stop_time: end time (default: the model's ``stop_time`` attribute or
        1 s); params: {dotted parameter name: value}; rtol/atol: integrator
        tolerances (default 1e-6 and rtol times each variable's nominal);
        intervals: number of output intervals (default 500) unless
        ``output_times`` is given; progress: optional callable(t, t_end).
        """
        from ..runtime.integrate import integrate
        exp = dict(getattr(self.model, "experiment", {}) or {})
        stop = float(stop_time if stop_time is not None else exp.get("stop_time", 1.0))
        rtol = float(rtol if rtol is not None else exp.get("rtol", 1e-6))
        intervals = int(intervals if intervals is not None else exp.get("intervals", 500))
        if not rtol > 0:
            raise Acausal2dError("rtol must be positive, got %g" % rtol)
        if atol is not None and not atol > 0:
            raise Acausal2dError("atol must be positive, got %g" % atol)
        if output_times is None:
            if not stop > start_time:
                raise Acausal2dError("stop_time (%g s) must be larger than start_time (%g s)"
                                     % (stop, start_time))
            if intervals < 1:
                raise Acausal2dError("intervals must be at least 1, got %d" % intervals)
            output_times = np.linspace(start_time, stop, intervals + 1)
        output_times = np.asarray(output_times, dtype=float)
        if output_times.ndim != 1 or len(output_times) < 2 or \
                np.any(np.diff(output_times) <= 0):
            raise Acausal2dError("output_times must be at least two increasing times")
        p = self.parameter_values(params)
        wall = _time.perf_counter()
        z0, d0 = self.initial_values(float(output_times[0]), p)
        times, Z, events, stats = integrate(self, z0, d0, p, output_times, rtol, atol, progress)
        stats["wall_time"] = _time.perf_counter() - wall
        stats["compile_time"] = self.compile_time
        offsets = self.alias_offset_fn(p).full().ravel()
        bound = self.alias_node < 0
        A = Z[:, np.where(bound, 0, self.alias_node)] * self.alias_sign + offsets
        A[:, bound] = offsets[bound]
        A = np.hstack([A, Z[:, self.alias_der_node] * self.alias_der_sign])
        res = Result(times, self.node_names, Z, self.alias_names + self.alias_der_names, A,
                     list(self.param_index), p, events, stats, self.outputs, self)
        res.singularities = stats.pop("singularities", [])
        res.stopped = stats.pop("stopped", None)
        return res
