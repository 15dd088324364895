"""Belt library (library/belt.py, issue 4): tangent construction, speed
ratio, wrap angles, slack spans, drum, spring belt, nozzle belt."""
import math

import casadi as ca
import numpy as np
import pytest

import acausal2d
from acausal2d import Component, start
from acausal2d.library import rotational, signals
from acausal2d.library.belt import (Belt, Drum, NozzleBelt, Pulley, RopeDrive, SpringBelt,
                                    connect_band, open_belt_closed_form, tangent)
from acausal2d.library.planar import Body, Fixed, Prismatic

R1, R2 = 0.1, 0.05
C2 = (0.5, 0.1)


def smooth_angle(t):
    """Drive angle with zero initial speed: phi = 2 (t - sin(2t)/2)."""
    return 2.0 * (t - ca.sin(2 * t) / 2)


class TwoPulleys(Component):
    """Driven pulley p1 (r 0.1 m at the origin) and free pulley p2 (r 0.05 m,
    J 1e-4) with a closed, very stiff belt; open (same winding direction) or
    crossed (opposite winding directions)."""

    def __init__(self, crossed=False, c=1e8, **kw):
        super().__init__(**kw)
        eps0 = 100.0 / c  # 100 N pretension
        self.p1 = Pulley(r=R1, x0=0.0, y0=0.0, w=1)
        self.p2 = Pulley(r=R2, x0=C2[0], y0=C2[1], w=-1 if crossed else 1, J=1e-4)
        self.span_a = Belt(c=c, d=c * 1e-4, eps=start(eps0, fixed=True))
        self.span_b = Belt(c=c, d=c * 1e-4, eps=start(eps0, fixed=True))
        # open belt: p1 K2 -> p2 K1 (lower span), p2 K2 -> p1 K1 (upper span)
        connect_band(self, self.span_a, 1, self.p1, 2)
        connect_band(self, self.span_a, 2, self.p2, 1)
        connect_band(self, self.span_b, 1, self.p2, 2)
        connect_band(self, self.span_b, 2, self.p1, 1)
        self.drive = rotational.Position()
        self.sig = signals.TimeFunction(smooth_angle)
        self.connect(self.sig.y, self.drive.phi_in)
        self.connect(self.drive.flange, self.p1.ctrR)


@pytest.mark.parametrize("crossed", [False, True])
def test_two_pulleys_ratio_and_wrap_angles(crossed):
    res = acausal2d.simulate(TwoPulleys(crossed=crossed), stop_time=2.0, rtol=1e-9,
                             output_times=np.linspace(0.0, 2.0, 101))
    assert res.events == []
    d = math.hypot(*C2)
    if crossed:
        a = math.asin((R1 + R2) / d)
        beta1 = beta2 = math.pi + 2 * a
        l_free = math.sqrt(d * d - (R1 + R2) ** 2)
        ratio = -R1 / R2
    else:
        beta1, beta2, l_free = open_belt_closed_form(R1, R2, d)
        ratio = R1 / R2
    # wrap angles and free span lengths: tangent construction, closed form
    for name, val in (("p1.beta", beta1), ("p2.beta", beta2)):
        assert np.max(np.abs(res[name] - val)) < 1e-8, name
    for span in ("span_a", "span_b"):
        assert np.max(np.abs(res[span + ".l"] - l_free)) < 1e-8
    # contact points lie on the circles and the spans are tangent to them
    for p, (cx, cy), r in (("p1", (0, 0), R1), ("p2", C2, R2)):
        for k in (1, 2):
            x, y = res["%s.ctrK%d.x" % (p, k)], res["%s.ctrK%d.y" % (p, k)]
            g = res["%s.ctrB%d.gamma" % (p, k)]
            assert np.max(np.abs(np.hypot(x - cx, y - cy) - r)) < 1e-10
            assert np.max(np.abs((x - cx) * np.cos(g) + (y - cy) * np.sin(g))) < 1e-10
    # speed ratio once the drive runs (t >= 0.5 s)
    w1, w2 = res["p1.w_rel"], res["p2.w_rel"]
    k = res.time >= 0.5
    assert np.max(np.abs(w2[k] / w1[k] / ratio - 1.0)) < 1e-8
    # belt tension stays near the 100 N pretension
    assert np.all(np.abs(res["span_a.F"] - 100.0) < 1.0)


def test_tangent_helper_matches_closed_form():
    d = 0.7
    g, l = tangent((0.0, 0.0, -0.2), (d, 0.0, 0.05))
    beta1, beta2, l_ref = open_belt_closed_form(0.2, 0.05, d)
    assert abs(l - l_ref) < 1e-14
    # the lower span of an open belt leaves the big pulley rising
    assert abs(g - math.asin(0.15 / d)) < 1e-14


