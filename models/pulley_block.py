"""Pulley block with bearing friction (Ebert 2015, ch. 7.3.1, Bild 7.21-7.24).

An upper block with two pulleys fixed in the ground (U1 large, U3 small), a
lower block with two pulleys (L2 large, L4 small) carried by one free body
with the 100 kg load, and one rope reeved alternately between the blocks:

    pull end --(1)-- U1 --(2)-- L2 --(3)-- U3 --(4)-- L4 --(5)-- upper block

Sections 2..5 carry the load, so without friction every section carries
m g / 4 and the rope travel is four times the load travel.  The rope end of
section 1 is pulled downwards by a smooth drive function (cosine velocity
ramps, constant speed in between); section 5 is fastened to the upper block.

Values the dissertation does not give (Bild 7.22 is lost) and that were chosen here:

- pulley radii: U1, L2 60 mm and 50 mm ("large"), U3, L4 40 mm and 30 mm
  ("small"); the pulleys of one block sit side by side (a planar stand-in
  for the violin arrangement) at x = 0 (U1), 0.20 m (U3), y = 0, and
  0.11 m (L2), 0.27 m (L4), y = -1.5 m, so that every section hangs
  vertically and every pulley is wrapped by exactly 180 degrees;
- pulleys massless with J = 1e-5 kg m^2; bearing pins 8 mm diameter
  (r_pin = 4 mm), mu = 0.25 (values of Ebert 2015), friction sign regularised with
  omega_s = 1e-3 rad/s (library/belt.py);
- rope: stiffness c = 2e6 N per unit strain (steel wire rope, about 6 mm),
  damping d = 2e4 N s per unit strain (the load mode is about critically
  damped); all sections start in the static equilibrium without friction
  (strain m g / (4 c));
- lower block: body of 100 kg, I = 2 kg m^2, centre of gravity 0.3 m below
  the pulley axes at x = 0.19 m (under the resultant of sections 2..5);
  its start position is fixed (``fixed=True``) so that the initialization
  does not move it;
- drive: the pull end (x = -0.06 m, y = -1 m at t = 0) moves down with
  V = 0.2 m/s, velocity ramps of 1 s (cosine), constant speed from 1 s to
  4 s, at rest from 5 s; the quasi-static phase is about 2 s .. 4 s.

Quasi-static section forces with bearing friction: every pulley is wrapped
by 180 degrees with parallel sections, so its bearing force is
T_in + T_out and the moment balance r (T_in - T_out) = mu r_pin (T_in +
T_out) gives T_out = T_in (r - mu r_pin) / (r + mu r_pin).  With
k_i = (r_i - mu r_pin)/(r_i + mu r_pin) the sections carry T1, T2 = k1 T1,
T3 = k2 T2, T4 = k3 T3, T5 = k4 T4, and T2 + T3 + T4 + T5 = m g.  The
efficiency is eta = m g / (4 T1) and the rope utilisation T5 / T1.

``acausal2d simulate models/pulley_block.py`` plots the section forces
(Bild 7.23); ``acausal2d study models/pulley_block.py`` runs the efficiency
sweep over mu (Bild 7.24) on Dask and compares it with the closed form
(running the file does both, into ./out).
"""
import math
import sys

import casadi as ca
import numpy as np

from acausal2d import Component, start, study
from acausal2d.library.belt import Belt, Pulley, RopeDrive, connect_band
from acausal2d.library.planar import Body, Fixed, FixedTranslation
from acausal2d.library.signals import TimeFunction

G = 9.81
MASS = 100.0
C_ROPE = 2e6
RADII = {"U1": 0.06, "L2": 0.05, "U3": 0.04, "L4": 0.03}
PULLEYS = ("U1", "L2", "U3", "L4")


def drive_profile(t, V=0.2, Ta=1.0, Tc=4.0):
    """Pull travel s(t) [m]: cosine velocity ramp over [0, Ta], constant speed
    V until Tc, cosine ramp down over [Tc, Tc + Ta], then rest.  ``t`` may be
    a number or the CasADi time symbol."""
    up = V * (t / 2 - Ta / (2 * math.pi) * ca.sin(math.pi * t / Ta))
    s_a = V * Ta / 2
    mid = s_a + V * (t - Ta)
    s_c = s_a + V * (Tc - Ta)
    tau = t - Tc
    down = s_c + V * (tau / 2 + Ta / (2 * math.pi) * ca.sin(math.pi * tau / Ta))
    s_end = s_c + V * Ta / 2
    return ca.if_else(t < Ta, up, ca.if_else(t < Tc, mid, ca.if_else(t < Tc + Ta, down, s_end)))


