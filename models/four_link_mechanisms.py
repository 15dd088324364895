"""The nine four-link mechanisms of Ebert (2015), Bild 2.2 (ch. 2.4), each built from
the VDI 2729 linkage elements (library/linkage.py) and driven at constant
speed by a motion preset: a crank turning once per second, or a slider
moving through its full stroke in one second.

==========  ===================================  ===========================
mechanism   name (Ebert 2015, ch. 2.4)                  elements
==========  ===================================  ===========================
DDDD(a)     four-bar (crank-rocker)              DAN + DDD
DDDS(a)     slider-crank (Schubkurbel)           DAN + DDS (guide on ground)
SDDD(a)     slider-rocker (Schubschwinge)        SAN + DDD
DDSD(b)     swinging crank-slider                DAN + DSD (guide pivot on
            (Kurbelschleife)                     ground, slider on the crank)
DSDD(b)     crank with guide (Kurbelschleife)    DAN + DDS (guide on the crank)
SDDS(a)     double slider (Doppelschieber)       SAN + DDS
SSDD(b)     Scotch yoke (Kreuzschubkurbel)       DAN + SSD (guide 1 on ground)
DSSD(c)     double slot (Doppelschleife)         DAN + SSD (guide 1 on crank)
DSDS(a)     slotted slider (Schubschleife)       SAN + DSD
==========  ===================================  ===========================

The DSDS(a) chain is driven at its slider: driven at the crank, its two
straight guides become parallel twice per turn (no full revolution exists).
All dimensions are in metres; masses keep the element defaults, gravity acts.
``acausal2d simulate models/four_link_mechanisms.py --model DDDS`` simulates
one of them; running the file simulates all nine into ./out/<name>.
"""
import math

from acausal2d import Component
from acausal2d.library.linkage import DAN, DDD, DDS, DSD, SAN, SSD
from acausal2d.library.linkage.drives import Preset

TWO_PI = 2.0 * math.pi


class _CrankDriven(Component):
    """Base: crank DAN (A0 at the origin, length 0.1 m) driven by a preset at
    one revolution per second."""
    experiment = {"stop_time": 1.0, "intervals": 200, "rtol": 1e-8}

    def __init__(self, **kw):
        super().__init__(**kw)
        self.preset = Preset(kind="speed", om=TWO_PI, phi0=0.0)
        self.crank = DAN(lL=0.1, mL=0.5, JL=1e-3)
        self.connect(self.preset.flange, self.crank.ctrR2)


class _SliderDriven(Component):
    """Base: linear drive SAN on a horizontal ground guide through the
    origin, its travel running from ``s0`` to ``s0 + stroke`` in one second."""
    experiment = {"stop_time": 1.0, "intervals": 200, "rtol": 1e-8}
    s0, stroke = 0.0, 0.2

    def __init__(self, **kw):
        super().__init__(**kw)
        self.preset = Preset(kind="speed", translational=True, om=self.stroke, phi0=self.s0)
        self.slider = SAN(mS=0.5, JS=1e-3)
        self.connect(self.preset.flange, self.slider.ctrT2)


class DDDD(_CrankDriven):
    """DDDD(a) four-bar crank-rocker: crank 0.1, coupler 0.35, rocker 0.3,
    ground B0 = (0.4, 0); K = +1.  Output: rocker angle ``dyad.phiL2``."""
    outputs = ["crank.phiL", "dyad.phiL2"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.dyad = DDD(lL1=0.35, lL2=0.3, x20=0.4, y20=0.0, K=1)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)


class DDDS(_CrankDriven):
    """DDDS(a) offset slider-crank: crank 0.1, coupler 0.35, horizontal
    guide through (0, -0.02), pin offset v = 0.02 (pin on the axis y = 0);
    K = +1.  Output: slider travel ``dyad.xG``."""
    outputs = ["crank.phiL", "dyad.xG"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.dyad = DDS(lL=0.35, v=0.02, x20=0.0, y20=-0.02, phi20=0.0, K=1)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)


