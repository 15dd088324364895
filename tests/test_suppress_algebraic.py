"""Why the Python path still reaches IDA's ``suppressalg`` outside
scikit-sundae's public API (issue 34; runtime/sundials_ext.py).

scikit-sundae 1.2 has no option for it and no public handle on its IDA
memory.  The public substitute, a huge absolute tolerance on the algebraic
unknowns (ida.ALGEBRAIC_ATOL), gives the same motion but weights those
unknowns out of IDA's Newton convergence test as well, so IDA takes more
steps.  The pointer read is guarded: only a pointer that IDA itself
confirms (its current time is the time of the last ``init_step``) is used.
"""
import numpy as np

import acausal2d
from acausal2d.runtime import ida, sundials_ext, tiers
from conftest import load_model_class

RTOL = 1e-8


def _run(monkeypatch, suppress):
    monkeypatch.setenv(tiers.ENV, "off")                     # the Python path
    if not suppress:
        monkeypatch.setattr(ida, "suppress_algebraic", lambda mem: False)
    cm = acausal2d.compile_model(load_model_class("piston_engine.py", "PistonEngine")())
    return cm.simulate(stop_time=1.0, intervals=500, rtol=RTOL)


def test_the_public_substitute_gives_the_same_motion_in_more_steps(monkeypatch):
    kept = _run(monkeypatch, True)
    public = _run(monkeypatch, False)
    for name in ("revoluteDrive.phi", "prismatic.s", "prismatic.v"):
        scale = 1.0 + np.max(np.abs(kept[name]))
        # both runs' global errors, a few hundred rtol over one second, with room
        assert np.max(np.abs(public[name] - kept[name])) <= 1e3 * RTOL * scale, name
    assert public.stats["steps"] > kept.stats["steps"], (public.stats, kept.stats)


def test_only_a_pointer_ida_confirms_is_used(monkeypatch):
    seen = []
    real = ida.ida_memory

    def spy(solver, t0):
        mem = real(solver, t0)
        seen.append((mem, real(solver, t0 + 1.0)))      # IDA reports t0, not t0 + 1
        return mem
    monkeypatch.setattr(ida, "ida_memory", spy)
    _run(monkeypatch, True)
    assert seen and all(mem is not None and wrong is None for mem, wrong in seen), seen
    assert sundials_ext.suppress_algebraic(None) is False
