"""The drive-train fuzz cases' errors (tests/fuzz_cases_drivetrain.py):
each invalid parameter is refused when the model is defined, with a
message naming the component's class and the parameter; the valid model
they derive from defines without error.  (test_fuzz runs a fixed sample of the
cases, all with ACAUSAL2D_FUZZ=all, through the API and the command line.)"""
import pytest

import fuzz_cases_drivetrain
from acausal2d.errors import ModelDefinitionError


def _define(source):
    space = {}
    exec(compile(source, "model.py", "exec"), space)
    return space["Model"]()


@pytest.mark.parametrize("case", fuzz_cases_drivetrain.bad_cases(), ids=lambda c: c["id"])
def test_bad_parameter_is_refused_naming_component_and_parameter(case):
    with pytest.raises(ModelDefinitionError) as err:
        _define(case["model"])
    msg = str(err.value)
    assert all(w in msg for w in case["words"]), msg


def test_the_valid_model_defines():
    _define(fuzz_cases_drivetrain.good_cases(n=1)[0]["model"])
