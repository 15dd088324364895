"""Accessory belt drive with a back-side tensioner on a lever (Ebert (2015),
Bild 3.1 c): "a belt drive combined with a linkage: the tensioner pulley is
guided movably in the frame on a simple lever and tensions the belt over
its back; typical applications are the accessory drives of vehicle
engines."  The text gives this sentence only; every number below is
assumed (a small petrol engine's accessory drive at idle).

Structure: one closed poly-V belt of five elastic spans
(:class:`~acausal2d.library.belt.Belt`) around the crankshaft pulley C
(driving), the tensioner T, the air-conditioning compressor K, the water
pump W and the alternator A, in this order counter-clockwise.  C, K, W and
A sit with their inner side on the belt (``w_i = -1``, turning
counter-clockwise); T sits outside the loop on the slack span leaving the
crankshaft and is wrapped by the belt's back (outer side): ``w_i = +1``,
it turns clockwise.  T's axis is the end of a lever: a
:class:`~acausal2d.library.linkage.DAN` pivoted in the frame (its crank is
the lever, not driven), the pulley placed on the lever's plane ``ctr2D2``
with ``x10 = y10 = 0`` (Anhang A.1, frameRef 'relative'); a torsion
spring between the DAN's housing flange ``ctrR1`` and lever flange
``ctrR2`` presses T into the belt, a viscous damper on the lever's flange
damps it.

Values ASSUMED (metres, x right, y up):

* pulleys: C (0, 0) r 80 mm, J 2e-3 kg m^2; K (0.32, -0.05) r 60 mm,
  J 1.5e-3; W (0.30, 0.20) r 55 mm, J 5e-4; A (0.05, 0.35) r 30 mm,
  J 3e-4; T (0.17, -0.10) at t0, r 35 mm, J 5e-5 (smooth back idler);
  massless housings, no bearing friction;
* belt: c = 1e5 N per unit strain, d = 50 N s per unit strain, every span
  pretensioned to F0 = 300 N at t0 (strain F0/c);
* tensioner lever: pivot (0.26, -0.20), lever to T of 135 mm, massless
  with J_L = 2e-3 kg m^2 (lever and idler); torsion spring 20 N m/rad,
  its unstressed angle from the lever's balance at t0 with F0 in both
  spans at T (:func:`spring_zero_angle`), damper 2 N m s/rad;
* loads (proportional to speed, none at rest): alternator 0.02 N m s/rad,
  water pump 0.01, compressor 0.02;
* the crankshaft pulley follows a speed ramp from rest at t = 0.1 s to
  80 rad/s (760 rpm) at 0.6 s (cycloidal, C2), then runs at that speed; no
  gravity on the drive (massless parts, gravity plays no role).

What follows (tests/test_accessory_drive.py): at rest the lever stays in
its balance; at the steady end each pulley's load torque equals r times
the difference of its span forces, the lever's spring torque the moment of
the two span forces at T about the pivot (the tensioner's static balance
from the run's geometry); the work of the crankshaft equals the loads'
work + the dampers' losses + the kinetic and elastic energy + the belt's
creep (strain energy of the material running onto and off the pulleys) --
the power balance, to the integration's tolerance; T turns against the
other pulleys (back-side wrap).
"""
import math
import sys

import casadi as ca

from acausal2d import Component, der, Parameter, RotationalFlange, start, Variable
from acausal2d.library import rotational
from acausal2d.library.belt import Belt, Pulley, connect_band, tangent
from acausal2d.library.linkage import DAN
from acausal2d.library.planar import PlanarWorld
from acausal2d.library.signals import TimeFunction

PULLEYS = {        # name: (axis, r, J, w_i, load [N m s/rad] or None)
    "C": ((0.0, 0.0), 0.08, 2e-3, -1, None),
    "T": ((0.17, -0.10), 0.035, 5e-5, 1, None),
    "K": ((0.32, -0.05), 0.06, 1.5e-3, -1, 0.02),
    "W": ((0.30, 0.20), 0.055, 5e-4, -1, 0.01),
    "A": ((0.05, 0.35), 0.03, 3e-4, -1, 0.02),
}
LOOP = ["C", "T", "K", "W", "A"]
"""The belt's path, counter-clockwise; span k (1..5) runs from LOOP[k-1] to
LOOP[k] (span 5 from A back to C)."""
PIVOT = (0.26, -0.20)
C_BELT, D_BELT, F0 = 1e5, 50.0, 300.0
C_SPRING, D_SPRING, J_LEVER = 20.0, 2.0, 2e-3
OMEGA, T_START, T_RAMP = 80.0, 0.1, 0.5
T_STOP = 1.5


def crank_angle(t):
    """Crankshaft angle: at rest until T_START, a cycloidal speed ramp to
    OMEGA over T_RAMP (speed OMEGA cycloid(u)), then OMEGA."""
    u = ca.fmin(ca.fmax((t - T_START) / T_RAMP, 0.0), 1.0)
    ramp = OMEGA * T_RAMP * (u ** 2 / 2 + (ca.cos(2 * ca.pi * u) - 1) / (4 * ca.pi ** 2))
    return ramp + OMEGA * ca.fmax(t - T_START - T_RAMP, 0.0)


