"""What the tier tests share (tests/test_native_tiers.py,
tests/test_native_tiers_build.py): the skip where no native code can be
built, a fresh cache with this process's queue emptied (and its notices
shown), and the agreement of two runs to the integration tolerance."""
import logging

import numpy as np
import pytest

from acausal2d.runtime import background, cbuild, drivers, native, notices, tiers

NEEDS_NATIVE = pytest.mark.skipif(cbuild.find_compiler() is None or not native.enabled(),
                                  reason="no C compiler or another SUNDIALS")
WAIT = 600.0           # s: a worker that does not end by then is a hang


def fresh_cache(tmp_path, monkeypatch):
    """Mode auto with an empty cache of its own and this process's queue,
    the driver objects installed with the package ignored (a machine that
    never compiled them; undone by ``monkeypatch``); the cache folder."""
    monkeypatch.setenv(tiers.ENV, "auto")
    monkeypatch.setenv(drivers.ENV, "0")
    monkeypatch.setenv(cbuild.CACHE_ENV, str(tmp_path / "cache"))
    monkeypatch.setattr(background, "_queue", [])
    monkeypatch.setattr(background, "_seen", set())
    monkeypatch.setattr(background, "_workers", [])
    monkeypatch.setattr(notices, "_said", set())
    log = notices.logger()           # the first-run notices asked for, as the command line does
    monkeypatch.setattr(log, "level", logging.INFO)
    monkeypatch.setattr(log, "_cache", {})
    return tmp_path / "cache"


def agree(a, b, names, rtol):
    """Two runs agree to the integration tolerance: each signal within
    1000 rtol of its range (both runs' global errors, a few hundred rtol
    at most over these short runs, with room)."""
    for name in names:
        scale = 1.0 + np.max(np.abs(b[name]))
        assert np.max(np.abs(a[name] - b[name])) <= 1e3 * rtol * scale, name


def native_runs(monkeypatch):
    """A list that gets the library of each native segment run (a
    structure's compiled library or the driver on CasADi's C API), for
    the rest of the test."""
    runs = []
    real = native.NativeIDA.run
    monkeypatch.setattr(native.NativeIDA, "run",
                        lambda self, *a: runs.append(self.lib) or real(self, *a))
    return runs
