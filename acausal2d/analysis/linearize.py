"""Linearisation of a compiled model at an operating point.

The run integrates the index-1 system of a dummy selection: the states x
(the selected states, nodes whose derivative node is not a dummy), their
derivative nodes and the algebraic unknowns follow from all index-reduced
equations E(t, z, p, d) = 0 with the states held (see
:mod:`acausal2d.compiler.index1`).  With G(z) = [E(t, z, p, d); z[x] - x]
the implicit function theorem gives the exact sensitivities

    dz/dx = -G_z^-1 G_x = G_z^-1 [0; I],   dz/du = -G_z^-1 [E_u; 0]

(dz/dx = -g_z^-1 g_x of the algebraic part), with E_z and E_u the CasADi
(automatic, exact) derivatives.  The state-space matrices are the rows of
the state derivatives: A = dz/dx[der(x)], B = dz/du[der(x)]; an output y
(any node, eliminated alias or alias derivative) gives C = dy/dx, D = dy/du.

Inputs u are parameters (a ``Constant`` source's ``k`` feeding a
``RealInput``, a force or torque value, a preload).  The model's top-level
``RealInput``s that nothing inside drives become such parameters with
:func:`acausal2d.library.inputs.bind_inputs` before compiling: each gets
a ``Constant`` source ``<input>_source`` (``k`` its value, default 0), and
the input is named by its connector (``u``) or by the parameter
(``u_source.k``).
"""
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from ..errors import Acausal2dError, SimulationError, translated
from ..runtime.evaluator import Evaluator
from ..runtime.events import values_from
from ..runtime.selection import select
from ..runtime.selection import singular_elements, worst_level
from ..compiler.structure import column
from ..language.symbols import time

SINGULAR_GZ = 1e-12
"""Smallest singular value of G_z (columns scaled by the nominal values,
rows to unit length), relative to the largest, below which the state
selection is singular at the point."""


@dataclass
class OperatingPoint:
    """Consistent node values ``z`` with relation values ``d`` at time
    ``t`` for the parameter vector ``p`` (see :func:`point_at`)."""
    t: float
    z: np.ndarray
    d: np.ndarray
    p: np.ndarray
    kind: str = "time"


@dataclass
class Linearization:
    """The linear model dx = A x + B u, y = C x + D u at ``point``:
    ``states`` names the selected states (the rows and columns of A),
    ``inputs`` the parameters taken as inputs, ``outputs`` the signals;
    ``dzdx`` (nodes x states) and ``dzdu`` the sensitivities of every node
    value; ``units`` {name: unit} of states, inputs and outputs."""
    A: np.ndarray
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    states: list
    inputs: list
    outputs: list
    units: dict
    point: OperatingPoint
    dzdx: np.ndarray
    dzdu: np.ndarray
    compiled: object = field(repr=False, default=None)

    def to_dict(self):
        """The JSON form ``{"A": ..., "states": ..., "point": ...}`` of
        ``linear.json``."""
        sys = self.compiled.system
        values = {name: float(v) for name, v in zip(sys.node_names, self.point.z)}
        return {"A": self.A.tolist(), "B": self.B.tolist(), "C": self.C.tolist(),
                "D": self.D.tolist(), "states": list(self.states), "inputs": list(self.inputs),
                "outputs": list(self.outputs), "units": dict(self.units),
                "point": {"time": float(self.point.t), "kind": self.point.kind,
                          "values": values}}

    def sensitivity(self, name):
        """d(name)/dx (a row over the states) of any node, eliminated alias
        or alias derivative of the model."""
        return signal_rows(self.compiled.system, [name], self.dzdx)[0]


