"""The explore page's parameter list (``GET /api/params``) shows the slider
ranges it computes to 12 significant digits: a parameter of 0.1 gets the
range -0.1 .. 0.3, not 0.30000000000000004."""
import json

from acausal2d.explore.runner import _slider
from acausal2d.language.dsl import Parameter


def test_slider_range_is_written_short():
    lo, hi = _slider(Parameter(0.1, "m", "a length"), 0.1)
    assert json.dumps([lo, hi]) == "[-0.1, 0.3]"
    lo, hi = _slider(Parameter(1.0, "kg", "a mass", positive=True), 1 / 3)
    assert json.dumps(hi) == "1.0"
    # 12 significant digits: off by at most half a unit of the 12th, 5e-12 relative
    assert abs(lo - 1 / 300) <= 5e-12 * (1 / 300) and len(repr(lo)) <= 16
