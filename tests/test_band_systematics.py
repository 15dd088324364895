"""The band-mechanism systematics of seed ch. 2.5.2 (models/band_systematics.py,
one model per structure): every structure assembles and runs, and with all
links massless its balances hold at every output point, computed from the
result's geometry independently of the model's equations:

- static balance of the loaded link (it carries the band's end): load
  torque + moment of the band force about the link's pivot = 0 (a slider:
  load force + the band force's component along its guide = 0), and the
  same for the driven link where it carries the other band end;
- power balance: drive power + load power = 0 (no losses, no masses);
- the band is taut and the transmission ratio is not constant.

The tolerances follow from the run's rtol = 1e-10 on positions and forces
of order 0.1 m and 10 N (relative residuals 1e-7 leave a factor of 1000)."""
import collections
import itertools
import os
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.errors import ModelDefinitionError
from acausal2d.library.belt.systematics import F_BAND, BandStructure, parse_structure
from acausal2d.library.belt.systematics_two import TwoBandStructure, parse_two_bands

ROOT = os.path.join(os.path.dirname(__file__), os.pardir)
sys.path.insert(0, os.path.join(ROOT, "models"))
import band_systematics as bs  # noqa: E402

REL = 1e-7


def _run(model):
    return acausal2d.simulate(model, stop_time=0.4, intervals=8, rtol=1e-10)


def _band_dir(res, end):
    g = res["band.gamma"]
    sign = 1.0 if end == 1 else -1.0          # away from the end along the band
    return sign * np.cos(g), sign * np.sin(g)


def _link_balance(res, model, name, point, end, load):
    """Residual of the link's balance: ``load`` (torque or force along the
    guide) + the band force's moment about the pivot (or component)."""
    link = getattr(model, name)
    u = _band_dir(res, end)
    F = res["band.F"]
    if hasattr(link, "lL") and name + ".phiL" in res.names:
        phi, lL = res[name + ".phiL"], float(link.parameter_value("lL"))
        px = res[name + ".ctr2D2.x"] - lL * np.cos(phi)
        py = res[name + ".ctr2D2.y"] - lL * np.sin(phi)
        qx, qy = res[point + ".x"], res[point + ".y"]
        return load + F * ((qx - px) * u[1] - (qy - py) * u[0])
    e = res[name + ".phiS"]
    return load + F * (u[0] * np.cos(e) + u[1] * np.sin(e))


def _rolling_balance(res, model, load):
    """Band as the frame: the loaded link carries the disc rolling on the band
    (y = 0); the contact force on the disc, -(roll.frame_a.fx, fy) at (roll.x,
    0), balances the load about the link's pivot (a slider: along its guide)."""
    name = model.load_link
    link = getattr(model, name)
    gx, gy = -res["roll.frame_a.fx"], -res["roll.frame_a.fy"]
    if model.load_kind == "torque":
        phi, lL = res[name + ".phiL"], float(link.parameter_value("lL"))
        px = res[name + ".ctr2D2.x"] - lL * np.cos(phi)
        py = res[name + ".ctr2D2.y"] - lL * np.sin(phi)
        return load + (res["roll.x"] - px) * gy - (0.0 - py) * gx
    e = res[name + ".phiS"]
    return load + gx * np.cos(e) + gy * np.sin(e)


def _load_power(res, model):
    name = model.load_link
    speed = res["%s.omL" % name] if model.load_kind == "torque" else res["der(%s.xG)" % name]
    return model.load_value * speed


@pytest.mark.parametrize("cls", bs.BAND_FRAME, ids=lambda c: c.code)
def test_band_frame_static_and_power_balance(cls):
    model = cls()
    res = _run(model)
    load = np.full_like(res["roll.x"], model.load_value)
    scale = np.max(np.hypot(res["roll.frame_a.fx"], res["roll.frame_a.fy"]))
    assert np.max(np.abs(_rolling_balance(res, model, load))) < REL * scale
    p_drive = res["drive.tau"] * res["drive.w"]
    assert np.max(np.abs(p_drive + _load_power(res, model))) < REL * np.max(np.abs(p_drive))
    # the disc rolls: 1e-6 m is 10^4 times the position error at rtol 1e-10 on 0.35 m
    assert abs(res["roll.x"][-1] - res["roll.x"][0]) > 1e-6
    ratio = _load_power(res, model) / model.load_value / res["drive.w"]
    assert np.ptp(ratio) > 1e-3 * np.max(np.abs(ratio))


def _coupler_point(res, model, j):
    """The point where the band pulls the coupler at joint j (2 or 3)."""
    frame = model.ends[j]
    return res[frame + ".x"], res[frame + ".y"]


