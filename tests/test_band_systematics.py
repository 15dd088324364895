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
import os
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d.errors import ModelDefinitionError
from acausal2d.library.belt.systematics import F_BAND, BandStructure, parse_structure

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
    assert abs(res["roll.x"][-1] - res["roll.x"][0]) > 1e-3        # the disc rolls
    ratio = _load_power(res, model) / model.load_value / res["drive.w"]
    assert np.ptp(ratio) > 1e-3 * np.max(np.abs(ratio))


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


def test_every_structure_has_its_own_class():
    codes = [c.code for c in bs.MODELS]
    assert len(set(codes)) == len(codes) == 19
    assert sorted(c.code for c in bs.BAND_FRAME) == sorted(
        ["BDDD~", "BDDB~", "DDSB~", "DSDB~", "BDSB~", "DSSB~"])
    for c in bs.MODELS:
        assert c.__name__ == c.code.replace("~", "_")
        assert parse_structure(c.code)


@pytest.mark.parametrize("code", ["DS~DD", "DD~DD", "DBDD", "DB~DB~", "BD~DB", "SDDB~", "BSSB~"])
def test_codes_the_rules_exclude_are_refused(code):
    """A band next to a prismatic joint (R3), a band without a disc (R2), no
    band, two marks, a disc away from the band, a band frame next to a
    slider; BSSB~ (two discs on the band frame, the coupler a slider on a
    moving guide) cannot be driven by a speed preset: refused, saying so."""
    with pytest.raises(ModelDefinitionError, match="band structure"):
        type("X", (BandStructure,), {"code": code})()
