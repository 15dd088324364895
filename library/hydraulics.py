"""Hydrostatics (lumped fluid power) for the hydraulic drum drive of Ebert (2015),
ch. 8.1 (Bild 8.6: diesel, pump, two controlled hydraulic motors,
planetary stage, drums).  The dissertation names the elements only; the equations
are the textbook relations of positive-displacement machines, valves and
compliant lines (Murrenhoff, Grundlagen der Fluidtechnik, Teil 1:
Hydraulik, ch. "Verdraengereinheiten" and "Kompressibilitaet"; Will/Gebhardt,
Hydraulik), written in Modelica's conventions.

Connector :class:`~acausal2d.HydraulicPort`: pressure ``p`` [Pa] as the
potential, volume flow ``q`` [m3/s] as the flow, positive INTO the element;
the hydraulic power entering an element through a port is ``p q``.
Pressures may be absolute or relative to the tank: the power balance of a
closed circuit does not depend on the reference, because the flows of each
connection sum to zero.  The fluid is incompressible except in
:class:`Volume` (bulk modulus); no inertia of the oil in the lines.

Displacement ``Vg`` of pumps and motors is the geometric volume per
REVOLUTION [m3/rev] as in data sheets (cm3/rev times 1e-6); the equations use
``D = Vg / (2 pi)`` [m3/rad].

Elements: :class:`PressureSource` (tank or constant-pressure supply),
:class:`Pump`, :class:`Motor` (fixed or, with ``variable=True``,
variable displacement), :class:`ReliefValve`, :class:`Volume`,
:class:`Throttle` (laminar), :class:`Orifice` (turbulent) and
:class:`PressureSensor`.

Pumps and motors: one positive-displacement law (four quadrants) between
``port_a`` and ``port_b``, shaft ``flange`` turning against the housing
``support`` (fixed to ground when left unconnected).

Geometric (loss-free) relations (Murrenhoff, Verdraengereinheiten)::

    w = der(flange.phi - support.phi),   dp = port_b.p - port_a.p
    D = alpha Vg / (2 pi),  q_g = D w   (displaced flow from a to b)
    P_g = dp q_g = D w dp               (geometric power to the fluid)

Constant volumetric efficiency ``eta_v`` (leakage) and mechanical-
hydraulic efficiency ``eta_hm`` (friction) as in the textbook, applied
in the direction of the power flow: pumping (``P_g > 0``, shaft power
into the fluid) ``q = eta_v q_g``, ``tau = D dp / eta_hm``; motoring
(``P_g < 0``) ``q = q_g / eta_v``, ``tau = eta_hm D dp``.  Written as
one law ``q = q_g eta_v^s``, ``tau = D dp eta_hm^(-s)`` with the
smooth power direction ``s = tanh(P_g / P_band)``: the textbook law up to
``1 - tanh(10) = 4e-9`` in the exponent for ``|P_g| >= 10 P_band``, a
smooth blend in between, so that flow and torque stay continuous and
differentiable through standstill and zero pressure (no relation, no
event; near standstill under pressure the blend acts as a stiff viscous
friction of slope ``(D dp)^2 ln(1/eta_hm) / P_band``).  The loss
``P_mech - P_hyd = P_g (eta_hm^-s - eta_v^s) >= 0`` in all four
quadrants, since ``s`` has the sign of ``P_g``.

Port flows: ``port_a.q = q``, ``port_b.q = -q`` (oil enters at a, leaves
at b; the leakage is lumped into ``q``).  Torque ``tau`` is what the shaft
takes: ``flange.tau = tau``, ``support.tau = -tau``.  Outputs: ``w``,
``dp``, ``q``, ``q_g``, ``tau``, ``s``, ``P_mech = tau w`` (shaft power
in), ``P_hyd = dp q`` (hydraulic power out), ``loss_power``.
"""
import casadi as ca

from acausal2d import (Component, der, HydraulicPort, Parameter, RealInput, RealOutput,
                       RotationalFlange, Variable)

__all__ = ["PressureSource", "PressureSensor", "Pump", "Motor", "ReliefValve", "Volume",
           "Throttle", "Orifice"]

_TWO_PI = 6.283185307179586


class PressureSource(Component):
    """Pressure ``p0`` at ``port`` (a tank for ``p0 = 0`` gauge, or a
    constant-pressure supply); with ``use_p_in=True`` the signal input
    ``p_in`` [Pa] gives the pressure instead (Modelica.Fluid's
    ``use_p_in``).  Takes or gives any flow; ``P = p q`` is the hydraulic
    power the source takes in (negative: it delivers)."""
    p0 = Parameter(0.0, "Pa", "pressure at the port (0: tank, gauge pressure)")
    P = Variable(unit="W", nominal=1e3, doc="hydraulic power into the source p q")

    def __init__(self, use_p_in=False, **kw):
        super().__init__(**kw)
        self.use_p_in = bool(use_p_in)
        self.port = HydraulicPort(nominal={"p": 1e6, "q": 1e-4})
        if self.use_p_in:
            self.p_in = RealInput(doc="pressure at the port [Pa]")

    def equations(self):
        p = self.p_in.u if self.use_p_in else self.p0
        return [self.port.p == p, self.P == self.port.p * self.port.q]