class Bounce(Component):
    """A 1 kg body on a vertical guide hangs from a fixed point by an elastic
    rope and is thrown upwards with 3 m/s."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.anchor = Fixed(r=(0.0, 0.0))
        self.rope = Belt(c=1e4, d=5.0, eps=start(9.81 / 1e4, fixed=True))
        self.guide = Fixed()
        self.slider = Prismatic(r=(0.0, 1.0), s=start(-1.0), v=start(3.0, fixed=True))
        self.body = Body(m=1.0, I=0.01, x=start(0.0), y=start(-1.0))
        self.connect(self.guide.frame, self.slider.frame_a)
        self.connect(self.slider.frame_b, self.body.frame_a)
        self.connect(self.anchor.frame, self.rope.ctr2D1)
        self.connect(self.rope.ctr2D2, self.body.frame_a)


def test_slack_span_zero_force_and_free_flight():
    res = acausal2d.simulate(Bounce(), stop_time=2.0, rtol=1e-8,
                             output_times=np.linspace(0.0, 2.0, 401))
    slack_events = [t for t, txt in res.events if "rope.eps" in txt]
    assert len(slack_events) >= 4          # slack, re-tension, slack, re-tension, ...
    t = res.time
    F, eps, y = res["rope.F"], res["rope.eps"], res["body.y"]
    slack = eps < -1e-12
    assert slack.any() and (~slack).any()
    assert np.all(F[slack] == 0.0)
    # between the first slack and re-tension events the body flies freely
    t_s, t_r = slack_events[0], slack_events[1]
    k_s = np.nonzero(t == t_s)[0][-1]
    y_s, v_s = y[k_s], res["der(body.y)"][k_s]
    sel = (t > t_s) & (t < t_r)
    free = y_s + v_s * (t[sel] - t_s) - 0.5 * 9.81 * (t[sel] - t_s) ** 2
    assert np.max(np.abs(y[sel] - free)) < 1e-6
    assert res.time[-1] == pytest.approx(2.0)


class SlackOverPulley(Component):
    """Rope from an anchor over a fixed pulley (J > 0) to a guided body that
    is thrown upwards: both spans go slack and re-tension."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.anchor = Fixed(r=(-0.1, -1.0))
        self.pulley = Pulley(r=0.1, x0=0.0, y0=0.0, w=-1, J=1e-3)
        eps0 = 9.81 / 1e4
        self.span_a = Belt(c=1e4, d=5.0, eps=start(eps0, fixed=True))
        self.span_b = Belt(c=1e4, d=5.0, eps=start(eps0, fixed=True))
        self.guide = Fixed(r=(0.1, 0.0))
        self.slider = Prismatic(r=(0.0, 1.0), s=start(-1.0), v=start(2.0, fixed=True))
        self.body = Body(m=1.0, I=0.01, x=start(0.1), y=start(-1.0))
        self.connect(self.guide.frame, self.slider.frame_a)
        self.connect(self.slider.frame_b, self.body.frame_a)
        self.connect(self.anchor.frame, self.span_a.ctr2D1)
        connect_band(self, self.span_a, 2, self.pulley, 1)
        connect_band(self, self.span_b, 1, self.pulley, 2)
        self.connect(self.span_b.ctr2D2, self.body.frame_a)


def test_slack_and_retension_over_pulley():
    res = acausal2d.simulate(SlackOverPulley(), stop_time=1.5, rtol=1e-8,
                             output_times=np.linspace(0.0, 1.5, 301))
    assert res.time[-1] == pytest.approx(1.5)
    texts = " ".join(txt for _, txt in res.events)
    assert "span_b.eps" in texts
    for span in ("span_a", "span_b"):
        slack = res[span + ".eps"] < -1e-12
        assert np.all(res[span + ".F"][slack] == 0.0)
    assert (res["span_b.eps"] < -1e-12).any()
    # the spans stay vertical at the pulley: 180 degree wrap
    assert np.max(np.abs(res["pulley.beta"] - math.pi)) < 1e-9