class PulleyBlock(Component):
    """Pulley block of Ebert (2015), ch. 7.3.1 (see the module docstring).

    ``friction`` adds the bearing friction torque to all four pulleys
    (``mu`` is then a parameter of each pulley, e.g. ``"U1.mu"``).
    Outputs: section forces ``rope1.F`` .. ``rope5.F``, pull force
    ``pull.F``, pull travel ``pull.s_in.u``, load position ``load.y``."""
    experiment = {"stop_time": 6.0, "intervals": 600, "rtol": 1e-8}
    outputs = ["rope1.F", "rope2.F", "rope3.F", "rope4.F", "rope5.F", "pull.F", "load.y"]
    figures = [{"name": "rope_forces", "title": "rope section forces (Bild 7.23)",
                "signals": ["rope1.F", "rope2.F", "rope3.F", "rope4.F", "rope5.F"]},
               {"name": "travel", "title": "pull end and load", "signals": ["pull.s_in.u",
                                                                           "load.y"]}]

    def __init__(self, friction=True, mu=0.25, **kw):
        super().__init__(**kw)
        r = RADII
        yU, yL = 0.0, -1.5
        xU1 = 0.0
        x2 = xU1 + r["U1"]                  # section 2
        xL2 = x2 + r["L2"]
        x3 = xL2 + r["L2"]                  # section 3
        xU3 = x3 + r["U3"]
        x4 = xU3 + r["U3"]                  # section 4
        xL4 = x4 + r["L4"]
        x5 = xL4 + r["L4"]                  # section 5
        xS = (x2 + x3 + x4 + x5) / 4        # centre of gravity under the resultant
        yS = yL - 0.3
        common = dict(J=1e-5, mu=mu, r_pin=0.004, friction=friction)
        # upper block: rope runs over the top, K1 on the left, K2 on the right
        # (w_i = +1: a positive turn pays the rope out at K1, eq. 4.95)
        self.U1 = Pulley(r=r["U1"], x10=xU1, y10=yU, w_i=1, enumHE1="left", enumHE2="right",
                         **common)
        self.U3 = Pulley(r=r["U3"], x10=xU3, y10=yU, w_i=1, enumHE1="left", enumHE2="right",
                         **common)
        # lower block: rope runs under the bottom, K1 left, K2 right; the axes
        # sit on the arms of the load body and start where its start values
        # put them (no coordinates of their own)
        self.L2 = Pulley(r=r["L2"], w_i=-1, enumHE1="left", enumHE2="right", **common)
        self.L4 = Pulley(r=r["L4"], w_i=-1, enumHE1="left", enumHE2="right", **common)
        self.load = Body(m=MASS, I=2.0, x=start(xS, fixed=True), y=start(yS, fixed=True),
                         phi=start(0.0, fixed=True))
        self.arm2 = FixedTranslation(r=(xL2 - xS, yL - yS))
        self.arm4 = FixedTranslation(r=(xL4 - xS, yL - yS))
        self.connect(self.load.frame_a, self.arm2.frame_a)
        self.connect(self.load.frame_a, self.arm4.frame_a)
        self.connect(self.arm2.frame_b, self.L2.ctr2D1)
        self.connect(self.arm4.frame_b, self.L4.ctr2D1)
        eps0 = MASS * G / 4 / C_ROPE
        for k in range(1, 6):
            setattr(self, "rope%d" % k, Belt(c=C_ROPE, d=2e4, eps=start(eps0, fixed=True)))
        self.pull = RopeDrive(x0=xU1 - r["U1"], y0=-1.0, angle=-math.pi / 2)
        self.profile = TimeFunction(drive_profile)
        self.connect(self.profile.y, self.pull.s_in)
        self.anchor = Fixed(r=(x5, yU))
        self.connect(self.pull.frame, self.rope1.ctr2D1)
        for k, name in enumerate(("U1", "L2", "U3", "L4")):   # rope k+1 onto it, k+2 off it
            connect_band(self, getattr(self, "rope%d" % (k + 1)), 2, getattr(self, name), 1)
            connect_band(self, getattr(self, "rope%d" % (k + 2)), 1, getattr(self, name), 2)
        self.connect(self.rope5.ctr2D2, self.anchor.frame)

    @study
    def efficiency(ctx):
        """Efficiency and rope utilisation over the bearing friction mu
        (Bild 7.24), a sweep on Dask, against the closed form."""
        table = ctx.sweep(vary={MU_TIED: "0:0.5:11"}, metrics=efficiency_metrics,
                          stop_time=3.0, intervals=30, rtol=1e-8)
        ctx.save(table, "pulley_block_efficiency")
        mus = table.column(MU_TIED)
        eta, util = table.column("efficiency"), table.column("utilisation")
        ctx.save(efficiency_figure(mus, eta, util), "pulley_block_efficiency")
        for mu, e, u in zip(mus, eta, util):
            T = quasi_static_forces(mu)
            ctx.note("mu = %.2f  efficiency %.4f (closed form %.4f)  utilisation %.4f "
                     "(closed form %.4f)" % (mu, e, MASS * G / (4 * T[0]), u, T[4] / T[0]))


