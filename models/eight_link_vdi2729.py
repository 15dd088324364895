"""8-link mechanism after VDI 2729 example 2 (Ebert 2015, ch. 7.1, Bild 7.3/7.4,
Anhang C, Tabelle C.1), kinematically driven at 1.5 rad/s, and the same
mechanism force-driven (torque + flywheel on the crank).

Structure (Bild 7.3, model view): DAN -> DSD -> FGP -> SDS, SSD; ``preset1``
drives the crank.  Links: 1 ground, 2 crank (DAN), 3 slotted coupler (DSD
guide, pivoted on the crank pin A), 4 bell crank "Winkelhebel" (DSD slider,
pivoted in the ground at B0, with the second arm FGP to D), 5/6 the SDS
sliders (slider 1 = C on the horizontal ground guide through C0, slider 2 on
a guide fixed to the bell-crank arm at D), 7/8 the SSD sliders (slider 1 = E
on the same ground guide, slider 2 pivoted at D).  Degree of freedom
3 (8 - 1) - 2 * 10 = 1.

Values from Anhang C (Tabelle C.1), converted to SI (mm -> m, g -> kg,
kg mm² -> kg m²):

* dAN1: P1 = (98, 24) mm (x10, y10, frame relative = global since
  unconnected), lL = 18 mm, phiL0 = 0, omL0 = 0, mL = 11.838905 g,
  JL = 0.91942937 kg mm², xSLrel = 6.6176566 mm, ySLrel = 0.
* preset1: speed 1.5 rad/s, phi0 = 0 (fixed).
* dSD1: y10 = 0, P2 = (50, 30) mm (x20, y20; ground pivot B0), off = v =
  -10 mm, mS = 112.33331 g, JS = 75.986105 kg mm², xSSrel = -27.015926 mm,
  ySSrel = 13.750918 mm, xSUrel = ySUrel = 0.
* fGP2: phi10 = -125°, lL (lU) = 50 mm, massless, x10 = y10 = 0.
* sDS1: y10 = 105 mm, phi10 = 0 (horizontal ground guide), phi20 = -95°
  (guide 2 against the bell-crank arm; the cell reads "-05"/"95"), x20 = y20
  = 0 at D, off1 = v1 = -35 mm, mS2 = 17.646559 g, JS2 = 2.483826 kg mm²,
  xSS2rel = -8.4422094 mm, ySS2rel = 8.1920228 mm, mS1 = 26.039372 g (unit
  cell empty, read as g).
* sSD1: y10 = 105 mm, phi10 = 0, off1 = v1 = -10 mm, off2 = v2 = -8 mm,
  offphi = phiv = -50°, mS1 = 36.058114 g, JS1 = 11.425901 kg mm² (units read
  as g, kg mm²), mS2 = 1.8954624 g, JS2 = 0.014961276 kg mm², ySS2rel = 0.

Values CHOSEN here because the figure (Bild 7.2) is lost and the cells are
empty:

* dSD1: P1 connected to the crank pin A (ctr2D1 <- dAN1.ctr2D2) with x10 = 0;
  P2 unconnected (ground pivot B0).
* The mass data of the guide U of dSD1 (the slotted coupler, link 3): the
  dissertation's printout (Anhang C, dSD1) leaves mU empty and gives JU = 0.1 kg m²
  with xSURel = ySURel = 0 [m] -- the element's default values (Tabelle
  B.11: m = 1 kg, J = 0.1 kg m²), in SI units where every other mass datum
  of the table is in g, kg mm² and mm: these cells were not filled from
  the Creo reference model.  Taken literally, JU = 0.1 kg m² is 1300 times
  the bell crank's inertia and 94 % (rms) of the drive power is the power
  of this one inertia torque (A.31), against which the dissertation's comparison
  with the reference model (Bild 7.6, lost) could not have agreed unless
  the reference had the same default.  Assumed here instead: the guide is
  a 20 g bar of 80 mm (longer than the largest distance A - B0 of 66 mm)
  with JU = mU (80 mm)²/12 = 10.7 kg mm² about its centre of gravity, at
  A as printed (``GUIDE_M``, ``GUIDE_L``).  What follows: the drive
  torque is -0.025 .. 0.013 N m (with the printed JU -0.083 .. 0.051 N m),
  mainly lifting the links against gravity: at 1.5 rad/s the power of all
  inertia forces and torques (``P_T<key>``, ``P_R<key>`` of the elements)
  is below 1 % (rms) of the drive power, the guide's own 0.02 %.
* fGP2 sits on the bell crank: fGP2.ctr2D1 <- dSD1.ctr2D4 (slider plane at B0).
* sDS1: x10 = 0 (C0 = (0, 105) mm); guide 2 on the arm end D
  (sDS1.ctr2D2 <- fGP2.ctr2D2); off2 = v2 = 0; JS1 = 2.0 kg mm²;
  xSS1rel = 0, ySS1rel = -17.5 mm (half way down to P).
* sSD1: x10 = 0 (same ground guide as C); slider 2 pivoted at D
  (sSD1.ctr2D2 <- fGP2.ctr2D2); xSS1rel = 0, ySS1rel = -5 mm, xSS2rel = 0.
* Force-driven variant: flywheel J = 0.05 kg m² on the crank, constant
  drive torque 0 (free run from 1.5 rad/s), start angle 0.
* Gravity (0, -9.81) m/s².

Outputs: relative slider travel C0-C (``relC0C.s_rel``) and E-C
(``relEC.s_rel``), drive torque ``preset1.tau`` and power ``preset1.power``
over the crank angle ``dAN1.phiL`` for one revolution (T = 2 pi / 1.5 s).
``acausal2d simulate models/eight_link_vdi2729.py`` plots the slider travels
and the drive torque over the crank angle (the model's ``figures``);
``acausal2d study models/eight_link_vdi2729.py`` runs the force-driven
variant over one period (running the file does both, into ./out).
"""
import math