class Hoist(Component):
    """A drum (r 0.1 m) driven by an angle lifts a 2 kg guided body; the
    rope hangs from the drum's right side."""

    def __init__(self, spring=False, **kw):
        super().__init__(**kw)
        self.drum = Drum(r=0.1, x0=-0.1, y0=0.0, w=1, J=0.01)
        if spring:
            self.rope = SpringBelt(k=1e4, b=100.0, l_dF=start(2 * 9.81 / 1e4, fixed=True))
        else:
            self.rope = Belt(c=1e6, d=1e3, eps=start(2 * 9.81 / 1e6, fixed=True))
        self.guide = Fixed()
        self.slider = Prismatic(r=(0.0, 1.0), s=start(-1.0, fixed=True), v=start(0.0, fixed=True))
        self.body = Body(m=2.0, I=0.01, x=start(0.0), y=start(-1.0))
        self.connect(self.guide.frame, self.slider.frame_a)
        self.connect(self.slider.frame_b, self.body.frame_a)
        connect_band(self, self.rope, 1, self.drum, 1)
        self.connect(self.rope.ctr2D2, self.body.frame_a)
        self.drive = rotational.Position()
        self.sig = signals.TimeFunction(smooth_angle)
        self.connect(self.sig.y, self.drive.phi_in)
        self.connect(self.drive.flange, self.drum.ctrR)


@pytest.mark.parametrize("spring", [False, True])
def test_drum_pays_out_rope(spring):
    res = acausal2d.simulate(Hoist(spring=spring), stop_time=2.0, rtol=1e-8,
                             output_times=np.linspace(0.0, 2.0, 201))
    # the rope hangs vertically from the drum's right side: lift = r * angle
    # minus the change of the rope's elongation
    dphi = res["drum.phi"] - res["drum.phi"][0]
    dy = res["body.y"] - res["body.y"][0]
    if spring:
        stretch = res["rope.l_dF"] - res["rope.l_dF"][0]
    else:
        l_u = res["rope.l_u"]
        stretch = res["rope.eps"] * l_u - res["rope.eps"][0] * l_u[0]
    assert np.max(np.abs(dy - 0.1 * dphi + stretch)) < 1e-5
    assert np.max(np.abs(res["drum.kappa1"] - 0.0)) < 1e-8
    assert dy[-1] > 0.4
    # the wound length grows by what is wound up
    assert np.max(np.abs(res["drum.l_wound"] - res["drum.l_wound"][0] - 0.1 * dphi)) < 1e-9
    # holding torque at rest: m g r
    assert res["drum.ctrR.tau"][0] == pytest.approx(2 * 9.81 * 0.1, rel=1e-9)


class Nozzle(Component):
    """A band from a fixed point through a nozzle, carried by a guided body
    that moves sideways, to a hanging 1 kg body."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.top = Fixed(r=(0.0, 0.0))
        self.nozzle = RopeDrive(x0=0.5, y0=0.0, angle=0.0)
        self.nozzle_drive = signals.TimeFunction(lambda t: 0.2 * (1 - ca.cos(2 * t)))
        self.band = NozzleBelt(c=1e5, d=100.0, eps=start(9.81 / 1e5, fixed=True))
        self.guide = Fixed(r=(1.0, 0.0))
        self.slider = Prismatic(r=(0.0, 1.0), s=start(-1.0), v=start(0.0, fixed=True))
        self.body = Body(m=1.0, I=0.01, x=start(1.0), y=start(-1.0))
        self.connect(self.nozzle_drive.y, self.nozzle.s_in)
        self.connect(self.guide.frame, self.slider.frame_a)
        self.connect(self.slider.frame_b, self.body.frame_a)
        self.connect(self.top.frame, self.band.ctr2D1)
        self.connect(self.nozzle.frame, self.band.ctr2D3)
        self.connect(self.band.ctr2D2, self.body.frame_a)


def test_nozzle_belt_force_balance():
    res = acausal2d.simulate(Nozzle(), stop_time=1.5, rtol=1e-8,
                             output_times=np.linspace(0.0, 1.5, 151))
    l1, l2 = res["band.l1"], res["band.l2"]
    x3 = res["band.ctr2D3.x"]
    assert np.max(np.abs(l1 - np.hypot(x3, 0.0))) < 1e-10
    assert np.max(np.abs(res["band.l"] - l1 - l2)) < 1e-9
    # the nozzle carries the resultant of both band pieces (4.76, 4.77)
    F = res["band.F"]
    g1, g2 = res["band.gamma1"], res["band.gamma2"]
    fx3 = F * np.cos(g1) - F * np.cos(g2)
    assert np.max(np.abs(res["band.ctr2D3.fx"] - fx3)) < 1e-7
    # the body rises as the nozzle moves out: unstretched length is conserved
    assert np.max(np.abs(res["band.l_u"] - res["band.l_u"][0])) < 1e-7