@pytest.mark.parametrize("cls", bs.TWO_BANDS, ids=lambda c: c.code)
def test_two_band_coupler_static_and_power_balance(cls):
    """The coupler hangs on the bands L1 and L3: the band forces, the
    vertical load W at its pivot H and the drive torque balance it (x, y,
    moment about H); drive power + W dy_H/dt = 0."""
    model = cls()
    res = _run(model)
    F1, F3 = res["band1.F"], res["band3.F"]
    assert np.all(F1 > 0.5 * F_BAND) and np.all(F3 > 0.5 * F_BAND)
    g1, g3 = res["band1.gamma"], res["band3.gamma"]
    u1, u3 = (-np.cos(g1), -np.sin(g1)), (np.cos(g3), np.sin(g3))
    W = model.load_value
    assert np.max(np.abs(F1 * u1[0] + F3 * u3[0])) < REL * F_BAND
    assert np.max(np.abs(F1 * u1[1] + F3 * u3[1] + W)) < REL * F_BAND
    hx, hy = res["carrier_x.ctr2D2.x"], res["carrier_x.ctr2D2.y"]
    (q2x, q2y), (q3x, q3y) = _coupler_point(res, model, 2), _coupler_point(res, model, 3)
    moment = res["drive.tau"] + F1 * ((q2x - hx) * u1[1] - (q2y - hy) * u1[0]) \
        + F3 * ((q3x - hx) * u3[1] - (q3y - hy) * u3[0])
    assert np.max(np.abs(moment)) < REL * F_BAND
    p_drive = res["drive.tau"] * res["drive.w"]
    p_load = W * res["der(carrier_y.xG)"]
    assert np.max(np.abs(p_drive + p_load)) < REL * np.max(np.abs(p_load))
    assert np.ptp(res["drive.tau"]) > 1e-3 * np.max(np.abs(res["drive.tau"]))


def _moment(res, F, prefix, c, u):
    """Moment about the point c of the band force F u at the frame ``prefix``."""
    return F * ((res[prefix + ".x"] - c[0]) * u[1] - (res[prefix + ".y"] - c[1]) * u[0])


def _driven_side(res, model, F, e):
    """Moment balance of the driven element at J2 and the power of the
    loads: the crank about its pivot J1 = (0, 0), or the winch disc about its
    centre (then the wheel L1 carrying it is loaded too, about its contact
    point)."""
    if not hasattr(model, "roll1"):
        return res["drive.tau"] + _moment(res, F, model.ends[2], (0.0, 0.0), e), 0.0
    centre = (res["arm1.frame_b.x"], res["arm1.frame_b.y"])
    m_winch = res["drive.tau"] + _moment(res, F, model.ends[2], centre, e)
    m_wheel = model.load1_value + _moment(res, F, model.ends[2], (res["roll1.x"], 0.0), e)
    assert np.max(np.abs(m_wheel)) < REL * abs(model.load1_value)
    return m_winch, model.load1_value * res["roll1.w"]


@pytest.mark.parametrize("cls", bs.TWO_BANDS_FRAME, ids=lambda c: c.code)
def test_band_frame_two_bands_static_and_power_balance(cls):
    """Band L2 and the band as the frame: the driven crank (pivot J1 on the
    band) or winch, and the wheels rolling on the band (moments about the
    contact point, where the contact force acts) balance the band force;
    drive power + load power = 0."""
    model = cls()
    res = _run(model)
    assert all(name in res.names for name in model.outputs)      # what the CLI plots
    F = res["band2.F"]
    assert np.all(F > 0.0) and abs(F[0] - F_BAND) < REL * F_BAND
    e = np.cos(res["band2.gamma"]), np.sin(res["band2.gamma"])   # pull at J2, along J2 -> J3
    m_drive, p_load1 = _driven_side(res, model, F, e)
    assert np.max(np.abs(m_drive)) < REL * np.max(np.abs(res["drive.tau"]))
    contact = (res["roll.x"], 0.0)
    m_load = model.load_value + _moment(res, F, model.ends[3], contact, (-e[0], -e[1]))
    assert np.max(np.abs(m_load)) < REL * abs(model.load_value)
    p_drive = res["drive.tau"] * res["drive.w"]
    p_load = model.load_value * res["roll.w"] + p_load1
    assert np.max(np.abs(p_drive + p_load)) < REL * np.max(np.abs(p_drive))
    assert np.ptp(res["roll.w"]) > 1e-3 * np.max(np.abs(res["roll.w"]))   # not a constant ratio


@pytest.mark.parametrize("cls", bs.MODELS, ids=lambda c: c.code)
def test_structure_static_and_power_balance(cls):
    model = cls()
    res = _run(model)
    F = res["band.F"]
    assert np.all(F > 0.5 * F_BAND) and abs(F[0] - F_BAND) < REL * F_BAND
    load = np.full_like(F, model.load_value)
    res_load = _link_balance(res, model, model.load_link, model.load_point, model.load_end, load)
    assert np.max(np.abs(res_load)) < REL * F_BAND
    if model.drive_end:
        res_drive = _link_balance(res, model, model.drive_link, model.drive_point,
                                  model.drive_end, res["drive.tau"])
        assert np.max(np.abs(res_drive)) < REL * np.max(np.abs(res["drive.tau"]))
    p_drive = res["drive.tau"] * res["drive.w"]
    residual = p_drive + _load_power(res, model)
    assert np.max(np.abs(residual)) < REL * np.max(np.abs(p_drive))
    ratio = _load_power(res, model) / model.load_value / res["drive.w"]
    assert np.ptp(ratio) > 1e-3 * np.max(np.abs(ratio))        # not a constant ratio


