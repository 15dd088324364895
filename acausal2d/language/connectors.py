"""Connector kinds.

A connector groups potential variables (equal across a connection) and flow
variables (summing to zero at a connection, Ebert (2015), eq. 4.1).  Flows are the
forces/torques acting *on* the component from outside.

- :class:`Frame`: planar frame, potentials x, y, phi; flows fx, fy, t, all
  resolved in the world frame.
- :class:`RotationalFlange`: phi; tau.
- :class:`TranslationalFlange`: s; f.
- :class:`BandPort`: wound length and belt angle; connects to exactly one
  other band port (Ebert 2015, ch. 4.1).
- :class:`HydraulicPort`: pressure p; volume flow q into the component.
- :class:`RealInput`, :class:`RealOutput`: a signal ``u``.

A connector created with ``ground=...`` is fixed to ground while it is left
unconnected (the triangle-symbol ports of Ebert (2015), Tabelle 4.1); ``ground`` maps
potential names to values or parameter expressions (a callable receiving the
owning component is evaluated when the model is flattened).  A connector
with ``required=True`` must be connected.
"""
from typing import Optional
from .declarations import Variable, VarInfo, _join
from ..errors import ModelDefinitionError


class Connector:
    """Base class of connector kinds (see module docstring)."""

    kind: str = "connector"
    potentials: tuple[str, ...] = ()
    flows: tuple[str, ...] = ()
    units: dict[str, str] = {}
    one_to_one = False
    signal: Optional[str] = None  # "input" / "output" for signal connectors

    def __init__(self, ground=None, required=False, doc="", nominal=None):
        self._owner = None
        self._name = None
        self._syms = {}
        self.ground = ground
        self.required = required
        self.doc = doc
        self.nominal = dict(nominal or {})

    def _attach(self, owner, name):
        if self._owner is not None:
            raise ModelDefinitionError("connector %s is already attached to %s"
                                       % (name, self._owner.describe()))
        self._owner = owner
        self._name = name

    @property
    def owner(self):
        """The component the connector belongs to."""
        return self._owner

    @property
    def path(self):
        """Dotted name of the connector in the model."""
        return _join(self._owner.path, self._name)

    def describe(self):
        """Dotted name with the owner's class, for messages."""
        if self._owner is None:
            return "<unattached %s>" % self.kind
        return "%s (%s)" % (self.path, type(self._owner).__name__)

    def _bind(self, table, vars_out):
        self._syms = {}
        for name in self.potentials + self.flows:
            decl = Variable(unit=self.units.get(name, ""),
                            nominal=self.nominal.get(name, 1.0))
            full = _join(self.path, name)
            sym = table.new_variable(full)
            self._syms[name] = sym
            vars_out.append(VarInfo(full, sym, decl, self._owner))

    def __getattr__(self, name):
        d = self.__dict__
        if name in type(self).potentials or name in type(self).flows:
            sym = d.get("_syms", {}).get(name)
            if sym is None:
                raise ModelDefinitionError(
                    "connector variable %s.%s is symbolic; use it inside equations()"
                    % (d.get("_name"), name))
            return sym
        raise AttributeError(name)

    def variables(self):
        """(name, symbol) of all connector variables."""
        return [(n, self._syms[n]) for n in self.potentials + self.flows]


class Frame(Connector):
    """Planar frame: position x, y [m], angle phi [rad]; force fx, fy [N]
    and torque t [N.m] acting on the component, world-resolved."""
    kind = "Frame"
    potentials = ("x", "y", "phi")
    flows = ("fx", "fy", "t")
    units = {"x": "m", "y": "m", "phi": "rad", "fx": "N", "fy": "N", "t": "N.m"}


class RotationalFlange(Connector):
    """1D rotational flange: angle phi [rad], torque tau [N.m]."""
    kind = "RotationalFlange"
    potentials = ("phi",)
    flows = ("tau",)
    units = {"phi": "rad", "tau": "N.m"}


class TranslationalFlange(Connector):
    """1D translational flange: position s [m], force f [N]."""
    kind = "TranslationalFlange"
    potentials = ("s",)
    flows = ("f",)
    units = {"s": "m", "f": "N"}


class BandPort(Connector):
    """Band connector: wound length L [m] and belt angle gamma [rad]
    (Ebert 2015, ch. 4.1).  It may be connected to exactly one other band port."""
    kind = "BandPort"
    potentials = ("L", "gamma")
    flows = ()
    units = {"L": "m", "gamma": "rad"}
    one_to_one = True


class HydraulicPort(Connector):
    """Hydrostatic port: pressure p [Pa] (potential), volume flow q [m3/s]
    (flow, positive INTO the component, Modelica's sign convention); the
    hydraulic power entering the component through the port is ``p q``."""
    kind = "HydraulicPort"
    potentials = ("p",)
    flows = ("q",)
    units = {"p": "Pa", "q": "m3/s"}


class RealInput(Connector):
    """Signal input ``u``; must be connected to exactly one output."""
    kind = "Real"
    potentials = ("u",)
    signal = "input"

    def __init__(self, **kw):
        kw.setdefault("required", True)
        super().__init__(**kw)


class RealOutput(Connector):
    """Signal output ``u``."""
    kind = "Real"
    potentials = ("u",)
    signal = "output"
