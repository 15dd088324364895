"""Rope drives of seed ch. 2.5.1 (Bild 2.4, 2.5): pull force, section forces
and travel ratio of the factor, potential and differential blocks against
their closed forms (inextensible ropes, constant pull speed: the static
forces hold exactly), and the golden rule of mechanics (work in = work out)."""
import os
import sys

import numpy as np
import pytest

import acausal2d
from acausal2d import cli

ROOT = os.path.join(os.path.dirname(__file__), os.pardir)
sys.path.insert(0, os.path.join(ROOT, "models"))
import rope_drives as rd  # noqa: E402

W = rd.MASS * rd.G
M_G = rd.PotentialBlock.M_PULLEY * rd.G
R, r = rd.DifferentialBlock.R, rd.DifferentialBlock.r


def _sim(cls):
    return acausal2d.simulate(cls(), stop_time=2.0, intervals=20, rtol=1e-10)


@pytest.mark.parametrize("cls, force, ratio, sections", [
    (rd.FactorBlock, W / 4, 4.0, {"rope2.F": W / 4, "rope5.F": W / 4}),
    (rd.PotentialBlock, ((W / 2 + M_G) / 2 + M_G) / 2, 8.0,
     {"right1.F": W / 2, "left1.F": W / 2, "right2.F": (W / 2 + M_G) / 2}),
    (rd.DifferentialBlock, W * (R - r) / (2 * R), 2 * R / (R - r),
     {"load_big.F": W / 2, "load_small.F": W / 2}),
], ids=lambda v: getattr(v, "__name__", None))
def test_force_and_travel_ratio_against_closed_form(cls, force, ratio, sections):
    res = _sim(cls)
    assert np.max(np.abs(res["pull.F"] - force)) < 1e-8 * force
    for name, value in sections.items():
        assert np.max(np.abs(res[name] - value)) < 1e-8 * value, name
    lift = res["load.y"] - res["load.y"][0]
    travel = res["pull.s_in.u"]
    assert abs(travel[-1] / lift[-1] - ratio) < 1e-8 * ratio
    assert lift[-1] > 0.02                            # the load went up
    if cls is not rd.PotentialBlock:                  # its pulleys lift themselves too
        # golden rule: work of the pull force = potential energy gained
        assert abs(force * travel[-1] - W * lift[-1]) < 1e-8 * W * lift[-1]


def test_rope_drive_from_the_cli_writes_figures(tmp_path):
    out = tmp_path / "diff"
    code = cli.main(["simulate", os.path.join(ROOT, "models", "rope_drives.py"),
                     "--model", "DifferentialBlock", "--out", str(out)])
    assert code == 0
    assert (out / "pull_force.png").exists() and (out / "travel.png").exists()
