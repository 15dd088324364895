"""Belt-span test rig: one span of the compressor's V-belt (models/compressor.py,
Ebert (2015), ch. 8.2) clamped at one end and stretched periodically at the other, for
identifying the span's stiffness c and damping d from its force curve.

The compressor's span forces (Bild 8.9) oscillate about the pretension with
the crank's torque pulses; the rig reproduces that load on one span alone
(the whole compressor takes seconds per run, the rig milliseconds): the
span (0.40 m, pretension strain 500 N / c) is anchored at (0, 0) and its
other end is moved along the span by

    s(t) = A (sin(w t) + 0.3 sin(2 w t)),   A = 0.6 mm, w = 50 rad/s

(the crank's speed of the running compressor, 157 rad/s / ratio 3), so the
span force is ``F = c eps + d der(eps)`` (eq. 4.58-4.62) with the strain
``eps`` following the end's travel: the damping term, 90 degrees out of
phase, separates d from c.

``models/belt_span_rig_measured.csv`` holds the span force ``span.F`` of
this rig at the compressor's values c = 1.5e5 N, d = 150 N s (per unit
strain) at 201 times over 0.5 s plus Gaussian noise of 3 N (numpy
``default_rng(2026)``), written by :func:`write_measured`.

    acausal2d fit models/belt_span_rig.py --data models/belt_span_rig_measured.csv \\
        --free span.c=1e5:1e4:1e6 --free span.d=50:0:1000 --out out/fit_span
"""
import os

import casadi as ca
import numpy as np

from acausal2d import Component, start
from acausal2d.library.belt import Belt, RopeDrive
from acausal2d.library.planar import Fixed
from acausal2d.library.signals import TimeFunction

LENGTH = 0.40
C_TRUE, D_TRUE = 1.5e5, 150.0
AMPLITUDE, OMEGA = 0.6e-3, 50.0
NOISE, SEED = 3.0, 2026
MEASURED = os.path.join(os.path.dirname(os.path.abspath(__file__)), "belt_span_rig_measured.csv")


def stretch(t):
    """Travel of the moving span end [m] (module docstring); CasADi or numbers."""
    return AMPLITUDE * (ca.sin(OMEGA * t) + 0.3 * ca.sin(2 * OMEGA * t))


class BeltSpanRig(Component):
    """One belt span between an anchor and a driven end (module docstring)."""
    experiment = {"stop_time": 0.5, "intervals": 200, "rtol": 1e-8}
    outputs = ["span.F"]

    def __init__(self, **kw):
        super().__init__(**kw)
        self.anchor = Fixed(r=(0.0, 0.0))
        self.span = Belt(c=C_TRUE, d=D_TRUE, eps=start(500.0 / C_TRUE, fixed=True))
        self.end = RopeDrive(x0=LENGTH, y0=0.0, angle=0.0)
        self.travel = TimeFunction(stretch)
        self.connect(self.travel.y, self.end.s_in)
        self.connect(self.anchor.frame, self.span.ctr2D1)
        self.connect(self.end.frame, self.span.ctr2D2)


def write_measured(path=MEASURED):
    """Simulate the rig at the true values, add the noise and write the CSV."""
    from acausal2d import simulate
    t = np.linspace(0.0, 0.5, 201)
    res = simulate(BeltSpanRig(), output_times=t)
    rng = np.random.default_rng(SEED)
    force = res["span.F"] + rng.normal(0.0, NOISE, t.size)
    np.savetxt(path, np.column_stack([t, force]), delimiter=",", header="time,span.F",
               comments="", fmt="%.10g")
    return path


if __name__ == "__main__":
    import sys

    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
