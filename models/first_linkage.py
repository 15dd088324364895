"""First models: a four-bar linkage from VDI 2729 elements.

A crank (DAN, 100 mm) turns once per second about A0 = (0, 0); a dyad with
three revolute joints (DDD: coupler 350 mm, rocker 300 mm) closes the loop
to the rocker's pivot B0 = (0.4, 0).  The shortest link is the crank and
100 + 400 < 350 + 300 (Grashof): the crank turns fully round and the
rocker swings.  By hand: the rocker's extreme positions are where crank and
coupler lie on one line, 450 mm and 250 mm from A0, so by the cosine law the
rocker swings through 39.9 degrees.  The page "A linkage from VDI elements"
of the documentation builds this file step by step.
"""
import math

from acausal2d import Component
from acausal2d.library.linkage import DAN, DDD
from acausal2d.library.linkage.drives import Preset

# -- step 1: the numbers
CRANK = 0.10        # crank A0 -> A, m
COUPLER = 0.35      # coupler A -> B, m
ROCKER = 0.30       # rocker B0 -> B, m
B0 = (0.40, 0.0)    # rocker pivot, m (A0 at the origin)
SPEED = 2 * math.pi  # crank speed, rad/s: one turn per second
# -- end step 1


class FourBar(Component):
    """Crank-rocker four-bar: DAN crank driven at one turn per second, DDD
    dyad with its second pivot at B0."""
    experiment = {"stop_time": 1.0, "intervals": 1000, "rtol": 1e-10}
    outputs = ["crank.phiL", "dyad.phiL2"]
    figures = [{"name": "first_linkage", "title": "four-bar: rocker angle over the crank angle",
                "x": "crank.phiL", "signals": [["dyad.phiL2"]]}]

    def __init__(self, **kw):
        super().__init__(**kw)
        # -- step 2: the crank; its housing ctr2D1, left unconnected, is the ground at A0
        self.crank = DAN(lL=CRANK, mL=0.5, JL=1e-3)
        # -- step 3: the drive: a motion preset on the crank's flange ctrR2
        self.preset = Preset(kind="speed", om=SPEED, phi0=0.0)
        self.connect(self.preset.flange, self.crank.ctrR2)
        # -- step 4: the dyad: link 1 (coupler) from the crank pin, link 2 (rocker) from B0;
        # K = +1: the joint B lies left of the line A -> B0 (above the ground line) at the start
        self.dyad = DDD(lL1=COUPLER, lL2=ROCKER, x20=B0[0], y20=B0[1], K=1)
        self.connect(self.crank.ctr2D2, self.dyad.ctr2D1)
        # -- end step 4


def rocker_limits():
    """The rocker's two extreme angles by the cosine law: B at CRANK + COUPLER
    (stretched) and COUPLER - CRANK (folded) from A0."""
    d = math.hypot(*B0)
    angles = []
    for reach in (COUPLER + CRANK, COUPLER - CRANK):
        at_b0 = math.acos((d ** 2 + ROCKER ** 2 - reach ** 2) / (2 * d * ROCKER))
        angles.append(math.pi - at_b0)      # the rocker points up and back towards A0
    return angles


def hand_check():
    """By hand: {quantity: value}."""
    stretched, folded = rocker_limits()
    # stretched, B is farther from A0: the rocker leans less far back, its angle is smaller
    return {"rocker max": folded, "rocker min": stretched, "swing": folded - stretched}


def measure(res):
    """The same quantities from a result of :class:`FourBar`."""
    phi = res["dyad.phiL2"]
    return {"rocker max": float(phi.max()), "rocker min": float(phi.min()),
            "swing": float(phi.max() - phi.min())}


if __name__ == "__main__":
    import acausal2d
    simulated = measure(acausal2d.simulate(FourBar()))
    for name, value in hand_check().items():
        print("%-10s simulated %10.6f rad   by hand %10.6f rad (%.2f deg)"
              % (name, simulated[name], value, math.degrees(value)))
