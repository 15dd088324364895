"""Signal blocks of Modelica.Blocks (Modelica Standard Library 4.0) with Modelica's names,
parameters and equations: Sources.Step, Sources.Pulse, Math.Gain, Math.Add, Math.Add3,
Math.Feedback, Nonlinear.Limiter, Continuous.Integrator,
Continuous.Derivative, Continuous.PID and Continuous.LimPID.

All are re-exported by :mod:`acausal2d.library.signals`
(``signals.PID``), where a Modelica user looks for them.  Inputs are
``RealInput`` connectors (``u``, ``u1``, ``u2``, ``u_s``, ``u_m``), outputs
``RealOutput`` connectors (``y``); a connector's value is its ``u``
(``gain.y.u``).  The start of a dynamic block is chosen by ``initType``,
Modelica.Blocks.Types.Init's names as strings: ``"NoInit"``,
``"SteadyState"``, ``"InitialState"``, ``"InitialOutput"`` (a prefix such
as ``"Modelica.Blocks.Types.Init."`` is allowed)."""
import casadi as ca

from acausal2d import Component, der, Parameter, RealInput, RealOutput, time, Variable
from acausal2d.errors import ModelDefinitionError

INIT_TYPES = ("NoInit", "SteadyState", "InitialState", "InitialOutput")
CONTROLLER_TYPES = ("P", "PI", "PD", "PID")


def _choice(comp, name, value, allowed):
    """``value`` (a string, optionally with a dotted Modelica prefix) as one
    of ``allowed``; a clear error naming the block and argument otherwise."""
    short = value.rsplit(".", 1)[-1] if isinstance(value, str) else None
    if short not in allowed:
        raise ModelDefinitionError("%s: %s must be one of %s, not %r" % (
            type(comp).__name__, name, ", ".join(repr(a) for a in allowed), value))
    return short


class _SISO(Component):
    # Modelica's result names of the connectors' signals (``gain.y``) ->
    # ours (``gain.y.u``), for compare; collected from every class
    modelica_names = {name: name + ".u" for name in ("y", "u", "u1", "u2", "u3", "u_s",
                                                     "u_m", "u_ff", "f_normalized")}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.u = RealInput()
        self.y = RealOutput()


class Step(Component):
    """Step signal (Modelica.Blocks.Sources.Step)::

        y = offset + (if time < startTime then 0 else height)

    The step at ``startTime`` is a time event."""
    height = Parameter(1.0, "", "height of the step")
    offset = Parameter(0.0, "", "offset of the output")
    startTime = Parameter(0.0, "s", "output = offset for time < startTime")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.y = RealOutput()

    def equations(self):
        return [self.y.u == self.offset + ca.if_else(time < self.startTime, 0, self.height)]


class Pulse(Component):
    """Pulse signal (Modelica.Blocks.Sources.Pulse)::

        y = offset + (amplitude during [T_start, T_start + width/100 * period)
                      of every period from startTime on, else 0)

    for ``nperiod`` periods (-1: for ever).  Each edge is a time event; the
    crossing function ``sin(pi tau) sin(pi (tau - width/100))``, ``tau = (time
    - startTime) / period``, is negative exactly while the pulse is on and
    crosses zero at the edges.  ``0 < width < 100`` (a width of 100 is a
    :class:`Step`)."""
    amplitude = Parameter(1.0, "", "amplitude of the pulse")
    width = Parameter(50.0, "1", "width of the pulse in % of the period", positive=True,
                      max=100.0)
    period = Parameter(1.0, "s", "time for one period", positive=True)
    offset = Parameter(0.0, "", "offset of the output")
    startTime = Parameter(0.0, "s", "output = offset for time < startTime")

    def __init__(self, nperiod=-1, **kw):
        super().__init__(**kw)
        if not self.parameter_value("width") < 100.0:
            raise ModelDefinitionError("%s: parameter width = 100 %% is a step; give width < 100 "
                                       "or use Step" % self.describe())
        if not (isinstance(nperiod, int) and (nperiod == -1 or nperiod > 0)):
            raise ModelDefinitionError("%s: nperiod must be -1 (for ever) or a whole number > 0, "
                                       "not %r" % (self.describe(), nperiod))
        self.nperiod = nperiod
        self.y = RealOutput()

    def equations(self):
        tau = (time - self.startTime) / self.period
        on = ca.sin(ca.pi * tau) * ca.sin(ca.pi * (tau - self.width / 100.0)) < 0
        end = self.startTime + self.nperiod * self.period
        active = time >= self.startTime if self.nperiod < 0 else \
            ca.logic_and(time >= self.startTime, time < end)
        return [self.y.u == self.offset + ca.if_else(active, ca.if_else(on, self.amplitude, 0), 0)]