# ------------------------------------------------------------ the point
def point_at(compiled, t=None, params=None, rtol=None):
    """The operating point of a run at time ``t`` (the start point for
    None or 0): simulated from the model's start values to t (``rtol``:
    the run's tolerance, default the model's); the right limit at an
    event."""
    p = compiled.parameter_values(params)
    if t is None or t == 0.0:
        try:
            ip = compiled.initial_point(0.0, params)
        except SimulationError as exc:        # the selection made there failed
            raise SimulationError("cannot linearise %s at its start point: %s" % (
                type(compiled.model).__name__, exc), time=0.0) from None
        return OperatingPoint(0.0, np.array(ip.z, dtype=float), np.array(ip.d, dtype=float), p)
    if not (isinstance(t, (int, float)) and np.isfinite(t) and t > 0):
        raise Acausal2dError("the time of the operating point (--at) must be a positive "
                             "number of seconds, got %r" % (t,))
    res = compiled.simulate(output_times=np.linspace(0.0, float(t), 3), params=params,
                            rtol=rtol, progress=False)
    if res.stopped:
        raise SimulationError("the run stopped before t=%g: %s" % (t, res.stopped), time=t)
    s = compiled.system
    z = np.array([res[name][-1] for name in s.node_names], dtype=float)
    return OperatingPoint(float(t), z, relation_values(compiled, float(t), z, p), p)


def relation_values(compiled, t, z, p):
    """Relation values (0/1) that the crossing functions give at z."""
    s = compiled.system
    d = np.zeros(len(s.relations))
    if not len(d):
        return d
    ev = Evaluator(s, p)
    for _ in range(3):          # relations whose crossing uses d settle in a few passes
        d = values_from(s, ev.crossings(t, z, d))
    return d


# ------------------------------------------------------------ the runtime adapter
def index1_states(compiled, ev, point):
    """(selection, state nodes, their derivative nodes) of the dummy
    selection the runtime makes at ``point`` - the one place that reads
    the runtime's selection and formulation."""
    try:
        with translated("selecting the states at t=%g" % point.t):
            selection = select(compiled.system, ev, point.t, point.z, point.d)
    except SimulationError as exc:
        raise SimulationError("cannot linearise %s at t=%g: the state selection is singular "
                              "there; linearise at another point.\n%s"
                              % (type(compiled.model).__name__, point.t, exc),
                              time=point.t) from None
    form = compiled.system.formulation(selection)
    return selection, np.array(form.states, dtype=int), np.array(form.state_deriv, dtype=int)


def singular_reason(compiled, ev, selection, point):
    """Text naming the components of the worst-conditioned dummy block at
    the point (why the state selection is singular there)."""
    worst = worst_level(compiled.system, ev, selection, point.t, point.z, point.d)
    if worst is None:
        return "the equations are singular in the algebraic unknowns"
    cond, lv, u = worst
    return ("the dummy block of %s is singular (relative condition %.2g): a singular "
            "position of the mechanism" % (", ".join(singular_elements(compiled.system,
                                                                      lv.eqs, u)), cond))


# ------------------------------------------------------------ sensitivities
def state_sensitivities(compiled, point):
    """(state nodes, derivative nodes, dz/dx, G_z) at ``point``; refuses a
    model without states (kinematically driven) and a point where the state
    selection is singular, naming the reason."""
    s = compiled.system
    ev = Evaluator(s, point.p)
    name = type(compiled.model).__name__
    if s.structure.n_var == s.structure.n_eq:
        raise Acausal2dError("%s is kinematically driven: it has no states (every position "
                             "follows from the drives), so it has no linear dynamics and no "
                             "modes" % name)
    selection, states, deriv = index1_states(compiled, ev, point)
    Ez = ev.jacobian(point.t, point.z, point.d, dense=True)
    S = np.zeros((len(states), s.structure.n_var))
    S[np.arange(len(states)), states] = 1.0
    Gz = np.vstack([Ez, S])
    _check_regular(compiled, ev, selection, point, Gz)
    rhs = np.vstack([np.zeros((Ez.shape[0], len(states))), np.eye(len(states))])
    return states, deriv, np.linalg.solve(Gz, rhs), Gz


def _check_regular(compiled, ev, selection, point, Gz):
    """Refuse a non-finite or singular G_z with the reason."""
    if not np.all(np.isfinite(Gz)):
        raise SimulationError("the derivatives of the equations are not finite at t=%g "
                              "(inf or NaN): no linearisation there" % point.t, time=point.t)
    scaled = Gz * compiled.system.nominal[None, :]
    scaled /= np.maximum(np.linalg.norm(scaled, axis=1), 1e-300)[:, None]
    sv = np.linalg.svd(scaled, compute_uv=False)
    if sv[-1] <= SINGULAR_GZ * sv[0]:
        raise SimulationError("the state selection is singular at t=%g: %s; linearise at "
                              "another point" % (point.t, singular_reason(compiled, ev,
                                                                          selection, point)),
                              time=point.t)


