"""What a new user finds out without reading the source: the version, a
model's parameters (``acausal2d params``), the parameter tables in
``help()`` of every component class, and the states the simulation chose."""
import os
import pydoc
import re
import shutil
import subprocess
import sys

import pytest

import acausal2d
from acausal2d import Component, Parameter, Variable
from acausal2d.library.planar import Body, Revolute

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MODELS = os.path.join(ROOT, "models")


def run(*args):
    exe = os.path.join(os.path.dirname(sys.executable), "acausal2d")
    exe = exe if os.path.exists(exe) else shutil.which("acausal2d")
    cmd = [exe] if exe else [sys.executable, "-m", "acausal2d"]
    return subprocess.run(cmd + list(args), capture_output=True, text=True, timeout=300)


def test_version():
    proc = run("--version")
    assert proc.returncode == 0
    assert proc.stdout.strip() == "acausal2d " + acausal2d.__version__
    assert re.fullmatch(r"\d+\.\d+\.\d+", acausal2d.__version__)
    from importlib.metadata import version
    assert version("acausal2d") == acausal2d.__version__      # pyproject reads it from there


def test_params_lists_value_unit_rule_and_doc():
    proc = run("params", os.path.join(MODELS, "pendulum.py"))
    assert proc.returncode == 0, proc.stderr
    rows = {ln.split()[0]: ln.split(None, 4) for ln in proc.stdout.splitlines()[3:]}
    assert rows["body.m"] == ["body.m", "1", "kg", ">=", "0  mass"]
    assert rows["rod.r"][:3] == ["rod.r", "(1,", "0)"]
    assert "vector from frame_a to frame_b" in proc.stdout
    assert rows["world.g"][:4] == ["world.g", "(0,", "-9.81)", "m/s2"]
    assert proc.stdout.startswith("Pendulum parameters")
    # the same table from Python
    cm = acausal2d.compile_model(acausal2d.load_model(os.path.join(MODELS, "pendulum.py")))
    assert cm.parameters_table() in proc.stdout
    assert run("params", os.path.join(MODELS, "nope.py")).returncode == 2


def test_help_shows_parameters_with_default_unit_rule_and_doc():
    text = pydoc.render_doc(Body, renderer=pydoc.plaintext)
    assert "Parameters (default, unit, rule, description):" in text
    assert re.search(r"m\s+1\s+kg\s+>= 0\s+mass", text)
    assert re.search(r"I\s+0\.1\s+kg\.m2\s+>= 0\s+rotational inertia", text)
    assert re.search(r"phi\s+rad\s+angle", text)
    assert "world = Outer(PlanarWorld)" in text
    assert "Revolute joint" in Revolute.__doc__ and "w    rad/s  relative angular" in \
        Revolute.__doc__

    class Spring(Component):
        """A spring."""
        c = Parameter(2.5, "N/m", "stiffness", positive=True)
        x = Variable(unit="m", doc="elongation")

    class StiffSpring(Spring):
        d = Parameter(0.1, "N.s/m", "damping", min=0)

    assert Spring.__doc__.startswith("A spring.\n\nParameters")
    assert re.search(r"c\s+2\.5\s+N/m\s+> 0\s+stiffness", Spring.__doc__)
    # inherited parameters are listed with the own ones
    assert re.search(r"c\s+2\.5.*\n\s+d\s+0\.1\s+N\.s/m\s+>= 0\s+damping", StiffSpring.__doc__)


def test_simulate_summary_names_the_states(tmp_path):
    proc = run("simulate", os.path.join(MODELS, "piston_engine.py"), "--stop-time", "0.5",
               "--out", str(tmp_path))
    assert proc.returncode == 0, proc.stderr
    assert "  states: revoluteDrive.phi, revoluteDrive.w\n" in proc.stdout
    driven = run("simulate", os.path.join(MODELS, "eight_link_vdi2729.py"), "--stop-time",
                 "0.5", "--out", str(tmp_path))
    assert "  states: none (the motion is prescribed)" in driven.stdout


# ---------------------------------------------------------- connectors (issue 34)
def test_help_of_a_component_lists_its_connectors_and_those_of_its_options():
    from acausal2d.library import rotational
    from acausal2d.library.planar import Body, Revolute
    assert "frame_a  Frame (x, y, phi, fx, fy, t)" in Body.__doc__
    assert Body.__doc__.index("Parameters") < Body.__doc__.index("Connectors")
    assert "w_in" in rotational.Speed.__doc__ and "flange" in rotational.Speed.__doc__
    doc = Revolute.__doc__
    assert "flange_a  RotationalFlange (phi, tau)  [with use_flange=True]" in doc
    assert "frame_b   Frame" in doc


def test_an_unknown_connector_names_the_valid_ones_and_the_closest():
    from acausal2d.library.planar import Revolute
    with pytest.raises(AttributeError) as info:
        Revolute().frame_c
    text = str(info.value)
    assert "did you mean 'frame_b'?" in text and "connectors frame_a, frame_b" in text
    with pytest.raises(AttributeError, match=r"exists with use_flange=True"):
        Revolute().flange_a
