"""Band mechanisms of Ebert (2015), ch. 2.5.2 (Bild 2.6-2.9): a band cam disc (a
curved drum pivoted in the ground, turned by a drive) and a band that
pulls the output.  The cam is an eccentric circle (support function p(psi)
= RC + E cos psi in the drum frame), so the lever arm of the band about the
drum pivot changes with the drum angle and the ratio is not constant.

==========  ===========================================  ==================
model       structure (Ebert (2015))                     output load
==========  ===========================================  ==================
DBDD        DB~DD (Bild 2.6, four-bar chain): band from  torque on the
            the drum to the tip of a rocker at B0         rocker
DBDDInv.    DB~DD with the rocker as ground (Bild    torque between
            2.6, change of the ground link): the drum on  crank and drum
            a driven crank, the band to a ground pin
DBDS        DB~DS (Bild 2.7, slider-crank chain): band   force on the
            from the drum to a slider on a ground guide   slider
SBDS        SB~DS (Bild 2.8, cross-slider chain): the   force on the
            band cam on a driven carriage, the band to    slider
            a slider on a vertical guide
Nozzle3     three-link band mechanism with a draw-off    the elastic band
            nozzle (Bild 2.9 left): the band runs from    (spring) behind
            the drum through a ground nozzle to an        the nozzle
            anchor; its elasticity is the tension spring
Spring3     three-link spring band mechanism (Bild 2.9   tension spring
            right): band with a tension spring from the   in the band
            drum to a ground pivot
NozzleSl.   Bild 3.1 f: band from a drum through a       take-up torque
            draw-off nozzle to the rocker of a slotted    on the drum
            crank (Kurbelschleife)
==========  ===========================================  ==================

All links are massless, so the balances are static at every instant:
drive torque = F h_D with h_D the distance of the band line from the drum
pivot, and F h_B = load torque (F cos alpha = load force on the slider); the
tests check these and the ratio omega_out / omega_drum = h_D / h_B against
the geometry of the result.  Lengths in metres.
"""
import math

from acausal2d import Component, start
from acausal2d.library.belt import (Band, CurvedDrum, Drum, NozzleBelt, SpringBelt,
                                    SupportContour, connect_band, tangent)
from acausal2d.library.linkage import DAN, DSD, SAN
from acausal2d.library.linkage.drives import ForceSource, Preset, TorqueSource
from acausal2d.library.planar import Fixed, FixedTranslation

RC, E = 0.05, 0.02               # cam: radius and eccentricity (centre at (E, 0) in its frame)
OM = 1.0                         # drum speed, rad/s


def band_start(a, b, l_names=("l", "l_x", "l_x0")):
    """Start values of a band span from the tangent construction with the
    cam taken as its circle at t = 0."""
    gam, length = tangent(a, b)
    return {"gamma": start(gam), **{n: start(length) for n in l_names}}


class _Drum(Component):
    """The band cam disc at the origin, turned at OM by a preset; the band
    leaves it at K1 (w = -1: a positive turn pays the band out)."""
    experiment = {"stop_time": 2.0, "intervals": 100, "rtol": 1e-10}
    outputs = ["drive.tau", "band.F"]
    figures = [{"name": "forces", "signals": ["band.F"], "x": "drive.phi",
                "title": "band force over the drum angle"},
               {"name": "drive_torque", "signals": ["drive.tau"], "x": "drive.phi",
                "title": "drive torque over the drum angle"}]

    def _drum(self, w_i=1):
        self.drive = Preset(kind="speed", om=OM, phi0=0.0)
        self.drum = CurvedDrum(SupportContour(RC, a=(E,), b=(0.0,)), w_i=w_i, n_wound=2.0)
        self.connect(self.drive.flange, self.drum.ctrR2)
        return (E, 0.0, -w_i * RC)    # the cam circle at t = 0, contact side -w_i

    def _band_to(self, span, frame, end=1):
        """Band end ``end`` on ``frame``, the other end on the drum."""
        self.connect(getattr(span, "ctr2D%d" % end), frame)
        connect_band(self, span, 3 - end, self.drum, 1)


class DBDD(_Drum):
    """DB~DD: the band pulls the tip of a rocker (length 0.1 at B0 = (0.2,
    0.12), hanging down at the start) loaded by a torque of 2 N m that keeps
    the band taut."""
    outputs = ["drive.tau", "band.F", "rocker.phiL"]

    def __init__(self, **kw):
        super().__init__(**kw)
        cam = self._drum()
        b0, phi0 = (0.2, 0.12), -math.pi / 2
        tip = (b0[0] + 0.1 * math.cos(phi0), b0[1] + 0.1 * math.sin(phi0))
        self.rocker = DAN(lL=0.1, x10=b0[0], y10=b0[1], mL=0.0, JL=0.0, phiL0=phi0,
                          phiL=start(phi0))
        self.load = TorqueSource(tau=2.0)
        self.connect(self.load.flange, self.rocker.ctrR2)
        self.band = Band(**band_start((*tip, 0.0), cam))
        self._band_to(self.band, self.rocker.ctr2D2)


