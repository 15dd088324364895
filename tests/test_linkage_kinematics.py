"""Position solution of every linkage element against the closed-form VDI
2729 module formulas (seed Anhang B), written here again in numpy as an
independent code path, at many drive positions, to 1e-9."""
import math

import numpy as np
import pytest

import acausal2d
from acausal2d import Component
from acausal2d.library.linkage import DAN, DDD, DDS, DSD, FGP, SAN, SDS, SSD
from acausal2d.library.linkage.drives import Preset
from vdi2729_reference import e, line_intersection, n, vdi_dan, vdi_ddd, vdi_dds, vdi_dsd, wrap

TOL = 1e-9
N_OUT = 41


# ------------------------------------------------------------ models
class CrankTest(Component):
    """A constant-speed crank (DAN) driving ``element`` through ``connect``."""

    def __init__(self, element, wire, om=2 * np.pi, lL=0.2, x10=0.05, y10=-0.03, **kw):
        super().__init__(**kw)
        self.preset = Preset(om=om, phi0=0.3)
        self.crank = DAN(lL=lL, x10=x10, y10=y10)
        self.elem = element
        self.connect(self.preset.flange, self.crank.ctrR2)
        wire(self)


def run(model, stop=1.0):
    # rtol 1e-10 keeps the algebraic positions to ~1e-11
    times = np.linspace(0, stop, N_OUT)
    res = acausal2d.simulate(model, stop_time=stop, rtol=1e-10, output_times=times)
    return res


def crank_points(res, lL=0.2, x10=0.05, y10=-0.03):
    phi = res["crank.phiL"]
    return phi, [vdi_dan(np.array([x10, y10]), lL, p) for p in phi]


def test_dan():
    m = CrankTest(FGP(lL=0.1), lambda s: None)
    res = run(m)
    phi, P = crank_points(res)
    assert np.max(np.abs(phi - (0.3 + 2 * np.pi * res.time))) < TOL
    got = np.column_stack([res["crank.ctr2D2.x"], res["crank.ctr2D2.y"]])
    assert np.max(np.abs(got - np.array(P))) < TOL


def test_san():
    class M(Component):
        def __init__(self, **kw):
            super().__init__(**kw)
            self.preset = Preset(translational=True, om=0.4, phi0=-0.1)
            self.san = SAN(x10=0.1, y10=0.2, phi10=0.3, v=0.05)
            self.connect(self.preset.flange, self.san.ctrT2)
    res = run(M())
    xG = res["san.xG"]
    assert np.max(np.abs(xG - (-0.1 + 0.4 * res.time))) < TOL
    for k in range(0, len(res.time), 5):
        P = np.array([0.1, 0.2]) + xG[k] * e(0.3) + 0.05 * n(0.3)
        assert abs(res["san.ctr2D2.x"][k] - P[0]) < TOL
        assert abs(res["san.ctr2D2.y"][k] - P[1]) < TOL


def test_fgp_on_crank_plane():
    def wire(s):
        s.connect(s.crank.ctr2D2, s.elem.ctr2D1)
    m = CrankTest(FGP(lL=0.15, x10=0.02, y10=0.01, phi10=-0.7), wire)
    res = run(m)
    phi, Pc = crank_points(res)
    for k in range(len(res.time)):
        P1 = Pc[k] + np.array([[np.cos(phi[k]), -np.sin(phi[k])],
                               [np.sin(phi[k]), np.cos(phi[k])]]) @ np.array([0.02, 0.01])
        P = P1 + 0.15 * e(phi[k] - 0.7)
        assert abs(res["elem.ctr2D2.x"][k] - P[0]) < TOL
        assert abs(res["elem.ctr2D2.y"][k] - P[1]) < TOL
        assert abs(wrap(res["elem.phiL"][k] - (phi[k] - 0.7))) < TOL


@pytest.mark.parametrize("K", [1, -1])
def test_ddd(K):
    def wire(s):
        s.connect(s.crank.ctr2D2, s.elem.ctr2D1)
    P2 = np.array([0.5, 0.1])
    m = CrankTest(DDD(lL1=0.6, lL2=0.45, x20=P2[0], y20=P2[1], K=K), wire)
    res = run(m)
    phi, Pc = crank_points(res)
    for k in range(len(res.time)):
        P = vdi_ddd(Pc[k], P2, 0.6, 0.45, K)
        assert abs(res["elem.xP"][k] - P[0]) < TOL
        assert abs(res["elem.yP"][k] - P[1]) < TOL
        a1 = math.atan2(*(P - Pc[k])[::-1])
        a2 = math.atan2(*(P - P2)[::-1])
        assert abs(wrap(res["elem.phiL1"][k] - a1)) < TOL
        assert abs(wrap(res["elem.phiL2"][k] - a2)) < TOL
        assert abs(wrap(res["elem.ctr2D4.phi"][k] - a2)) < TOL