def friction_factor(r, mu, r_pin=0.004):
    """T_out / T_in of a pulley wrapped by 180 degrees (module docstring)."""
    return (r - mu * r_pin) / (r + mu * r_pin)


def quasi_static_forces(mu, m=MASS, g=G):
    """Closed-form quasi-static section forces T1..T5 while lifting."""
    ks = [friction_factor(RADII[p], mu) for p in PULLEYS]
    rel = [1.0]
    for k in ks:
        rel.append(rel[-1] * k)
    T1 = m * g / sum(rel[1:])
    return [T1 * q for q in rel]


def efficiency_metrics(res):
    """Efficiency m g / (4 F1) and rope utilisation F5 / F1 at the end of a
    run (the quasi-static phase; a sweep metric)."""
    F1, F5 = res.final("rope1.F"), res.final("rope5.F")
    return {"efficiency": MASS * G / (4 * F1), "utilisation": F5 / F1}


MU_TIED = ",".join("%s.mu" % p for p in PULLEYS)
"""The four pulleys' friction coefficients, varied together in a sweep."""


def efficiency_sweep(mus=None, png="pulley_block_efficiency.png", compiled=None,
                     t_eval=3.0, **sweep_options):
    """Simulate the pulley block to the quasi-static time ``t_eval`` for
    every mu in ``mus`` (all four pulleys) with :func:`acausal2d.sweep`
    (on Dask; in this process with the CompiledModel ``compiled``) and
    return (mus, efficiency, utilisation) (Bild 7.24).  Writes a PNG plot
    to ``png`` unless it is None."""
    from acausal2d import sweep
    mus = np.linspace(0.0, 0.5, 6) if mus is None else np.asarray(mus, dtype=float)
    table = sweep(compiled or __file__, vary={MU_TIED: mus}, metrics=efficiency_metrics,
                  stop_time=t_eval, intervals=30, rtol=1e-8, model_name="PulleyBlock",
                  **sweep_options)
    if table.failed:
        raise RuntimeError("pulley block sweep: %s" % table.failed[0]["error"])
    eta, util = table.column("efficiency"), table.column("utilisation")
    if png:
        from acausal2d.visual.plotting import save_figure
        save_figure(efficiency_figure(mus, eta, util), png, dpi=100)
    return mus, eta, util


def efficiency_figure(mus, eta, util):
    """Efficiency and rope utilisation over mu, simulated and in closed form
    (Bild 7.24), as a matplotlib Figure (object API)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=(6.5, 4.2))
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    fine = np.linspace(float(mus.min()), float(mus.max()), 101)
    T = np.array([quasi_static_forces(m) for m in fine])
    ax.plot(fine, MASS * G / (4 * T[:, 0]), color="0.6", lw=1, label="closed form")
    ax.plot(fine, T[:, 4] / T[:, 0], color="0.6", lw=1)
    ax.plot(mus, eta, "o-", label="efficiency m g / (4 F1) [-]")
    ax.plot(mus, util, "s-", label="rope utilisation F5 / F1 [-]")
    ax.set_xlabel("bearing friction coefficient mu [-]")
    ax.set_ylabel("[-]")
    ax.set_title("PulleyBlock: efficiency and rope utilisation (Bild 7.24)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