def _param_jacobian(compiled):
    """CasADi function dE/dp(t, z, p, d), made once per compiled model."""
    fn = getattr(compiled, "_dEdp", None)
    if fn is None:
        s = compiled.system
        z = column(s.structure.var_sym)
        E = column(s.structure.eq_expr)
        fn = ca.Function("dEdp", [time, z, s.p, s.d], [ca.jacobian(E, s.p)])
        offsets = ca.SX.sym("p", s.p.numel())
        off = s.alias_offset_fn(offsets)
        compiled._dOdp = ca.Function("dOdp", [offsets], [ca.jacobian(off, offsets)])
        compiled._dEdp = fn
    return fn


def input_sensitivities(compiled, point, Gz, inputs):
    """dz/du (nodes x inputs) for the parameters ``inputs``."""
    s = compiled.system
    if not inputs:
        return np.zeros((s.structure.n_var, 0))
    idx = [_input_index(compiled, name) for name in inputs]
    Ep = np.array(_param_jacobian(compiled)(point.t, point.z, point.p, point.d))[:, idx]
    rhs = np.vstack([Ep, np.zeros((Gz.shape[0] - Ep.shape[0], len(idx)))])
    return -np.linalg.solve(Gz, rhs)


def _input_index(compiled, name):
    s = compiled.system
    name = getattr(compiled.model, "input_parameters", {}).get(name, name)
    if name in s.param_index:
        return s.param_index[name]
    raise Acausal2dError("unknown input %r: an input is a scalar parameter, e.g. the value "
                         "'k' of a Constant source feeding a RealInput (%s)" % (
                             name, ", ".join(n for n, *_ in s.parameters[:12])))


def signal_rows(system, names, dz, dp=None):
    """Rows d(name)/d(.) for nodes, eliminated aliases and alias
    derivatives, from the node sensitivities ``dz`` (and, for aliases fixed
    by parameters, ``dp``: their offsets' parameter derivatives)."""
    nodes = {n: j for j, n in enumerate(system.node_names)}
    aliases = {n: k for k, n in enumerate(system.alias_names)}
    ders = {n: k for k, n in enumerate(system.alias_der_names)}
    rows = []
    for name in names:
        if name in nodes:
            rows.append(dz[nodes[name]])
        elif name in aliases:
            k = aliases[name]
            j = system.alias_node[k]
            row = dz[j] * system.alias_sign[k] if j >= 0 else np.zeros(dz.shape[1])
            rows.append(row + (dp[k] if dp is not None else 0.0))
        elif name in ders:
            k = ders[name]
            rows.append(dz[system.alias_der_node[k]] * system.alias_der_sign[k])
        else:
            raise Acausal2dError("unknown output %r: outputs are signals of the model, e.g. %s"
                                 % (name, ", ".join(system.node_names[:8])))
    return np.array(rows, dtype=float).reshape(len(names), dz.shape[1])


def linearize_point(compiled, point, inputs=(), outputs=None):
    """The :class:`Linearization` at an :class:`OperatingPoint`."""
    s = compiled.system
    inputs = list(inputs or [])
    outputs = list(compiled.outputs if outputs is None else outputs)
    states, deriv, dzdx, Gz = state_sensitivities(compiled, point)
    dzdu = input_sensitivities(compiled, point, Gz, inputs)
    dp = None
    if inputs:
        dp = np.array(compiled._dOdp(point.p))[:, [_input_index(compiled, n) for n in inputs]]
    names = [s.node_names[j] for j in states]
    units = compiled.units
    return Linearization(
        A=dzdx[deriv], B=dzdu[deriv], C=signal_rows(s, outputs, dzdx),
        D=signal_rows(s, outputs, dzdu, dp), states=names, inputs=inputs, outputs=outputs,
        units={n: units.get(n, "") for n in names + inputs + outputs}, point=point,
        dzdx=dzdx, dzdu=dzdu, compiled=compiled)
