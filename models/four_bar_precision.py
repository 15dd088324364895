"""Four-bar precision-point synthesis: link lengths chosen so that the
coupler curve passes through given points (Ebert 2015, ch. 2, the DDDD four-bar
of models/four_link_mechanisms.py with a coupler point).

The crank (A0 at the origin) turns once per second (crank angle 2 pi t);
the dyad DDD joins the coupler (A -> B) and the rocker (B0 -> B, B0 at
(0.4, 0)); the coupler point C sits on the coupler at 0.2 m from A, 30 deg
to the left of A -> B (an FGP on the coupler's plane).  Its path is
``coupler.ctr2D2.x``, ``coupler.ctr2D2.y``.

``models/four_bar_precision_points.csv`` holds six precision points: the
coupler point at the crank angles 0, 60, ..., 300 deg (t = k/6 s) of the
four-bar with crank 0.1 m, coupler 0.35 m, rocker 0.3 m (written by
:func:`write_points`).  The model file starts from other lengths (crank
0.11, coupler 0.33, rocker 0.32 m); ``acausal2d fit`` finds the lengths
that pass the points (a least-squares synthesis with zero residual):

    acausal2d fit models/four_bar_precision.py \\
        --data models/four_bar_precision_points.csv \\
        --free crank.lL=0.11:0.05:0.2 --free dyad.lL1=0.33:0.2:0.5 \\
        --free dyad.lL2=0.32:0.2:0.5 --out out/four_bar
"""
import math
import os

import numpy as np

from acausal2d import Component
from acausal2d.library.linkage import DAN, DDD, FGP
from acausal2d.library.linkage.drives import Preset

TRUE = {"crank.lL": 0.10, "dyad.lL1": 0.35, "dyad.lL2": 0.30}
POINTS = os.path.join(os.path.dirname(os.path.abspath(__file__)),
                      "four_bar_precision_points.csv")


class FourBarPrecision(Component):
    """Crank-rocker four-bar with a coupler point (module docstring)."""
    experiment = {"stop_time": 1.0, "intervals": 120, "rtol": 1e-8}
    outputs = ["coupler.ctr2D2.x", "coupler.ctr2D2.y"]
    figures = [{"name": "coupler_curve", "title": "coupler curve",
                "signals": ["coupler.ctr2D2.y"], "x": "coupler.ctr2D2.x"}]

    def __init__(self, crank=0.11, coupler=0.33, rocker=0.32, **kw):
        super().__init__(**kw)
        self.preset = Preset(kind="speed", om=2 * math.pi, phi0=0.0)
        self.crank = DAN(lL=crank, mL=0.5, JL=1e-3)
        self.connect(self.preset.flange, self.crank.ctrR2)
        self.dyad = DDD(lL1=coupler, lL2=rocker, x20=0.4, y20=0.0, K=1)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)
        self.coupler = FGP(lL=0.2, phi10=math.radians(30.0), mL=0.0, JL=0.0)
        self.connect(self.dyad.ctr2D3, self.coupler.ctr2D1)


def write_points(path=POINTS):
    """The coupler point of the TRUE four-bar at t = k/6 s, as CSV."""
    from acausal2d import simulate
    t = np.arange(6) / 6.0
    res = simulate(FourBarPrecision(TRUE["crank.lL"], TRUE["dyad.lL1"], TRUE["dyad.lL2"]),
                   output_times=np.union1d(t, [1.0]))
    x = np.interp(t, res.time, res["coupler.ctr2D2.x"])
    y = np.interp(t, res.time, res["coupler.ctr2D2.y"])
    np.savetxt(path, np.column_stack([t, x, y]), delimiter=",", comments="", fmt="%.15g",
               header="time,coupler.ctr2D2.x,coupler.ctr2D2.y")
    return path


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