class PressureSensor(Component):
    """Pressure at ``port`` as the signal ``p`` [Pa]; takes no flow."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.port = HydraulicPort(nominal={"p": 1e6, "q": 1e-4})
        self.p = RealOutput()

    def equations(self):
        return [self.p.u == self.port.p, self.port.q == 0]


class _Machine(Component):
    """Positive-displacement machine, the law :class:`Pump` and :class:`Motor`
    share (module docstring, "Pumps and motors")."""
    Vg = Parameter(1e-4, "m3/rev", "displacement per revolution (at alpha = 1)", positive=True)
    eta_v = Parameter(0.95, "1", "volumetric efficiency", positive=True, max=1.0)
    eta_hm = Parameter(0.9, "1", "mechanical-hydraulic efficiency", positive=True, max=1.0)
    P_band = Parameter(1.0, "W", "geometric power over which pumping and motoring efficiencies "
                       "blend", positive=True)
    w = Variable(unit="rad/s", doc="shaft speed relative to the housing")
    dp = Variable(unit="Pa", nominal=1e6, doc="pressure rise port_b.p - port_a.p")
    q_g = Variable(unit="m3/s", nominal=1e-4, doc="geometric flow D w from a to b")
    q = Variable(unit="m3/s", nominal=1e-4, doc="flow through the machine from a to b")
    tau = Variable(unit="N.m", nominal=1e2, doc="torque the shaft takes from the flange")
    s = Variable(unit="1", doc="power direction: +1 pumping, -1 motoring, blended in between")
    P_mech = Variable(unit="W", nominal=1e3, doc="shaft power into the machine tau w")
    P_hyd = Variable(unit="W", nominal=1e3, doc="hydraulic power out of the machine dp q")
    loss_power = Variable(unit="W", nominal=1e3, doc="power lost P_mech - P_hyd (>= 0)")

    def __init__(self, variable=False, **kw):
        super().__init__(**kw)
        self.variable = bool(variable)
        nominal = {"p": 1e6, "q": 1e-4}
        self.port_a = HydraulicPort(nominal=nominal, doc=self._port_docs[0])
        self.port_b = HydraulicPort(nominal=nominal, doc=self._port_docs[1])
        self.flange = RotationalFlange(doc="shaft")
        self.support = RotationalFlange(ground={"phi": 0.0}, doc="housing (ground if unconnected)")
        if self.variable:
            self.alpha = RealInput(doc="relative displacement Vg_actual / Vg (-1..1)")

    _port_docs = ("inlet", "outlet")

    def equations(self):
        alpha = self.alpha.u if self.variable else 1.0
        D = alpha * self.Vg / _TWO_PI
        s = ca.tanh(self.dp * self.q_g / self.P_band)   # bounded: eta^s stays in [eta, 1/eta]
        return [self.w == der(self.flange.phi - self.support.phi),
                self.dp == self.port_b.p - self.port_a.p,
                self.q_g == D * self.w, self.s == s,
                self.q == self.q_g * ca.exp(s * ca.log(self.eta_v)),
                self.tau == D * self.dp * ca.exp(-s * ca.log(self.eta_hm)),
                self.port_a.q == self.q, self.port_b.q == -self.q,
                self.flange.tau == self.tau, self.support.tau == -self.tau,
                self.P_mech == self.tau * self.w, self.P_hyd == self.dp * self.q,
                self.loss_power == self.P_mech - self.P_hyd]


class Pump(_Machine):
    """Hydrostatic pump: ``port_a`` suction, ``port_b`` pressure side; a
    positive shaft speed displaces oil from a to b.  Fixed displacement
    ``Vg``, or with ``variable=True`` the signal input ``alpha`` sets the
    displacement ``alpha Vg`` (swash plate, over centre for alpha < 0).
    Equations, efficiencies and outputs: module docstring (pumping:
    ``q = eta_v D w``, ``tau = D dp / eta_hm``)."""
    _port_docs = ("suction side", "pressure side")


class Motor(_Machine):
    """Hydrostatic motor: ``port_a`` supply (high pressure), ``port_b``
    return; oil flowing from a to b turns the shaft positively and the motor
    drives its load (``tau < 0``: the flange takes a negative torque, i.e.
    the motor gives ``-tau = eta_hm D (p_a - p_b)``).  Fixed displacement
    ``Vg``, or with ``variable=True`` the signal input ``alpha`` sets the
    displacement ``alpha Vg`` (secondary control).  Equations: module
    docstring (motoring: ``q = D w / eta_v``)."""
    _port_docs = ("supply (high pressure)", "return")


class ReliefValve(Component):
    """Pressure relief valve from ``port_a`` (the protected line) to
    ``port_b`` (tank), with the static characteristic of a direct-operated
    valve (Murrenhoff, Druckventile; SimulationX/Modelica-style cracking
    pressure and gradient)::

        dp = port_a.p - port_b.p
        q = G (dp - p_crack)   if dp > p_crack   else 0

    ``G`` is the gradient of the characteristic [m3/(s Pa)]: the pressure
    exceeds ``p_crack`` by ``q / G`` at the flow ``q``.  The flow is
    continuous when the valve opens or closes, and the opening (the relation
    ``dp > p_crack``) is an event.  ``port_a.q = q``, ``port_b.q = -q``;
    ``loss_power = dp q`` (>= 0) is the power throttled into heat."""
    p_crack = Parameter(2.5e7, "Pa", "cracking pressure", positive=True)
    G = Parameter(1e-9, "m3/(s.Pa)", "gradient of flow over pressure above p_crack", positive=True)
    dp = Variable(unit="Pa", nominal=1e6, doc="pressure drop port_a.p - port_b.p")
    q = Variable(unit="m3/s", nominal=1e-4, doc="flow from a to b")
    loss_power = Variable(unit="W", nominal=1e3, doc="power throttled dp q")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.port_a = HydraulicPort(nominal={"p": 1e6, "q": 1e-4}, doc="protected line")
        self.port_b = HydraulicPort(nominal={"p": 1e6, "q": 1e-4}, doc="tank")

    def equations(self):
        return [self.dp == self.port_a.p - self.port_b.p,
                self.q == self.G * ca.fmax(self.dp - self.p_crack, 0.0),
                self.port_a.q == self.q, self.port_b.q == -self.q,
                self.loss_power == self.dp * self.q]


class Volume(Component):
    """Compliant oil volume (line or chamber) with the constant bulk
    modulus ``K`` (Murrenhoff, Kompressibilitaet: ``dV = -V0 dp / K``)::

        der(p) = K / V0 * port.q

    ``port.p = p``; several elements connected to ``port`` add their flows.
    ``p`` starts at its start value (``fixed``; default 0, i.e. tank
    pressure).  ``E = V0 p^2 / (2 K)`` is the elastic energy stored in the
    oil (``der(E) = p port.q``)."""
    V0 = Parameter(1e-3, "m3", "oil volume", positive=True)
    K = Parameter(1.4e9, "Pa", "bulk modulus of the oil", positive=True)
    p = Variable(start=0.0, fixed=True, unit="Pa", nominal=1e6, state_select="prefer",
                 doc="pressure")
    E = Variable(unit="J", nominal=1e2, doc="elastic energy V0 p^2 / (2 K)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.port = HydraulicPort(nominal={"p": 1e6, "q": 1e-4})

    def equations(self):
        return [self.port.p == self.p, der(self.p) == self.K / self.V0 * self.port.q,
                self.E == self.V0 * self.p ** 2 / (2 * self.K)]


class _TwoPort(Component):
    dp = Variable(unit="Pa", nominal=1e6, doc="pressure drop port_a.p - port_b.p")
    q = Variable(unit="m3/s", nominal=1e-4, doc="flow from a to b")
    loss_power = Variable(unit="W", nominal=1e3, doc="power throttled dp q (>= 0)")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.port_a = HydraulicPort(nominal={"p": 1e6, "q": 1e-4})
        self.port_b = HydraulicPort(nominal={"p": 1e6, "q": 1e-4})

    def _common(self):
        return [self.dp == self.port_a.p - self.port_b.p,
                self.port_a.q == self.q, self.port_b.q == -self.q,
                self.loss_power == self.dp * self.q]


class Throttle(_TwoPort):
    """Laminar throttle (long narrow gap, Hagen-Poiseuille): ``q = G dp``
    with the conductance ``G`` [m3/(s Pa)]; ``loss_power = G dp^2``."""
    G = Parameter(1e-10, "m3/(s.Pa)", "laminar conductance", positive=True)

    def equations(self):
        return self._common() + [self.q == self.G * self.dp]


class Orifice(_TwoPort):
    """Turbulent orifice (sharp-edged, Murrenhoff "Blende")::

        q = Cd A sqrt(2 |dp| / rho) sign(dp)

    regularised near ``dp = 0`` as Modelica.Fluid.Utilities.regRoot, so that
    the flow stays differentiable (no infinite slope, no sign jump)::

        q = Cd A sqrt(2 / rho) dp / (dp^2 + dp_small^2)^(1/4)

    which equals the turbulent law within ``(dp_small/dp)^2 / 4`` relative for
    ``|dp| >> dp_small``."""
    A = Parameter(1e-5, "m2", "orifice cross-section", positive=True)
    Cd = Parameter(0.7, "1", "discharge coefficient", positive=True)
    rho = Parameter(870.0, "kg/m3", "oil density", positive=True)
    dp_small = Parameter(1e3, "Pa", "regularisation pressure of regRoot", positive=True)

    def equations(self):
        root = self.dp / (self.dp ** 2 + self.dp_small ** 2) ** 0.25
        return self._common() + [self.q == self.Cd * self.A * ca.sqrt(2 / self.rho) * root]
