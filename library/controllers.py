"""Controllers of Modelica.Blocks.Continuous (Modelica Standard Library 4.0): :class:`PID` and
:class:`LimPID`, written flat with Modelica's parameters and equations.

Modelica composes both of sub-blocks (``I``: Integrator, ``D``:
Derivative, ``gainPID``, ``addFF``, ``limiter``, ...); here the states and
signals of those sub-blocks are variables of the controller, and
``modelica_names`` maps Modelica's result names to them (``pid.I.y`` ->
``pid.I_y``, ``pid.D.x`` -> ``pid.D_x``), so ``compare`` against a Modelica
result finds them.  Both are re-exported by
:mod:`acausal2d.library.signals`."""
import casadi as ca

from acausal2d import Component, der, Parameter, RealInput, RealOutput, Variable
from acausal2d.errors import ModelDefinitionError
from acausal2d.library.blocks import (_check_limits, _choice, _limit, CONTROLLER_TYPES,
                                      INIT_TYPES)

EPS_PID = 100 * 2.220446049250313e-16   # PID's floor max([Td/Nd, 100*eps]) of the D block's T
EPS_LIMPID = 1e-14                     # LimPID's floor max([Td/Nd, 1.e-14])


def _sub_init(init_type):
    """initType of the sub-blocks (I, D) for the controller's initType, as
    in Modelica's PID and LimPID: SteadyState -> both steady;
    InitialState -> both at their start states; InitialOutput -> I free
    (the output equation fixes it), D steady; NoInit -> both free."""
    i_init = init_type if init_type in ("SteadyState", "InitialState") else "NoInit"
    d_init = {"SteadyState": "SteadyState", "InitialOutput": "SteadyState",
              "InitialState": "InitialState"}.get(init_type, "NoInit")
    return i_init, d_init


class _Controller(Component):
    """The parts PID and LimPID share: the integrator state ``I_y``, the
    derivative's state ``D_x`` and output ``D_y``, and their start."""
    I_y = Variable(doc="integrator output (Modelica I.y)")
    D_x = Variable(doc="state of the derivative block (Modelica D.x)")
    D_y = Variable(doc="output of the derivative block (Modelica D.y)")
    y_value = Variable(doc="controller output")

    def _setup_init(self, init_type, with_i=True, with_d=True):
        self.initType = _choice(self, "initType", init_type, INIT_TYPES)
        self.with_I, self.with_D = with_i, with_d
        i_init, d_init = _sub_init(self.initType)
        for state, init, used in (("I_y", i_init, with_i), ("D_x", d_init, with_d)):
            if used and init == "InitialState":
                self.variable(state).fixed = True
            elif used and init == "SteadyState":
                self.add_variable("der_" + state, start=0.0, fixed=True,
                                  doc="der(%s), 0 at the start" % state)
        self._output_var = None

    def _fix_output(self, name):
        """initType InitialOutput: ``name`` (Modelica's y or gainPID.y)
        starts at y_start."""
        if self.initType == "InitialOutput":
            self.variable(name).fixed = True
            self._output_var = name

    def guesses(self, context):
        """The states start at (or near) xi_start, xd_start; the output
        named by initType InitialOutput at y_start."""
        out = {"I_y": self.xi_start, "D_x": self.xd_start}
        if self._output_var:
            out[self._output_var] = self.y_start
        return out

    def _dynamics(self, e_i, e_d):
        """der(I.y) = e_i / Ti; the derivative block on e_d with k = Td and
        T = max(Td/Nd, floor) (Modelica's D); with Td = 0 (Modelica's
        zeroGain) der(D.x) = 0 and D.y = 0: ``Td / (Td + 1e-300)`` is
        exactly 1 for every normal Td > 0 and 0 for Td = 0."""
        eqs = [der(self.I_y) == e_i / self.Ti] if self.with_I else [self.I_y == 0]
        if self.with_D:
            t_d = ca.fmax(self.Td / self.Nd, self.T_FLOOR)
            gain = self.Td / (self.Td + 1e-300)
            eqs += [der(self.D_x) == gain * (e_d - self.D_x) / t_d,
                    self.D_y == self.Td / t_d * (e_d - self.D_x)]
        else:
            eqs += [self.D_x == 0, self.D_y == 0]
        for state in ("I_y", "D_x"):
            if "der_" + state in self._var_decls:
                eqs.append(getattr(self, "der_" + state) == der(getattr(self, state)))
        return eqs