class Gain(_SISO):
    """Output the product of a gain and the input
    (Modelica.Blocks.Math.Gain): ``y = k * u``."""
    k = Parameter(1.0, "1", "gain")

    def equations(self):
        return [self.y.u == self.k * self.u.u]


class Add(Component):
    """Weighted sum of two inputs (Modelica.Blocks.Math.Add):
    ``y = k1 * u1 + k2 * u2``."""
    k1 = Parameter(1.0, "1", "gain of input u1")
    k2 = Parameter(1.0, "1", "gain of input u2")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.u1 = RealInput()
        self.u2 = RealInput()
        self.y = RealOutput()

    def equations(self):
        return [self.y.u == self.k1 * self.u1.u + self.k2 * self.u2.u]


class Add3(Component):
    """Weighted sum of three inputs (Modelica.Blocks.Math.Add3):
    ``y = k1 * u1 + k2 * u2 + k3 * u3``."""
    k1 = Parameter(1.0, "1", "gain of input u1")
    k2 = Parameter(1.0, "1", "gain of input u2")
    k3 = Parameter(1.0, "1", "gain of input u3")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.u1 = RealInput()
        self.u2 = RealInput()
        self.u3 = RealInput()
        self.y = RealOutput()

    def equations(self):
        return [self.y.u == self.k1 * self.u1.u + self.k2 * self.u2.u + self.k3 * self.u3.u]


class Product(Component):
    """Product of two inputs (Modelica Standard Library 4.0,
    Modelica.Blocks.Math.Product)::

        y = u1 * u2

    It has no parameters."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.u1 = RealInput()
        self.u2 = RealInput()
        self.y = RealOutput()

    def equations(self):
        return [self.y.u == self.u1.u * self.u2.u]


class Feedback(Component):
    """Difference of the commanded and the feedback signal
    (Modelica.Blocks.Math.Feedback): ``y = u1 - u2`` (``u2`` is the
    feedback input, drawn below the block in Modelica)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.u1 = RealInput()
        self.u2 = RealInput()
        self.y = RealOutput()

    def equations(self):
        return [self.y.u == self.u1.u - self.u2.u]


def _limit(u, lo, hi):
    """Modelica.Blocks.Nonlinear.Limiter's law ``if u > uMax then uMax else
    if u < uMin then uMin else u``; both kinks are events."""
    return ca.if_else(u > hi, hi, ca.if_else(u < lo, lo, u))


class Limiter(_SISO):
    """Limit the range of a signal (Modelica.Blocks.Nonlinear.Limiter)::

        y = if u > uMax then uMax else if u < uMin then uMin else u

    Passing a limit is an event.  ``uMin`` defaults to ``-uMax`` as in
    Modelica; ``uMax < uMin`` is refused."""
    uMax = Parameter(1.0, "", "upper limit of the input signal")
    uMin = Parameter(-1.0, "", "lower limit of the input signal (default -uMax)")

    def __init__(self, **kw):
        if "uMax" in kw and "uMin" not in kw:
            kw["uMin"] = -kw["uMax"] if isinstance(kw["uMax"], (int, float)) else kw["uMax"]
        super().__init__(**kw)
        self.check_parameters(self.parameter_value)

    def check_parameters(self, value):
        """``uMax >= uMin`` (on the values ``value(name)`` gives)."""
        _check_limits(self, "uMax", "uMin", value)

    def equations(self):
        return [self.y.u == _limit(self.u.u, self.uMin, self.uMax)]


