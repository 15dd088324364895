"""Piston engine without any state priority (reference
PistonEngine_DynamicStateSelection.csv).

The same slider-crank as ``piston_engine.py``, but every joint has
``state_select='default'``: the compiler picks the states itself at the
current position and re-selects them where its choice becomes singular.
The run starts at the dead centre, where the piston position cannot be a
state.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from piston_engine import PistonEngine  # noqa: E402


class PistonEngineDynamic(PistonEngine):
    """Slider-crank with the states left to the compiler."""
    outputs = ["bodyDrive.phi", "prismatic.s", "prismatic.v", "revoluteDisc.phi",
               "revoluteDisc.w", "revoluteDrive.w"]

    def __init__(self, **kw):
        super().__init__(drive_state_select="default", state_select="default", **kw)


if __name__ == "__main__":
    from acausal2d.cli import run_model_file
    sys.exit(run_model_file(__file__))