def span_ends():
    """(start, end) geometry (cx, cy, signed radius) of each span for the
    tangent construction: a span leaves its first pulley at K2 (signed
    radius -w r) and reaches the next at K1 (+w r), w = -w_i."""
    out = []
    for k in range(len(LOOP)):
        a, b = PULLEYS[LOOP[k]], PULLEYS[LOOP[(k + 1) % len(LOOP)]]
        out.append(((a[0][0], a[0][1], a[3] * a[1]), (b[0][0], b[0][1], -b[3] * b[1])))
    return out


def lever_moment(F=F0):
    """Moment about the pivot of the belt on T with the force F in both of
    its spans (span 1 pulls T towards C, span 2 towards K)."""
    g1, _ = tangent(*span_ends()[0])
    g2, _ = tangent(*span_ends()[1])
    Rx = F * (math.cos(g2) - math.cos(g1))
    Ry = F * (math.sin(g2) - math.sin(g1))
    T = PULLEYS["T"][0]
    return (T[0] - PIVOT[0]) * Ry - (T[1] - PIVOT[1]) * Rx


def lever_start():
    """Lever length and start angle (pivot -> T)."""
    T = PULLEYS["T"][0]
    return math.hypot(T[0] - PIVOT[0], T[1] - PIVOT[1]), math.atan2(T[1] - PIVOT[1],
                                                                   T[0] - PIVOT[0])


def spring_zero_angle():
    """Unstressed angle of the torsion spring: balance of the lever at t0,
    -C_SPRING (phi_L0 - phi_0) + lever_moment() = 0."""
    return lever_start()[1] - lever_moment() / C_SPRING


class ViscousLoad(Component):
    """A torque against the speed of ``flange`` (reaction in the ground):
    ``flange.tau = d w``, ``w = der(flange.phi)``; ``loss_power = d w^2``.
    (The absolute angle keeps its own scale; a Damper to a fixed flange
    would make it a relative state of nominal 1e-4 rad.)"""
    d = Parameter(1.0, "N.m.s/rad", "damping constant", min=0.0)
    w = Variable(unit="rad/s", doc="speed of the flange")
    loss_power = Variable(unit="W", doc="power taken, d w^2")

    def __init__(self, **kw):
        super().__init__(**kw)
        self.flange = RotationalFlange()

    def equations(self):
        return [self.w == der(self.flange.phi), self.flange.tau == self.d * self.w,
                self.loss_power == self.d * self.w ** 2]


class AccessoryDrive(Component):
    """Accessory belt drive with a back-side tensioner on a lever (module
    docstring)."""
    experiment = {"stop_time": T_STOP, "intervals": 300, "rtol": 1e-8}
    outputs = ["span1.F", "span2.F", "span5.F", "lever.phiL", "C.ctrR2.tau", "T.w_rel"]
    figures = [{"name": "accessory_drive_spans", "title": "span forces (Bild 3.1 c)",
                "signals": ["span1.F", "span2.F", "span3.F", "span4.F", "span5.F"]},
               {"name": "accessory_drive_tensioner", "title": "tensioner lever angle",
                "signals": ["lever.phiL"]}]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.world = PlanarWorld(g=(0.0, 0.0))
        length, phi0 = lever_start()
        self.lever = DAN(x10=PIVOT[0], y10=PIVOT[1], lL=length, mL=0.0, JL=J_LEVER,
                         phiL=start(phi0, fixed=True), omL=start(0.0, fixed=True))
        self.tensioner = rotational.Spring(c=C_SPRING, phi_rel0=spring_zero_angle())
        self.lever_damper = ViscousLoad(d=D_SPRING)      # the housing stands: absolute = relative
        self.connect(self.lever.ctrR1, self.tensioner.flange_a)
        self.connect(self.lever.ctrR2, self.tensioner.flange_b)
        self.connect(self.lever.ctrR2, self.lever_damper.flange)
        for name, (P, r, J, w_i, load) in PULLEYS.items():
            place = dict(x10=0.0, y10=0.0) if name == "T" else dict(x10=P[0], y10=P[1])
            setattr(self, name, Pulley(r=r, J=J, w_i=w_i, **place))
            if load is not None:
                setattr(self, "load" + name, ViscousLoad(d=load))
                self.connect(getattr(self, name).ctrR2, getattr(self, "load" + name).flange)
        self.connect(self.lever.ctr2D2, self.T.ctr2D1)
        self.law = TimeFunction(crank_angle)
        self.drive = rotational.Position()
        self.connect(self.law.y, self.drive.phi_in)
        self.connect(self.drive.flange, self.C.ctrR2)
        for k in range(1, len(LOOP) + 1):
            span = Belt(c=C_BELT, d=D_BELT, eps=start(F0 / C_BELT, fixed=True))
            setattr(self, "span%d" % k, span)
            connect_band(self, span, 1, getattr(self, LOOP[k - 1]), 2)
            connect_band(self, span, 2, getattr(self, LOOP[k % len(LOOP)]), 1)


if __name__ == "__main__":
    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