class DBDDInverted(_Drum):
    """A neighbour of DB~DD in Bild 2.6 (change of the ground link): the
    rocker is the ground.  The former ground is a crank (0.15 at the origin,
    driven at OM from 90 degrees) carrying the drum's pivot; the band runs
    from the drum to the ground pin G = (0.25, 0.1); a torque of 1 N m
    between crank and drum keeps it taut."""
    outputs = ["drive.tau", "band.F", "drum.phi_rel"]
    G = (0.25, 0.1)

    def __init__(self, **kw):
        super().__init__(**kw)
        self.drive = Preset(kind="speed", om=OM, phi0=math.pi / 2)
        self.crank = DAN(lL=0.15, mL=0.0, JL=0.0)
        self.connect(self.drive.flange, self.crank.ctrR2)
        self.drum = CurvedDrum(SupportContour(RC, a=(E,), b=(0.0,)), w_i=-1, n_wound=2.0)
        self.connect(self.crank.ctr2D2, self.drum.ctr2D1)
        self.load = TorqueSource(tau=1.0)              # on the drum ...
        self.connect(self.load.flange, self.drum.ctrR2)
        self.reaction = TorqueSource(tau=-1.0)         # ... and back on the crank (housing)
        self.connect(self.reaction.flange, self.drum.ctrR1)
        self.pin = Fixed(r=self.G)
        self.band = Band(**band_start((*self.G, 0.0), (E, 0.15, RC)))
        self._band_to(self.band, self.pin.frame)


class DBDS(_Drum):
    """DB~DS: the band pulls a slider on a horizontal ground guide at y =
    -0.1 away from the drum; a force of 20 N pulls the slider back."""
    outputs = ["drive.tau", "band.F", "slider.xG"]

    def __init__(self, **kw):
        super().__init__(**kw)
        cam = self._drum()
        self.slider = SAN(x10=0.0, y10=-0.1, phi10=0.0, mS=0.0, JS=0.0, xS0=0.2,
                          xG=start(0.2))
        self.load = ForceSource(f=20.0)
        self.connect(self.load.flange, self.slider.ctrT2)
        self.band = Band(**band_start((0.2, -0.1, 0.0), cam))
        self._band_to(self.band, self.slider.ctr2D2)