def _check_limits(comp, hi, lo, value):
    """``value(hi) >= value(lo)``, else an error naming both."""
    if value(hi) < value(lo):
        raise ModelDefinitionError("%s: parameter %s = %g is below %s = %g; give %s >= %s" % (
            comp.describe(), hi, value(hi), lo, value(lo), hi, lo))


class Integrator(_SISO):
    """Output the integral of the input (Modelica.Blocks.Continuous.
    Integrator, without reset): ``der(y) = k * u``.  ``initType``:
    ``"InitialState"`` (default) and ``"InitialOutput"`` start at
    ``y = y_start``, ``"SteadyState"`` at ``der(y) = 0``, ``"NoInit"``
    leaves ``y_start`` a guess.  The output value is the variable
    ``y_value`` (also on the connector ``y``)."""
    k = Parameter(1.0, "1", "integrator gain")
    y_start = Parameter(0.0, "", "initial or guess value of the output (= state)")
    y_value = Variable(doc="output (= state)")

    def __init__(self, initType="InitialState", **kw):
        super().__init__(**kw)
        self.initType = _choice(self, "initType", initType, INIT_TYPES)
        if self.initType in ("InitialState", "InitialOutput"):
            self.variable("y_value").fixed = True
        elif self.initType == "SteadyState":
            self.add_variable("dy", start=0.0, fixed=True, doc="der(y)")

    def guesses(self, context):
        """y starts at (or near) y_start."""
        return {"y_value": self.y_start}

    def equations(self):
        eqs = [self.y.u == self.y_value, der(self.y_value) == self.k * self.u.u]
        if self.initType == "SteadyState":
            eqs.append(self.dy == der(self.y_value))
        return eqs


def _steady(comp, state):
    """Declare ``der_<state>``, held at 0 at the start (Modelica's
    ``der(x) = 0`` of initType SteadyState); its equation is
    :func:`_steady_equation`."""
    comp.add_variable("der_" + state, start=0.0, fixed=True, doc="der(%s), 0 at the start" % state)


def _steady_equation(comp, state):
    name = "der_" + state
    return [getattr(comp, name) == der(getattr(comp, state))] if name in comp._var_decls else []


class Derivative(_SISO):
    """Approximated derivative block (Modelica.Blocks.Continuous.Derivative)
    with the state ``x``::

        der(x) = (u - x) / T
        y = (k / T) * (u - x)

    i.e. the transfer function ``k s / (T s + 1)``; for ``k = 0``
    (Modelica's zeroGain) ``der(x) = 0`` and ``y = 0`` (the factor ``k^2 /
    (k^2 + 1e-300)`` is exactly 1 for every normal k).  ``initType``:
    ``"NoInit"`` (default, ``x_start`` a guess), ``"SteadyState"``
    (``der(x) = 0``), ``"InitialState"`` (``x = x_start``),
    ``"InitialOutput"`` (``y = y_start``)."""
    k = Parameter(1.0, "1", "gain")
    T = Parameter(0.01, "s", "time constant (T > 0)", positive=True)
    x_start = Parameter(0.0, "", "start value of the state x")
    y_start = Parameter(0.0, "", "start value of the output (initType='InitialOutput')")
    x = Variable(doc="state of the block")
    y_value = Variable(doc="output")

    def __init__(self, initType="NoInit", **kw):
        super().__init__(**kw)
        self.initType = _choice(self, "initType", initType, INIT_TYPES)
        if self.initType == "InitialState":
            self.variable("x").fixed = True
        elif self.initType == "InitialOutput":
            self.variable("y_value").fixed = True
        elif self.initType == "SteadyState":
            _steady(self, "x")

    def guesses(self, context):
        """x starts at (or near) x_start, y at y_start."""
        return {"x": self.x_start, "y_value": self.y_start}

    def equations(self):
        gain = self.k * self.k / (self.k * self.k + 1e-300)
        return [der(self.x) == gain * (self.u.u - self.x) / self.T, self.y.u == self.y_value,
                self.y_value == self.k / self.T * (self.u.u - self.x)] + _steady_equation(self, "x")
