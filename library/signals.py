"""Signal blocks (Modelica.Blocks conventions): sources with a RealOutput
``y``, the first-order filter :class:`FirstOrder` and
:class:`InverseBlockConstraints`, which lets a prescribed output drive a
model backwards (an inverse model).

Signals carry no physics of the dissertation; they feed its drives and sources
(Ebert 2015, ch. 4.2 motion presets, ch. 8 showcase drives)."""
import casadi as ca

from acausal2d import Component, der, Parameter, RealInput, RealOutput, time, Variable
from acausal2d.errors import ModelDefinitionError


class _Source(Component):
    def __init__(self, **kw):
        super().__init__(**kw)
        self.y = RealOutput()


class Constant(_Source):
    """y = k."""
    k = Parameter(0.0, "", "output value")

    def equations(self):
        return [self.y.u == self.k]


def _former_start_time(kw):
    """``start_time``, the former name of Modelica's ``startTime``, still
    accepted as a keyword (one name in the model: ``startTime``)."""
    if "start_time" in kw:
        if "startTime" in kw:
            raise ModelDefinitionError("give startTime only (start_time is its former name)")
        kw["startTime"] = kw.pop("start_time")
    return kw


class Sine(_Source):
    """Sine wave (Modelica Standard Library 4.0, Modelica.Blocks.Sources.Sine)::

        y = offset + (if time < startTime then 0
                      else amplitude * sin(2 pi f (time - startTime) + phase))

    The switch at ``startTime`` is a time event.  ``start_time`` is accepted
    as the former name of ``startTime``."""
    amplitude = Parameter(1.0, "", "amplitude")
    f = Parameter(1.0, "Hz", "frequency", min=0.0)
    phase = Parameter(0.0, "rad", "phase")
    offset = Parameter(0.0, "", "offset")
    startTime = Parameter(0.0, "s", "output = offset before this time")

    def __init__(self, **kw):
        super().__init__(**_former_start_time(kw))

    def equations(self):
        wave = self.amplitude * ca.sin(2 * ca.pi * self.f * (time - self.startTime) + self.phase)
        return [self.y.u == self.offset + ca.if_else(time < self.startTime, 0, wave)]


class Ramp(_Source):
    """Linear ramp (Modelica Standard Library 4.0, Modelica.Blocks.Sources.Ramp)::

        y = offset + (if time < startTime then 0
                      else if time < startTime + duration
                      then (time - startTime) * height / duration
                      else height)

    Both kinks are time events.  ``duration`` must be > 0 here (Modelica's 0
    is a step: use :class:`~acausal2d.library.blocks.Step`).  ``start_time``
    is accepted as the former name of ``startTime``."""
    height = Parameter(1.0, "", "height of the ramp")
    duration = Parameter(1.0, "s", "duration of the ramp", positive=True)
    offset = Parameter(0.0, "", "offset of the output")
    startTime = Parameter(0.0, "s", "output = offset for time < startTime")

    def __init__(self, **kw):
        super().__init__(**_former_start_time(kw))

    def equations(self):
        tau = (time - self.startTime) / self.duration
        ramp = ca.if_else(time < self.startTime, 0,
                          ca.if_else(time < self.startTime + self.duration, tau, 1))
        return [self.y.u == self.offset + self.height * ramp]


class KinematicPTP(_Source):
    """Point-to-point motion as fast as the kinematic limits allow: the
    path's acceleration (Modelica Standard Library 4.0,
    Modelica.Blocks.Sources.KinematicPTP, one axis: ``nout = 1``)::

        aux1 = deltaq / qd_max,  aux2 = deltaq / qdd_max
        sd_max = 1 / abs(aux1),  sdd_max = 1 / abs(aux2)
        Ta1 = sqrt(1 / sdd_max),  Ta2 = sd_max / sdd_max
        noWphase = Ta2 >= Ta1
        Tv = if noWphase then Ta1 else 1 / sd_max
        Te = if noWphase then Ta1 + Ta1 else Tv + Ta2
        sdd = if time < startTime then 0 else
              (if noWphase then
                 (if time < Ta1 + startTime then sdd_max
                  else if time < Te + startTime then -sdd_max else 0)
               else
                 (if time < Ta2 + startTime then sdd_max
                  else if time < Tv + startTime then 0
                  else if time < Te + startTime then -sdd_max else 0))
        y = deltaq * sdd

    ``y`` is the acceleration ``der(qd)`` of a motion that moves by
    ``deltaq`` from rest to rest in ``Te``: accelerating at ``qdd_max`` to
    ``qd_max`` (or, with no phase of constant speed, to the speed reached
    half way), then decelerating.  Integrate it twice (two
    :class:`~acausal2d.library.blocks.Integrator`, or a torque ``J y`` on an
    inertia) for the speed and the position.  Every switch is a time
    event.  The parameters are scalars (Modelica's vectors synchronise
    several axes to the slowest; here one axis per block)."""
    deltaq = Parameter(1.0, "", "distance to move", nonzero=True)
    qd_max = Parameter(1.0, "", "maximum velocity der(q)", positive=True)
    qdd_max = Parameter(1.0, "", "maximum acceleration der(qd)", positive=True)
    startTime = Parameter(0.0, "s", "time instant at which the movement starts")

    def equations(self):
        aux1, aux2 = self.deltaq / self.qd_max, self.deltaq / self.qdd_max
        sd_max, sdd_max = 1 / ca.fabs(aux1), 1 / ca.fabs(aux2)
        ta1, ta2 = ca.sqrt(1 / sdd_max), sd_max / sdd_max
        no_w = ta2 >= ta1
        tv = ca.if_else(no_w, ta1, 1 / sd_max)
        te = ca.if_else(no_w, ta1 + ta1, tv + ta2)
        t0 = self.startTime
        triangle = ca.if_else(time < ta1 + t0, sdd_max,
                              ca.if_else(time < te + t0, -sdd_max, 0.0))
        trapezoid = ca.if_else(time < ta2 + t0, sdd_max,
                               ca.if_else(time < tv + t0, 0.0,
                                          ca.if_else(time < te + t0, -sdd_max, 0.0)))
        sdd = ca.if_else(time < self.startTime, 0.0, ca.if_else(no_w, triangle, trapezoid))
        return [self.y.u == self.deltaq * sdd]