@pytest.mark.parametrize("K", [1, -1])
def test_dds(K):
    def wire(s):
        s.connect(s.crank.ctr2D2, s.elem.ctr2D1)
    P2, phiU, v, lL = np.array([0.3, -0.2]), 0.25, 0.05, 0.5
    m = CrankTest(DDS(lL=lL, v=v, K=K, x20=P2[0], y20=P2[1], phi20=phiU), wire)
    res = run(m)
    phi, Pc = crank_points(res)
    for k in range(len(res.time)):
        P, xG = vdi_dds(Pc[k], P2, phiU, lL, v, K)
        assert abs(res["elem.xP"][k] - P[0]) < TOL
        assert abs(res["elem.yP"][k] - P[1]) < TOL
        assert abs(res["elem.xG"][k] - xG) < TOL
        aL = math.atan2(*(Pc[k] - P)[::-1])
        assert abs(wrap(res["elem.phiL"][k] - aL)) < TOL
        PS = P2 + xG * e(phiU)
        assert abs(res["elem.ctr2D4.x"][k] - PS[0]) < TOL


def test_dsd():
    def wire(s):
        s.connect(s.crank.ctr2D2, s.elem.ctr2D2)
    P1, v = np.array([-0.4, 0.1]), -0.06
    m = CrankTest(DSD(v=v, x10=P1[0], y10=P1[1]), wire)
    res = run(m)
    phi, Pc = crank_points(res)
    for k in range(len(res.time)):
        aU, xG = vdi_dsd(P1, Pc[k], v)
        assert abs(wrap(res["elem.phiU"][k] - aU)) < TOL
        assert abs(res["elem.xG"][k] - xG) < TOL
        assert abs(wrap(res["elem.ctr2D3.phi"][k] - aU)) < TOL


def test_ssd():
    def wire(s):
        s.connect(s.crank.ctr2D2, s.elem.ctr2D2)
    P1, a1, v1, v2, pv = np.array([-0.3, 0.4]), 0.1, 0.04, -0.03, math.radians(70)
    m = CrankTest(SSD(v1=v1, v2=v2, phiv=pv, x10=P1[0], y10=P1[1], phi10=a1), wire)
    res = run(m)
    phi, Pc = crank_points(res)
    a2 = a1 + pv
    for k in range(len(res.time)):
        # P2 - v2 n2 lies on guide 2 through P; P = P1 + v1 n1 + xG1 e1
        xG1, t = line_intersection(P1 + v1 * n(a1), e(a1), Pc[k] - v2 * n(a2), e(a2))
        P = P1 + v1 * n(a1) + xG1 * e(a1)
        xG2 = -t
        assert abs(res["elem.xG1"][k] - xG1) < TOL
        assert abs(res["elem.xG2"][k] - xG2) < TOL
        assert abs(res["elem.ctr2D3.x"][k] - P[0]) < TOL
        assert abs(res["elem.ctr2D3.y"][k] - P[1]) < TOL
        assert abs(wrap(res["elem.ctr2D4.phi"][k] - a2)) < TOL


def test_sds_guide_on_crank():
    def wire(s):
        s.connect(s.crank.ctr2D2, s.elem.ctr2D1)
    P2, a2, v1, v2 = np.array([0.1, 0.5]), 0.0, 0.03, -0.05
    m = CrankTest(SDS(v1=v1, v2=v2, x20=P2[0], y20=P2[1], phi20=a2, phi10=0.4), wire)
    res = run(m, stop=0.3)   # guide 1 turns with the crank: stop before it gets parallel
    phi, Pc = crank_points(res)
    for k in range(len(res.time)):
        a1 = phi[k] + 0.4
        xG1, xG2 = line_intersection(Pc[k] + v1 * n(a1), e(a1), P2 + v2 * n(a2), e(a2))
        P = Pc[k] + v1 * n(a1) + xG1 * e(a1)
        assert abs(res["elem.xG1"][k] - xG1) < TOL
        assert abs(res["elem.xG2"][k] - xG2) < TOL
        assert abs(res["elem.xP"][k] - P[0]) < TOL
        assert abs(res["elem.yP"][k] - P[1]) < TOL


def test_frame_ref_global():
    """frameRef2='global': the guide point of a DDS on the moving crank plane
    is given by its global start position (Anhang A.4-A.6)."""
    def wire(s):
        s.connect(s.crank.ctr2D2, s.elem.ctr2D2)
    G = np.array([0.5, 0.4])
    m = CrankTest(DDS(lL=0.5, v=0.0, x10=0.6, y10=0.3, x20=G[0], y20=G[1], phi20=0.0,
                      frameRef2="global"), wire)
    res = run(m, stop=0.1)
    assert abs(res["elem.ctrT1.s"][0]) < TOL
    # at t = 0 the guide point PKS2 is at G with angle 0
    phi0 = res["crank.phiL"][0]
    Pc = vdi_dan(np.array([0.05, -0.03]), 0.2, phi0)
    P = np.array([res["elem.xP"][0], res["elem.yP"][0]])
    # P lies on the guide line y = G_y (v = 0) at t = 0 and at distance lL from P1
    assert abs(P[1] - G[1]) < TOL
    assert abs(np.hypot(*(P - np.array([0.6, 0.3]))) - 0.5) < TOL
    # the guide moves with the crank: relative coordinates stay constant
    rel = G - Pc
    k = len(res.time) - 1
    c, s = np.cos(res["crank.phiL"][k] - phi0), np.sin(res["crank.phiL"][k] - phi0)
    Pck = vdi_dan(np.array([0.05, -0.03]), 0.2, res["crank.phiL"][k])
    G_k = Pck + np.array([[c, -s], [s, c]]) @ rel
    Pk = np.array([res["elem.xP"][k], res["elem.yP"][k]])
    assert abs((Pk - G_k) @ n(res["crank.phiL"][k] - phi0)) < TOL
