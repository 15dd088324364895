"""Issue 32: Anhang A.1 placement of output ports (the point frames PCSn of
Anhang C) of the linkage elements DAN and DDD: x_n0, y_n0, phi_n0 are the
offset of the element's point Pn in the port's connection frame (A.7-A.9
with the connection frame as the unknown), the port forces pass by
A.16-A.18."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component, ModelDefinitionError
from acausal2d.library.linkage import DAN, DDD
from acausal2d.library.linkage.drives import Preset
from acausal2d.library.planar import Body

G = 9.81
RTOL = 1e-9
L, OM, PHI0 = 0.2, 2.0, 0.3
REL = (0.05, 0.03, 0.4)            # x20, y20, phi20


class CrankWithOffsetPort(Component):
    """A massless crank (DAN, lL = 0.2 m, housing at the origin) turned at
    2 rad/s carries a 1.5 kg body (I = 0.02 kg m^2) on its output port
    ctr2D2, placed with the offset (x20, y20, phi20) = REL."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.drive = Preset(kind="speed", om=OM, phi0=PHI0)
        self.crank = DAN(lL=L, mL=0.0, JL=0.0, x20=REL[0], y20=REL[1], phi20=REL[2])
        self.connect(self.drive.flange, self.crank.ctrR2)
        self.body = Body(m=1.5, I=0.02)
        self.connect(self.crank.ctr2D2, self.body.frame_a)


def test_output_port_follows_A7_A9_and_carries_the_load_by_A18():
    """Connection frame C = P - R(phi_C) (x20, y20), phi_C = phiL - phi20
    (A.7-A.9 solved for C, P = lL e(phiL)); at constant speed the body
    moves on a circle about the origin, so the drive torque is its weight
    moment m g x_C (power balance m g vy = tau om).  Prescribed motion:
    positions and torque hold to the rows' tolerance (bounds 1e3 rtol)."""
    t = np.linspace(0.0, 1.0, 21)
    res = acausal2d.simulate(CrankWithOffsetPort(), stop_time=1.0, rtol=RTOL, output_times=t)
    phi = PHI0 + OM * res.time
    phic = phi - REL[2]
    cx = L * np.cos(phi) - (np.cos(phic) * REL[0] - np.sin(phic) * REL[1])
    cy = L * np.sin(phi) - (np.sin(phic) * REL[0] + np.cos(phic) * REL[1])
    assert np.max(np.abs(res["body.x"] - cx)) < 1e3 * RTOL * L
    assert np.max(np.abs(res["body.y"] - cy)) < 1e3 * RTOL * L
    assert np.max(np.abs(res["body.phi"] - phic)) < 1e3 * RTOL
    tau = 1.5 * G * cx
    assert np.max(np.abs(res["drive.tau"] - tau)) < 1e3 * RTOL * 1.5 * G * L


def test_ddd_output_ports_are_placed_and_global_is_refused():
    """DDD's link planes ctr2D3/ctr2D4 take the same offsets; 'global' has
    no meaning for a point the element computes and is refused by name."""
    with pytest.raises(ModelDefinitionError, match="frameRef3 of the output port ctr2D3 must "
                                                   "be 'relative'"):
        DDD(frameRef3="global")
    d = DDD(lL1=0.3, lL2=0.3, x20=0.4, x30=0.1, phi40=math.pi / 2)
    assert d._output_offset(3) is not None and d._output_offset(4) is not None
    assert DAN()._output_offset(2) is None          # zero offset: the port is the point