def _independent_enumeration():
    """The structures by brute force over the code grammar, written without
    the derivation's chain-bands-discs-frame construction: every string of
    four joints from D, S, B with one or two '~' marks (after a joint: the
    link to the next joint, cyclically, is a band), kept if

    * two bands are never adjacent;
    * a band's two joints are D or B (no S), at least one B;
    * a B is at a band's end (it is the band's disc);
    * replacing every B by D leaves a chain with at most two S;

    and identified with its reading from the other side (joints reversed,
    the band marks moved with the links).  Returns {canonical code: both
    codes}."""
    found = {}
    for joints in itertools.product("DSB", repeat=4):
        for marks in itertools.chain(itertools.combinations(range(4), 1),
                                     itertools.combinations(range(4), 2)):
            if len(marks) == 2 and marks[1] - marks[0] in (1, 3):
                continue
            ends = [(joints[k], joints[(k + 1) % 4]) for k in marks]
            if any("S" in e or "B" not in e for e in ends):
                continue
            at_band = {j for k in marks for j in (k, (k + 1) % 4)}
            if any(ch == "B" and i not in at_band for i, ch in enumerate(joints)):
                continue
            if joints.count("S") > 2:
                continue
            code = "".join(j + ("~" if i in marks else "") for i, j in enumerate(joints))
            rev = "".join(joints[::-1][i] + ("~" if (2 - i) % 4 in marks else "")
                          for i in range(4))
            found.setdefault(min(code, rev), {code, rev})
    return found


def test_the_derived_structures_are_complete():
    """The derivation from the rules (library/belt/structures.py) and the
    brute-force enumeration above give the same 37 structures: 18 four-bar,
    12 slider-crank and 7 cross-slider structures from 6 + 3 + 2 chains
    with bands; the models file makes one class of each, named by the
    reading it is built in."""
    from acausal2d.library.belt.structures import derive_structures, derived_chains
    derived = {s.code: set(s.readings) for s in derive_structures()}
    assert derived == _independent_enumeration()
    chains = collections.Counter(s.chain for s in derive_structures())
    assert chains == {"4-bar": 18, "slider-crank": 12, "cross-slider": 7}
    assert derived_chains() == {"4-bar": 6, "slider-crank": 3, "cross-slider": 2,
                                "slotted slider": 0}
    built = {c.code for c in bs.CLASSES}
    assert len(built) == len(bs.CLASSES) == 37
    assert {min(r) for r in derived.values() for c in built if c in r} == set(derived)
    for c in bs.CLASSES:
        assert getattr(bs, c.__name__) is c


def test_every_structure_has_its_own_class():
    codes = [c.code for c in bs.MODELS]
    assert len(set(codes)) == len(codes) == 19
    assert sorted(c.code for c in bs.BAND_FRAME) == sorted(
        ["BDDD~", "BDDB~", "DDSB~", "DSDB~", "BDSB~", "DSSB~", "BSSB~"])
    assert len(bs.TWO_BANDS) == 6
    for c in bs.MODELS:
        assert c.__name__ == c.code.replace("~", "_")
        assert parse_structure(c.code)
    for c in bs.TWO_BANDS:
        assert c.__name__ == c.code.replace("~", "_")
        assert parse_two_bands(c.code)[1] == (1, 3)
    for c in bs.TWO_BANDS_FRAME:
        assert c.__name__ == c.code.replace("~", "_") + "frame"
        assert parse_two_bands(c.code)[1] == (2, 4)


@pytest.mark.parametrize("code", ["DS~DD", "DD~DD", "DBDD", "DB~DB~", "BD~DB", "SDDB~"])
def test_codes_the_rules_exclude_are_refused(code):
    """A band next to a prismatic joint (R3), a band without a disc (R2), no
    band, two marks, a disc away from the band, a band frame next to a
    slider: refused, saying so."""
    with pytest.raises(ModelDefinitionError, match="band structure"):
        type("X", (BandStructure,), {"code": code})()


@pytest.mark.parametrize("code", ["DB~BD~", "D~DD~B", "DBB~B", "S~BD~B"])
def test_two_band_codes_refused(code):
    """Adjacent bands, a band without a disc, one mark, a slider: refused
    naming the code."""
    with pytest.raises(ModelDefinitionError, match="two-band structure"):
        type("X", (TwoBandStructure,), {"code": code})()