class PID(_Controller):
    """PID controller in additive description form
    (Modelica.Blocks.Continuous.PID)::

        y = k * (u + I.y + D.y)
        der(I.y) = u / Ti
        der(D.x) = (u - D.x) / T_d,   D.y = Td / T_d * (u - D.x),
        T_d = max(Td / Nd, 1e-14)

    i.e. ``y = k (1 + 1/(Ti s) + Td s/((Td/Nd) s + 1)) u``.  ``initType``
    (default ``"InitialState"``: ``I.y = xi_start``, ``D.x = xd_start``),
    ``"SteadyState"`` (``der(I.y) = der(D.x) = 0``), ``"InitialOutput"``
    (``y = y_start``, D steady) or ``"NoInit"``.  ``Td = 0`` removes the
    derivative part (Modelica's zero-gain Derivative).  Connectors ``u``,
    ``y``."""
    T_FLOOR = EPS_PID
    k = Parameter(1.0, "1", "gain")
    Ti = Parameter(0.5, "s", "time constant of the integrator", positive=True)
    Td = Parameter(0.1, "s", "time constant of the derivative block", min=0.0)
    Nd = Parameter(10.0, "1", "the higher Nd, the more ideal the derivative block",
                   positive=True)
    xi_start = Parameter(0.0, "", "start value of the integrator state")
    xd_start = Parameter(0.0, "", "start value of the derivative block's state")
    y_start = Parameter(0.0, "", "start value of the output (initType='InitialOutput')")
    modelica_names = {"I.y": "I_y", "D.x": "D_x", "D.y": "D_y"}

    def __init__(self, initType="InitialState", **kw):
        super().__init__(**kw)
        self.u = RealInput()
        self.y = RealOutput()
        self._setup_init(initType)
        self._fix_output("y_value")

    def equations(self):
        return self._dynamics(self.u.u, self.u.u) + [
            self.y.u == self.y_value,
            self.y_value == self.k * (self.u.u + self.I_y + self.D_y)]


