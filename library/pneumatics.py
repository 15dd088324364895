"""Pneumatics: a cylinder chamber with ideal-gas compression (for the
compressor of Ebert (2015), ch. 8.2, "Pneumatics" subsystem of Bild 8.8).

The dissertation only names the subsystem ("Pneumatikeinrichtung zur
Druckluftbereitstellung"); its equations are not given there.  This module
uses the textbook filling-and-emptying model of a piston chamber (lumped
gas, ideal gas law, no heat transfer unless a polytropic exponent is given).

:class:`GasCylinder` -- chamber between the piston ``flange_a`` and the
cylinder head ``flange_b`` (1D translational flanges, e.g. the flange of a
``planar.Prismatic(use_flange=True)`` and a ``translational.Fixed``).

Volume and force::

    V = A * (flange_b.s - flange_a.s)          (gap piston -> head, incl. dead volume)
    flange_a.f = (p - p_amb) A,  flange_b.f = -(p - p_amb) A

(the gas pushes piston and head apart; ambient pressure acts on the back
of the piston).

Gas mass and energy (open adiabatic chamber; ``n = kappa``)::

    der(m) = mdot_in - mdot_out
    V der(p) + n p der(V) = kappa (R T_in mdot_in - (p V / m) mdot_out)

With both valves closed the second line is ``V dp + n p dV = 0``, i.e.
``p V^n = const`` (adiabatic for ``n = kappa``, polytropic otherwise -- the
polytropic exponent lumps the heat exchange with the wall; with mass flow
the right-hand side stays the adiabatic enthalpy flux, so ``n != kappa``
with open valves is an approximation).  The outflow leaves with the chamber
temperature ``T = p V / (m R)``, the inflow enters with ``T_in``.

Valves (structural options ``intake``, ``discharge``): ideal check valves
with a linear flow conductance, as events::

    mdot_out = G_out (p - p_out)   if p > p_out   else 0   (discharge into a
                                                           reservoir at p_out)
    mdot_in  = G_in (p_in - p)     if p < p_in    else 0   (intake from p_in)

The relations ``p > p_out`` and ``p < p_in`` are zero crossings: opening and
closing of each valve are events.  The flow is continuous across them (it
vanishes at the switching pressure), so re-initialization is trivial.  A
large conductance makes the valve ideal (the chamber pressure then stays
close to the reservoir pressure while the valve is open; the pressure
overshoot is ``mdot / G``).  Without both valves the chamber holds a fixed
gas mass.

Initial state: ``p`` starts at ``p_amb`` (``fixed``) and the gas mass
follows from the start temperature ``T`` (``fixed``, default ``T_in``):
``m = p V / (R T)``.  Change with ``GasCylinder(p=start(2e5, fixed=True))``.
"""
import casadi as ca

from acausal2d import Component, der, Parameter, TranslationalFlange, Variable

__all__ = ["GasCylinder"]


class GasCylinder(Component):
    """Piston chamber with ideal gas and optional intake/discharge check
    valves (see the module docstring for the equations).

    Outputs: ``V`` volume, ``p`` pressure, ``m`` gas mass, ``T`` gas
    temperature, ``mdot_in``, ``mdot_out`` valve mass flows, ``F`` gas force
    on the piston ``(p - p_amb) A`` (pushing it away from the head), ``P_gas``
    power delivered by the piston to the gas ``-(p - p_amb) der(V)``.
    """
    A = Parameter(5.026548245743669e-3, "m2", "piston area (default bore 80 mm)", positive=True)
    p_amb = Parameter(1.0e5, "Pa", "ambient pressure behind the piston", positive=True)
    kappa = Parameter(1.4, "1", "ratio of specific heats (air)", min=1.0)
    n = Parameter(1.4, "1", "polytropic exponent of compression/expansion (= kappa: adiabatic)", min=1.0)
    R = Parameter(287.0, "J/(kg.K)", "specific gas constant (air)", positive=True)
    p_in = Parameter(1.0e5, "Pa", "intake pressure", positive=True)
    T_in = Parameter(293.15, "K", "intake temperature", positive=True)
    p_out = Parameter(8.0e5, "Pa", "reservoir (discharge) pressure", positive=True)
    G_in = Parameter(1e-6, "kg/(s.Pa)", "intake valve conductance", min=0.0)
    G_out = Parameter(1e-6, "kg/(s.Pa)", "discharge valve conductance", min=0.0)

    V = Variable(start=1e-4, unit="m3", nominal=1e-4, state_select="avoid",
                 doc="chamber volume")
    p = Variable(start=1.0e5, fixed=True, unit="Pa", nominal=1e5, state_select="prefer",
                 doc="chamber pressure")
    m = Variable(start=1e-4, unit="kg", nominal=1e-4, state_select="prefer",
                 doc="gas mass in the chamber")
    T = Variable(start=293.15, fixed=True, unit="K", nominal=300.0, doc="gas temperature")
    mdot_in = Variable(unit="kg/s", nominal=1e-2, doc="mass flow through the intake valve")
    mdot_out = Variable(unit="kg/s", nominal=1e-2, doc="mass flow through the discharge valve")
    F = Variable(unit="N", nominal=1e3, doc="gas force on the piston (p - p_amb) A")
    P_gas = Variable(unit="W", nominal=1e3, doc="power from the piston into the gas")

    def __init__(self, intake=True, discharge=True, **kw):
        super().__init__(**kw)
        self.intake = bool(intake)
        self.discharge = bool(discharge)
        self.flange_a = TranslationalFlange(doc="piston")
        self.flange_b = TranslationalFlange(doc="cylinder head")

    def equations(self):
        eqs = [self.V == self.A * (self.flange_b.s - self.flange_a.s),
               self.F == (self.p - self.p_amb) * self.A,
               self.flange_a.f == self.F, self.flange_b.f == -self.F,
               self.P_gas == -(self.p - self.p_amb) * der(self.V),
               self.p * self.V == self.m * self.R * self.T]
        if self.intake:
            eqs.append(self.mdot_in == ca.if_else(self.p < self.p_in,
                                                  self.G_in * (self.p_in - self.p), 0.0))
        else:
            eqs.append(self.mdot_in == 0)
        if self.discharge:
            eqs.append(self.mdot_out == ca.if_else(self.p > self.p_out,
                                                   self.G_out * (self.p - self.p_out), 0.0))
        else:
            eqs.append(self.mdot_out == 0)
        eqs += [der(self.m) == self.mdot_in - self.mdot_out,
                self.V * der(self.p) + self.n * self.p * der(self.V)
                == self.kappa * (self.R * self.T_in * self.mdot_in - self.R * self.T * self.mdot_out)]
        return eqs