class SDDD(_SliderDriven):
    """SDDD(a) slider-rocker: the slider point runs from x = 0 to 0.2 on the
    x-axis; coupler 0.25 to a rocker 0.15 about B0 = (0.1, 0.25); K = -1.
    Output: rocker angle ``dyad.phiL2``."""
    outputs = ["slider.xG", "dyad.phiL2"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.dyad = DDD(lL1=0.25, lL2=0.15, x20=0.1, y20=0.25, K=-1)
        self.connect(self.slider.ctr2D2, self.dyad.ctr2D1)


class DDSD(_CrankDriven):
    """DDSD(b) swinging crank-slider (Kurbelschleife): the guide turns about
    B0 = (-0.25, 0), the slider turns on the crank pin at offset v = 0.02.
    Output: guide angle ``dyad.phiU``."""
    outputs = ["crank.phiL", "dyad.phiU", "dyad.xG"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.dyad = DSD(v=0.02, x10=-0.25, y10=0.0)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D2)


class DSDD(_CrankDriven):
    """DSDD(b): the crank carries a straight guide along itself (through A0);
    a slider on it is pinned to a link of 0.4 turning about B0 = (0.3, 0.1);
    K = +1.  Output: link angle ``dyad.phiL``."""
    outputs = ["crank.phiL", "dyad.phiL", "dyad.xG"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.dyad = DDS(lL=0.4, v=0.0, x10=0.3, y10=0.1, x20=0.0, y20=0.0, phi20=0.0, K=1)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D2)


class SDDS(_SliderDriven):
    """SDDS(a) double slider (elliptic trammel): slider 1 on the x-axis runs
    from -0.2 to 0.2, a link of 0.3 joins it to slider 2 on the y-axis; K =
    +1 (upper branch).  Output: travel of slider 2 ``dyad.xG``."""
    outputs = ["slider.xG", "dyad.xG"]
    s0, stroke = -0.2, 0.4

    def __init__(self, **kw):
        super().__init__(**kw)
        self.dyad = DDS(lL=0.3, v=0.0, x20=0.0, y20=0.0, phi20=math.pi / 2, K=1)
        self.connect(self.slider.ctr2D2, self.dyad.ctr2D1)


class SSDD(_CrankDriven):
    """SSDD(b)/DDSS(b) Scotch yoke (Kreuzschubkurbel): the yoke slides on a
    horizontal ground guide through (-0.3, 0); its slot (phiv = 90°, offset
    v1 = 0.05) carries the block turning on the crank pin.  Output: yoke
    travel ``dyad.xG1``."""
    outputs = ["crank.phiL", "dyad.xG1", "dyad.xG2"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.dyad = SSD(v1=0.05, v2=0.0, phiv=math.pi / 2, x10=-0.3, y10=0.0, phi10=0.0)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D2)


class DSSD(_CrankDriven):
    """DSSD(c) double slot (Doppelschleife): a cross block slides on a guide
    along the crank and on a perpendicular guide of a second link that turns
    about B0 = (0.05, 0.02); the output link turns with the crank (+90°).
    Outputs: travels ``dyad.xG1``, ``dyad.xG2``."""
    outputs = ["crank.phiL", "dyad.xG1", "dyad.xG2", "dyad.phiS2"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.dyad = SSD(v1=0.0, v2=0.0, phiv=math.pi / 2, x10=0.0, y10=0.0, phi10=0.0,
                        x20=0.05, y20=0.02)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)


class DSDS(_SliderDriven):
    """DSDS(a) slotted slider (Schubschleife) driven at its slider: the
    slider point runs from x = -0.2 to 0.2 on the x-axis; a guide turning
    about A0 = (0, 0.15) carries a block pinned to the slider (v = 0).
    Output: guide angle ``dyad.phiU``."""
    outputs = ["slider.xG", "dyad.phiU", "dyad.xG"]
    s0, stroke = -0.2, 0.4

    def __init__(self, **kw):
        super().__init__(**kw)
        self.dyad = DSD(v=0.0, x10=0.0, y10=0.15)
        self.connect(self.slider.ctr2D2, self.dyad.ctr2D2)


MECHANISMS = [DDDD, DDDS, SDDD, DDSD, DSDD, SDDS, SSDD, DSSD, DSDS]
"""All nine mechanisms of Bild 2.2."""


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(max(run_model_file(__file__, cls.__name__, "out/" + cls.__name__)
                 for cls in MECHANISMS))