class LimPID(_Controller):
    """P, PI, PD or PID controller with limited output, anti-windup
    compensation, set-point weighting and optional feed-forward
    (Modelica Standard Library 4.0, Modelica.Blocks.Continuous.LimPID)::

        controlError = u_s - u_m
        P.y = wp * u_s - u_m
        der(D.x) = (wd * u_s - u_m - D.x) / T_d,  D.y = Td / T_d * (wd * u_s - u_m - D.x)
        gainPID.y = k * (P.y + D.y + I.y)
        addFF.y = gainPID.y + kFF * u_ff
        y = if addFF.y > yMax then yMax else if addFF.y < yMin then yMin else addFF.y
        der(I.y) = (u_s - u_m + (y - addFF.y) / (k * Ni)) / Ti

    with ``T_d = max(Td / Nd, 1e-14)``; the last term is the anti-windup
    (tracking) feedback of gain ``1/(k Ni)``: while the output is limited the
    integrator is pulled back with the time constant ``Ni Ti``.
    ``controllerType`` ``"P"``, ``"PI"``, ``"PD"`` or ``"PID"`` (default)
    drops the integrator (``I.y = 0``) and/or the derivative (``D.y = 0``).
    ``yMin`` defaults to ``-yMax``.  ``withFeedForward=True`` adds the input
    ``u_ff``.  ``initType`` as for :class:`PID`, but Modelica's default here
    is ``"NoInit"`` (the start values ``xi_start``, ``xd_start`` then hold
    unless the model's initial equations decide otherwise);
    ``"InitialOutput"`` holds ``gainPID.y = y_start`` (within the limits).
    Connectors ``u_s`` (set point), ``u_m`` (measurement), ``y``."""
    T_FLOOR = EPS_LIMPID
    k = Parameter(1.0, "1", "gain of the controller", positive=True)
    Ti = Parameter(0.5, "s", "time constant of the integrator", positive=True)
    Td = Parameter(0.1, "s", "time constant of the derivative block", min=0.0)
    yMax = Parameter(1.0, "", "upper limit of the output")
    yMin = Parameter(-1.0, "", "lower limit of the output (default -yMax)")
    wp = Parameter(1.0, "1", "set-point weight of the proportional block (0..1)", min=0.0)
    wd = Parameter(0.0, "1", "set-point weight of the derivative block (0..1)", min=0.0)
    Ni = Parameter(0.9, "1", "Ni*Ti is the time constant of the anti-windup compensation",
                   min=2.3e-14)
    Nd = Parameter(10.0, "1", "the higher Nd, the more ideal the derivative block",
                   min=2.3e-14)
    kFF = Parameter(1.0, "1", "gain of the feed-forward input")
    xi_start = Parameter(0.0, "", "start value of the integrator state")
    xd_start = Parameter(0.0, "", "start value of the derivative block's state")
    y_start = Parameter(0.0, "", "start value of gainPID.y (initType='InitialOutput')")
    controlError = Variable(doc="control error u_s - u_m")
    gainPID_y = Variable(doc="unlimited PID output k (P + I + D) (Modelica gainPID.y)")
    addFF_y = Variable(doc="unlimited output with feed-forward (Modelica addFF.y)")
    modelica_names = {"I.y": "I_y", "D.x": "D_x", "D.y": "D_y", "gainPID.y": "gainPID_y",
                      "addFF.y": "addFF_y"}

    def __init__(self, controllerType="PID", initType="NoInit", withFeedForward=False, **kw):
        if "yMax" in kw and "yMin" not in kw and isinstance(kw["yMax"], (int, float)):
            kw["yMin"] = -kw["yMax"]
        super().__init__(**kw)
        self.controllerType = _choice(self, "controllerType", controllerType,
                                      CONTROLLER_TYPES)
        self._setup_init(initType, "I" in self.controllerType, "D" in self.controllerType)
        self.check_parameters(self.parameter_value)
        self._fix_output("gainPID_y")
        self.withFeedForward = bool(withFeedForward)
        self.u_s = RealInput(doc="set point")
        self.u_m = RealInput(doc="measurement")
        self.y = RealOutput()
        if self.withFeedForward:
            self.u_ff = RealInput(doc="feed-forward input")

    def check_parameters(self, value):
        """``yMax >= yMin``, and Modelica's error for initType InitialOutput
        with y_start outside [yMin, yMax] (on the values ``value(name)``
        gives)."""
        _check_limits(self, "yMax", "yMin", value)
        y0, lo, hi = (value(n) for n in ("y_start", "yMin", "yMax"))
        if self.initType == "InitialOutput" and not lo <= y0 <= hi:
            raise ModelDefinitionError("%s: parameter y_start = %g is outside the limits yMin = "
                                       "%g, yMax = %g; give a y_start between them"
                                       % (self.describe(), y0, lo, hi))

    def equations(self):
        u_s, u_m = self.u_s.u, self.u_m.u
        ff = self.kFF * self.u_ff.u if self.withFeedForward else 0
        track = (self.y_value - self.addFF_y) / (self.k * self.Ni)
        return self._dynamics(u_s - u_m + track, self.wd * u_s - u_m) + [
            self.controlError == u_s - u_m,
            self.gainPID_y == self.k * (self.wp * u_s - u_m + self.D_y + self.I_y),
            self.addFF_y == self.gainPID_y + ff,
            self.y_value == _limit(self.addFF_y, self.yMin, self.yMax),
            self.y.u == self.y_value]