class TimeFunction(_Source):
    """y = func(time) for a Python function building a CasADi expression of
    the time symbol (e.g. ``lambda t: 1.5 * t``).  Changing the function
    needs a recompilation; its numbers can be parameters of other components."""

    def __init__(self, func, **kw):
        super().__init__(**kw)
        self.func = func

    def equations(self):
        return [self.y.u == self.func(time)]


_INIT_TYPES = ("steady_state", "initial_output", "free")


class FirstOrder(Component):
    """First-order transfer function (Modelica.Blocks.Continuous.FirstOrder)
    ``T der(y) + y = k u`` from the input ``u`` to the output ``y``.

    ``init`` chooses the start: ``"steady_state"`` (Modelica's
    initType SteadyState: ``der(y) = 0`` at the start, so ``y = k u`` there),
    ``"initial_output"`` (``y`` starts at ``y_start``) or ``"free"`` (the
    start value of ``y`` is only a guess).  The steady state is held as
    the fixed start value 0 of the variable ``dy = der(y)``.

    Variables: ``y_value`` (the output, also on the connector ``y``) and
    ``dy``."""
    k = Parameter(1.0, "", "gain")
    T = Parameter(1.0, "s", "time constant", positive=True)
    y_start = Parameter(0.0, "", "start value of y (init='initial_output')")
    y_value = Variable(unit="", doc="output value")
    dy = Variable(unit="1/s", doc="der(y)")

    def __init__(self, init="steady_state", **kw):
        super().__init__(**kw)
        if init not in _INIT_TYPES:
            raise ModelDefinitionError("%s: init must be one of %s, not %r"
                                       % (type(self).__name__, ", ".join(_INIT_TYPES), init))
        self.init = init
        if init == "steady_state":
            self.variable("dy").start, self.variable("dy").fixed = 0.0, True
        elif init == "initial_output":
            self.variable("y_value").fixed = True
        self.u = RealInput()
        self.y = RealOutput()

    def guesses(self, context):
        """y starts at y_start when init='initial_output'."""
        return {"y_value": self.y_start} if self.init == "initial_output" else {}

    def equations(self):
        return [self.dy == der(self.y_value), self.y.u == self.y_value,
                self.T * self.dy + self.y_value == self.k * self.u.u]


class InverseBlockConstraints(Component):
    """Modelica.Blocks.Math.InverseBlockConstraints: the two inputs are
    made equal (``u1 = u2``) and the output ``y1`` (and its copy ``y2``)
    is left as an unknown of the model.

    Connect a prescribed signal to ``u2``, the measured output of a model
    to ``u1`` and ``y1`` to the model's input: the model then runs
    backwards, its input is solved for so that its output follows the
    prescription.  The prescription is differentiated as often as the
    model needs (index reduction), so it must be smooth enough: a motion
    prescribed through a mechanism of relative degree 2 needs a
    prescription whose second derivative exists (e.g. a ramp filtered by a
    :class:`FirstOrder`)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.u1 = RealInput()
        self.u2 = RealInput()
        self.y1 = RealOutput()
        self.y2 = RealOutput()

    def equations(self):
        return [self.u1.u == self.u2.u, self.y2.u == self.y1.u]


# Modelica.Blocks' sources, math blocks and controllers, where Modelica users look for them
from acausal2d.library.blocks import (Add, Add3, Derivative, Feedback, Gain,  # noqa: E402,F401
                                      Integrator, Limiter, Pulse, Step)
from acausal2d.library.controllers import LimPID, PID  # noqa: E402,F401