from acausal2d import Component, simulate, start, study
from acausal2d.library.linkage import DAN, DSD, FGP, SDS, SSD
from acausal2d.library.linkage.drives import Preset, RelativePosition, TorqueSource
from acausal2d.library.planar import Fixed
from acausal2d.library.rotational import Inertia

MM, G, KGMM2 = 1e-3, 1e-3, 1e-6
OMEGA = 1.5
PERIOD = 2 * math.pi / OMEGA
GUIDE_M = 0.020               # kg, mass of the dSD1 guide (assumed, see above)
GUIDE_L = 0.080               # m, length of the dSD1 guide bar (assumed)


class EightLinkVDI2729(Component):
    """8-link mechanism of VDI 2729 example 2 with masses and gravity.

    ``drive='kinematic'`` (default): ``preset1`` turns the crank at 1.5 rad/s
    (kinematic analysis; drive torque ``preset1.tau``).  ``drive='force'``:
    a torque source and a flywheel on the crank, started at 1.5 rad/s
    (dynamic analysis of the same mechanism)."""
    experiment = {"stop_time": PERIOD, "intervals": 360, "rtol": 1e-8}
    outputs = ["dAN1.phiL", "relC0C.s_rel", "relEC.s_rel", "preset1.tau", "preset1.power"]
    figures = [{"name": "slider_travels", "x": "dAN1.phiL", "title": "slider travels",
                "signals": ["relC0C.s_rel", "relEC.s_rel"]},
               {"name": "drive", "x": "dAN1.phiL", "title": "drive torque and power",
                "signals": ["preset1.tau", "preset1.power"]}]

    @study
    def force_driven(ctx):
        """The mechanism driven by a torque on a flywheel instead of the
        prescribed crank motion, over one period."""
        res = simulate(EightLinkVDI2729(drive="force"), stop_time=PERIOD)
        ctx.note("force-driven: crank angle after %.3f s = %.4f rad (speed %.4f rad/s)"
                 % (PERIOD, res.final("dAN1.phiL"), res.final("dAN1.omL")))
        ctx.save(res, "eight_link_force_driven")

    def __init__(self, drive="kinematic", flywheel_J=0.05, torque=0.0, **kw):
        super().__init__(**kw)
        if drive == "kinematic":
            self.dAN1 = DAN(x10=98 * MM, y10=24 * MM, lL=18 * MM, phiL0=0.0, omL0=0.0,
                            mL=11.838905 * G, JL=0.91942937 * KGMM2,
                            xSLrel=6.6176566 * MM, ySLrel=0.0)
            self.preset1 = Preset(kind="speed", om=OMEGA, phi0=0.0)
            self.connect(self.preset1.flange, self.dAN1.ctrR2)
        elif drive == "force":
            self.dAN1 = DAN(x10=98 * MM, y10=24 * MM, lL=18 * MM, phiL0=0.0, omL0=OMEGA,
                            mL=11.838905 * G, JL=0.91942937 * KGMM2,
                            xSLrel=6.6176566 * MM, ySLrel=0.0,
                            phiL=start(fixed=True), omL=start(fixed=True))
            self.flywheel = Inertia(J=flywheel_J)
            self.motor = TorqueSource(tau=torque)
            self.connect(self.dAN1.ctrR2, self.flywheel.flange_a)
            self.connect(self.flywheel.flange_b, self.motor.flange)
        else:
            raise ValueError("drive must be 'kinematic' or 'force'")
        self.dSD1 = DSD(x10=0.0, y10=0.0, x20=50 * MM, y20=30 * MM, v=-10 * MM,
                        mU=GUIDE_M, JU=GUIDE_M * GUIDE_L ** 2 / 12, xSUrel=0.0, ySUrel=0.0,
                        mS=112.33331 * G, JS=75.986105 * KGMM2,
                        xSSrel=-27.015926 * MM, ySSrel=13.750918 * MM)
        self.fGP2 = FGP(phi10=math.radians(-125.0), lL=50 * MM, mL=0.0, JL=0.0)
        self.sDS1 = SDS(x10=0.0, y10=105 * MM, phi10=0.0,
                        x20=0.0, y20=0.0, phi20=math.radians(-95.0),
                        v1=-35 * MM, v2=0.0,
                        mS1=26.039372 * G, JS1=2.0 * KGMM2, xSS1rel=0.0, ySS1rel=-17.5 * MM,
                        mS2=17.646559 * G, JS2=2.483826 * KGMM2,
                        xSS2rel=-8.4422094 * MM, ySS2rel=8.1920228 * MM)
        self.sSD1 = SSD(x10=0.0, y10=105 * MM, phi10=0.0,
                        v1=-10 * MM, v2=-8 * MM, phiv=math.radians(-50.0),
                        mS1=36.058114 * G, JS1=11.425901 * KGMM2, xSS1rel=0.0,
                        ySS1rel=-5 * MM, mS2=1.8954624 * G, JS2=0.014961276 * KGMM2,
                        xSS2rel=0.0, ySS2rel=0.0)
        self.C0 = Fixed(r=(0.0, 105 * MM))
        self.relC0C = RelativePosition()
        self.relEC = RelativePosition()
        self.connect(self.dAN1.ctr2D2, self.dSD1.ctr2D1)
        self.connect(self.dSD1.ctr2D4, self.fGP2.ctr2D1)
        self.connect(self.fGP2.ctr2D2, self.sDS1.ctr2D2)
        self.connect(self.fGP2.ctr2D2, self.sSD1.ctr2D2)
        self.connect(self.C0.frame, self.relC0C.ctr2D1)
        self.connect(self.sDS1.ctr2D3, self.relC0C.ctr2D2)
        self.connect(self.sDS1.ctr2D3, self.relEC.ctr2D1)
        self.connect(self.sSD1.ctr2D3, self.relEC.ctr2D2)


# bodies with mass: (element, mass param, inertia param, xS, yS, angle) - for energy checks
BODIES = [
    ("dAN1", "mL", "JL", "xSL", "ySL", "phiL"),
    ("dSD1", "mU", "JU", "xSU", "ySU", "phiU"),
    ("dSD1", "mS", "JS", "xSS", "ySS", "phiU"),
    ("fGP2", "mL", "JL", "xSL", "ySL", "phiL"),
    ("sDS1", "mS1", "JS1", "xSS1", "ySS1", "phiS1"),
    ("sDS1", "mS2", "JS2", "xSS2", "ySS2", "phiS2"),
    ("sSD1", "mS1", "JS1", "xSS1", "ySS1", "phiS1"),
    ("sSD1", "mS2", "JS2", "xSS2", "ySS2", "phiS2"),
]
"""Every body of the mechanism: element name, mass and inertia parameter
names, centre-of-gravity and angle variable names."""


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