class SBDS(_Drum):
    """A structure of the cross-slider chain (Bild 2.8, two prismatic
    joints): the band cam is a plate on a carriage driven along the ground
    x axis at 0.05 m/s (to the right) (no rotation: its flange is held), and the band pulls
    a slider on the vertical ground guide x = 0.15 against a force of 10 N."""
    outputs = ["drive.tau", "band.F", "slider.xG"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.drive = Preset(kind="speed", translational=True, om=0.05, phi0=0.0)
        self.carriage = SAN(mS=0.0, JS=0.0, xS0=0.0)
        self.connect(self.drive.flange, self.carriage.ctrT2)
        self.drum = CurvedDrum(SupportContour(RC, a=(E,), b=(0.0,)), w_i=1, n_wound=2.0)
        self.connect(self.drum.ctrR1, self.drum.ctrR2)   # held on the carriage
        self.connect(self.carriage.ctr2D2, self.drum.ctr2D1)
        self.slider = SAN(x10=0.15, y10=-0.4, phi10=math.pi / 2, mS=0.0, JS=0.0, xS0=0.2,
                          xG=start(0.2))
        self.load = ForceSource(f=-10.0)
        self.connect(self.load.flange, self.slider.ctrT2)
        self.band = Band(**band_start((0.15, -0.2, 0.0), (E, 0.0, -RC)))
        self._band_to(self.band, self.slider.ctr2D2)


class Nozzle3(_Drum):
    """Three-link band mechanism with a draw-off nozzle at N = (0.2, -0.05):
    the band (elastic, c = 500 N per unit strain, 20 % pre-strain) runs from
    the drum through the nozzle to the anchor A = (0.2, -0.25)."""
    NOZZLE, ANCHOR = (0.2, -0.05), (0.2, -0.25)

    def __init__(self, **kw):
        super().__init__(**kw)
        cam = self._drum(w_i=-1)
        g1, l1 = tangent((*self.NOZZLE, 0.0), cam)
        self.band = NozzleBelt(c=500.0, eps=start(0.2, fixed=True), gamma1=start(g1 + math.pi),
                               l1=start(l1), l2=start(0.2), gamma2=start(-math.pi / 2))
        self.nozzle, self.anchor = Fixed(r=self.NOZZLE), Fixed(r=self.ANCHOR)
        self.connect(self.band.ctr2D3, self.nozzle.frame)
        self.connect(self.band.ctr2D2, self.anchor.frame)
        connect_band(self, self.band, 1, self.drum, 1)


class Spring3(_Drum):
    """Three-link spring band mechanism: band with a tension spring (k = 400
    N/m, 0.1 m long, 0.05 m pre-extension) from the drum to the ground pivot
    A = (0.3, 0.0)."""
    ANCHOR = (0.3, 0.0)

    def __init__(self, **kw):
        super().__init__(**kw)
        cam = self._drum(w_i=-1)
        self.band = SpringBelt(k=400.0, l0=0.1, l_dF=start(0.05, fixed=True),
                               **band_start(cam, (*self.ANCHOR, 0.0), ("l", "l_x", "l_x0")))
        self.anchor = Fixed(r=self.ANCHOR)
        connect_band(self, self.band, 1, self.drum, 1)
        self.connect(self.band.ctr2D2, self.anchor.frame)


class NozzleSlottedCrank(Component):
    """Bild 3.1 f: "the band is led from a band pulley through a draw-off
    nozzle and attached to a crank-slotted mechanism (Kurbelschleife)".

    The dissertation gives only this sentence; assumed here: the
    slotted crank is a crank of R_CRANK = 0.04 m about A0 = (0, 0), driven
    at one revolution per second, whose pin slides in a guide (rocker,
    :class:`~acausal2d.library.linkage.DSD`) pivoted at B0 = (0, -0.12);
    the band is fastened to the rocker at E, L_ROCKER = 0.2 m from B0, and
    runs through the ground nozzle N = (0.25, 0.08) (an elastic band, eq.
    4.67-4.77, c = 2000 N per unit strain) to a drum of radius 0.04 m at D =
    (0.45, 0) that a take-up torque of 0.4 N m keeps winding (the thread
    tensioner of a sewing machine's take-up lever, Ebert (2015), ch. 3.1): the band
    pulls with 10 N while the rocker swings it out and back.  Massless links.

    Closed forms: the rocker angle psi = atan2(R sin phi + 0.12, R cos phi)
    (the guide passes through the crank pin, offset v = 0), the band force
    at the drum F = T / r, and the power balance drive torque x omega =
    the band's pull on E times E's speed along the band."""
    experiment = {"stop_time": 1.0, "intervals": 100, "rtol": 1e-10}
    outputs = ["drive.tau", "band.F", "rocker.phiU"]
    figures = [{"name": "drive_torque", "signals": ["drive.tau"], "x": "drive.phi",
                "title": "drive torque over the crank angle"}]
    R_CRANK, B0, L_ROCKER = 0.04, (0.0, -0.12), 0.2
    NOZZLE, DRUM, R_DRUM, T_TAKE_UP, C_BAND = (0.25, 0.08), (0.45, 0.0), 0.04, 0.4, 2000.0
    J_DRUM = 1e-4

    def __init__(self, **kw):
        super().__init__(**kw)
        om = 2 * math.pi
        self.drive = Preset(kind="speed", om=om, phi0=0.0)
        self.crank = DAN(lL=self.R_CRANK, mL=0.0, JL=0.0)
        self.connect(self.drive.flange, self.crank.ctrR2)
        self.rocker = DSD(v=0.0, x10=self.B0[0], y10=self.B0[1], mU=0.0, JU=0.0, mS=0.0,
                          JS=0.0)
        self.connect(self.crank.ctr2D2, self.rocker.ctr2D2)
        self.arm = FixedTranslation(r=(self.L_ROCKER, 0.0))
        self.connect(self.rocker.ctr2D3, self.arm.frame_a)
        self._band()

    def _band(self):
        psi = math.atan2(-self.B0[1], self.R_CRANK)
        E = (self.B0[0] + self.L_ROCKER * math.cos(psi), self.B0[1] + self.L_ROCKER * math.sin(psi))
        N = self.NOZZLE
        g1, l1 = tangent((*N, 0.0), (*self.DRUM, self.R_DRUM))
        eps = self.T_TAKE_UP / self.R_DRUM / self.C_BAND
        self.band = NozzleBelt(c=self.C_BAND, eps=start(eps, fixed=True),
                               gamma1=start(g1 + math.pi), l1=start(l1),
                               l2=start(math.hypot(E[0] - N[0], E[1] - N[1])),
                               gamma2=start(math.atan2(E[1] - N[1], E[0] - N[0])))
        # the drum's inertia J_DRUM and the elastic band swing (the thread
        # tension varies about T / r); at rest at t = 0 with eps = T / (r c)
        self.drum = Drum(r=self.R_DRUM, w_i=-1, n_wound=3.0, x10=self.DRUM[0], y10=self.DRUM[1],
                         frameRef="global", J=self.J_DRUM, w_rel=start(0.0, fixed=True))
        self.take_up = TorqueSource(tau=self.T_TAKE_UP)
        self.connect(self.take_up.flange, self.drum.ctrR2)
        self.nozzle = Fixed(r=N)
        self.connect(self.band.ctr2D3, self.nozzle.frame)
        self.connect(self.band.ctr2D2, self.arm.frame_b)
        connect_band(self, self.band, 1, self.drum, 1)


MODELS = [DBDD, DBDDInverted, DBDS, SBDS, Nozzle3, Spring3, NozzleSlottedCrank]
