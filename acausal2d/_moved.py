"""Import paths of modules that moved when the package was laid out by
concern (acausal2d 0.2): the old dotted names stay importable and are the
same module objects as the new ones, so ``from acausal2d.tools.cli import
main`` and ``import acausal2d.library.planar_forces`` keep working.

The table :data:`MOVED` is the only place that knows the old names.  A
finder on ``sys.meta_path`` answers an old name by importing the new module
and registering it under the old name too; nothing is imported before a
user asks for it.
"""
import importlib
import importlib.abc
import importlib.machinery
import sys
import types

MOVED = {
    # acausal2d.tools -> by what a user does
    "acausal2d.tools.compiled": "acausal2d.compiled",
    "acausal2d.tools.result": "acausal2d.result",
    "acausal2d.tools.check": "acausal2d.analysis.check",
    "acausal2d.tools.compare": "acausal2d.analysis.compare",
    "acausal2d.tools.study": "acausal2d.analysis.study",
    "acausal2d.tools.sweep": "acausal2d.analysis.sweep",
    "acausal2d.tools.plotting": "acausal2d.visual.plotting",
    "acausal2d.tools.scene": "acausal2d.visual.scene",
    "acausal2d.tools.animation": "acausal2d.visual.animation",
    "acausal2d.tools.loader": "acausal2d.io.loader",
    "acausal2d.tools.mec2": "acausal2d.io.mec2",
    "acausal2d.tools.files": "acausal2d.io.files",
    "acausal2d.tools.cli": "acausal2d.cli",
    # acausal2d.library: flat modules -> subpackages after the seed
    "acausal2d.library.planar_forces": "acausal2d.library.planar.forces",
    "acausal2d.library.planar_sensors": "acausal2d.library.planar.sensors",
    "acausal2d.library.linkage_drives": "acausal2d.library.linkage.drives",
    "acausal2d.library.belt_curved": "acausal2d.library.belt.curved",
    "acausal2d.library.crane": "acausal2d.library.belt.crane",
    "acausal2d.library.band_synthesis": "acausal2d.library.synthesis",
    "acausal2d.library.band_functional": "acausal2d.library.synthesis.functional",
    "acausal2d.library.band_assessment": "acausal2d.library.synthesis.assessment",
    "acausal2d.library.band_balancing": "acausal2d.library.synthesis.balancing",
    "acausal2d.library.contour_export": "acausal2d.library.synthesis.contour_export",
    "acausal2d.library.node_drives": "acausal2d.library.nodes.drives",
    "acausal2d.library.node_correction": "acausal2d.library.nodes.correction",
}
"""Old dotted module name -> the module that holds its contents now."""

OLD_PACKAGES = {
    "acausal2d.tools": "the user tools, now acausal2d.compiled, acausal2d.result, "
                       "acausal2d.analysis, acausal2d.visual, acausal2d.io and acausal2d.cli",
}
"""Old packages that no longer exist as folders: importing them gives an
empty package through which the old submodule names of :data:`MOVED` import."""


class _Alias(importlib.abc.Loader):
    """Loader that hands out an already imported module under another name.

    The import system stamps the alias's spec on the module it gets back;
    :meth:`exec_module` puts the module's own spec back, or its relative
    imports would resolve against the old package (and Python warns
    ``__package__ != __spec__.parent``)."""

    def __init__(self, target):
        self.target = target
        self.own_spec = None

    def create_module(self, spec):
        if self.target is None:
            module = types.ModuleType(spec.name, OLD_PACKAGES[spec.name])
            module.__path__ = []
            return module
        module = importlib.import_module(self.target)
        self.own_spec = module.__spec__
        return module

    def exec_module(self, module):
        if self.own_spec is not None:
            module.__spec__ = self.own_spec


class _MovedFinder(importlib.abc.MetaPathFinder):
    """Finds the old names of :data:`MOVED` and :data:`OLD_PACKAGES`."""

    def find_spec(self, fullname, path=None, target=None):
        if fullname in MOVED:
            loader = _Alias(MOVED[fullname])
        elif fullname in OLD_PACKAGES:
            loader = _Alias(None)
        else:
            return None
        return importlib.machinery.ModuleSpec(fullname, loader,
                                              is_package=fullname in OLD_PACKAGES)


def install():
    """Put the finder on ``sys.meta_path`` once (called by ``acausal2d``)."""
    if not any(isinstance(f, _MovedFinder) for f in sys.meta_path):
        sys.meta_path.append(_MovedFinder())
