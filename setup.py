"""Install-time step of acausal2d (everything else is in pyproject.toml).

The native drivers' constant C is compiled into the package while it is
installed, where a C compiler is found (:mod:`acausal2d.runtime.drivers`):
without it a machine's first native run would wait about a second for
gcc.  Without a compiler, or where the compiler fails, the install goes on
and the drivers are compiled on first use instead.  Because the package
then holds object files of this machine, its wheel is tagged for this
platform (:class:`PlatformDistribution`).
"""
import importlib
import os
import sys
import types

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution

ROOT = os.path.dirname(os.path.abspath(__file__))


def _drivers():
    """``acausal2d/runtime/drivers.py`` of this source tree, imported as
    ``_acausal2d_source.runtime.drivers`` without running the package's
    ``__init__`` (its dependencies are not installed yet: the module and
    what it imports use the standard library only), and never an installed
    acausal2d of the same name."""
    for name, folder in (("_acausal2d_source", "acausal2d"),
                         ("_acausal2d_source.runtime", "acausal2d/runtime")):
        if name not in sys.modules:
            module = types.ModuleType(name)
            module.__path__ = [os.path.join(ROOT, folder)]
            sys.modules[name] = module
    return importlib.import_module("_acausal2d_source.runtime.drivers")


class BuildWithDrivers(build_py):
    """``build_py``, then the drivers' objects compiled into the package (the
    source tree for an editable install)."""

    def run(self):
        super().run()
        if getattr(self, "editable_mode", False):
            dest = os.path.join(ROOT, "acausal2d", "runtime", "prebuilt")
        else:
            dest = os.path.join(self.build_lib, "acausal2d", "runtime", "prebuilt")
        try:
            built = _drivers().install(dest, log=lambda text: print(text, file=sys.stderr))
        except Exception as exc:  # noqa: BLE001 - never fail an install: compiled on first use
            print("acausal2d: the native drivers were not compiled at install (%s: %s); they "
                  "are compiled on first use" % (type(exc).__name__, exc), file=sys.stderr)
            return
        print("acausal2d: compiled %d native driver objects into %s" % (len(built), dest),
              file=sys.stderr)


class PlatformDistribution(Distribution):
    """A distribution that holds compiled code: its wheel is not pure."""

    def has_ext_modules(self):
        return True


setup(cmdclass={"build_py": BuildWithDrivers}, distclass=PlatformDistribution)
