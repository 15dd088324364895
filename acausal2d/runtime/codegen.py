"""What C a native library is generated from, and how large it may be.

A :class:`Recipe` names a library's CasADi functions and the C appended to
their code; :func:`generate` writes the C with CasADi's code generator
(:data:`CODEGEN`); :func:`optimization` chooses the compiler flags by size
and :func:`too_large` refuses sizes that would take too long to compile at
run time.  Recipes are pickled (their functions serialized) for the
background worker (:mod:`~acausal2d.runtime.background`).
"""

import casadi as ca

from . import cbuild
from . import drivers
from .drivers import GCC_LIMITS, is_gcc

NATIVE_BELOW = 1_000_000     # no native code from this size on (the Python path)
CHARS_PER_INSTRUCTION = 20   # generated C per CasADi instruction, low (measured: 23-30)
"""Compile time of the generated C grows with its size and is paid once per
model structure and machine (gcc, measured: piston engine 36 kB 0.25 s at
-O1; chain of 20 links 157 kB 1.2 s; belt drive 856 kB about 3 s for its
first simulate; chain of 100 links 787 kB 7.2 s at -O1, 2.3 s at -O0).
-O0 code was 1.4x (chain) to 3.6x (belt drive) slower in warm runs, so -O1
is kept; above :data:`NATIVE_BELOW` large models keep the Python path.
A library is compiled by the detached worker after a run (or first, in
mode ``now``), so its compile time delays only the runs that follow."""
def eliminated(fn):
    """``fn`` with its common subexpressions merged (``casadi.cse``): the
    same operations on the same inputs, so the same values to the last bit,
    in fewer instructions (belt drive: residual 7374 -> 3737, iteration
    matrix 24662 -> 9408; piston engine 268 -> 256, 322 -> 262).  Functions
    other than SX functions are returned as they are."""
    if not fn.is_a("SXFunction"):
        return fn
    args = fn.sx_in()
    outs = fn(*args)
    outs = [ca.cse(o) for o in (outs if isinstance(outs, (list, tuple)) else [outs])]
    return ca.Function(fn.name(), args, outs, fn.name_in(), fn.name_out())


def _residual_and_jacobian(residual_fn, jacobian_fn):
    """E and dE/dz as one function "EJ" (their shared subexpressions once)."""
    args = residual_fn.sx_in()
    outs = [residual_fn(*args), jacobian_fn(*args)]
    return ca.Function("EJ", args, ca.cse(outs))


CODEGEN = {"with_header": False}
"""CasADi's code generator options (``avoid_stack`` compiled the chain of 81
links in 0.43x the wall time but ran it 1.8x slower)."""


def generate(recipe):
    """The C text of a :class:`Recipe`: CasADi's code of its functions,
    then its suffix.  Its size is what the size limits measure
    (:func:`optimization`)."""
    cg = ca.CodeGenerator(recipe.name + ".c", CODEGEN)
    for how, fns in recipe.parts:
        if how == "ej":
            cg.add(_residual_and_jacobian(*fns))
        else:
            for fn in fns:
                cg.add(eliminated(fn) if how == "cse" else fn)
    return cg.dump() + "\n" + recipe.suffix


def too_large(*functions):
    """True where the C of these CasADi functions would be too large to
    compile at run time (estimated from their instruction counts)."""
    count = 0
    for fn in functions:
        try:
            count += fn.n_instructions()
        except RuntimeError:       # not an SX/MX function (a map): judged by its code
            pass
    return count * CHARS_PER_INSTRUCTION >= NATIVE_BELOW


def optimization(size, compiler=None):
    """The compiler flags for ``size`` characters of generated C
    (:func:`generate`), or None: too large to compile at run time (see
    :data:`NATIVE_BELOW`); -O1, with gcc's alias query limits
    (:data:`GCC_LIMITS`) where ``compiler`` is gcc."""
    if size >= NATIVE_BELOW:
        return None
    return ["-O1"] + (list(GCC_LIMITS) if is_gcc(compiler) else [])


class Recipe:
    """What a library is generated from: ``parts`` is a list of (how,
    CasADi functions) - how is "plain" (added as it is), "cse" (common
    subexpressions merged, :func:`eliminated`) or
    "ej" (residual and Jacobian as one function); ``suffix`` is C appended
    to CasADi's code; ``objects`` name the drivers' objects
    (:data:`~acausal2d.runtime.drivers.OBJECTS`, compiled once per machine
    by :func:`~acausal2d.runtime.cbuild.build_object`) linked in; ``libraries`` and ``library_dirs`` are linked."""

    def __init__(self, name, parts, suffix="", libraries=(), library_dirs=(), objects=()):
        self.name, self.parts, self.suffix = name, list(parts), suffix
        self.libraries, self.library_dirs = list(libraries), list(library_dirs)
        self.objects = list(objects)

    def __getstate__(self):
        parts = [(how, [cbuild.serialized(fn) for fn in fns]) for how, fns in self.parts]
        state = dict(self.__dict__, parts=parts)
        state.pop("_code", None)
        state.pop("_size", None)
        return state

    def __setstate__(self, state):
        state["parts"] = [(how, [cbuild.deserialized(s) for s in fns])
                          for how, fns in state["parts"]]
        self.__dict__.update(state)

    @staticmethod
    def _object_flags():
        return drivers.flags(cbuild.find_compiler())

    def code(self):
        """The C compiled (:func:`generate`'s), made once per recipe."""
        if getattr(self, "_code", None) is None:
            self._code = generate(self)
        return self._code

    def size(self):
        """Characters of :func:`generate`'s C (what the limits measure)."""
        return len(self.code())

    def make(self):
        """Generate the C and compile it (:func:`~acausal2d.runtime.cbuild.
        build`); the library's path."""
        code = self.code()
        flags = optimization(self.size(), cbuild.find_compiler())
        if flags is None:
            raise cbuild.BuildFailed("the generated C of %s is too large to compile at run "
                                     "time (%d characters)" % (self.name, self.size()))
        objects = [cbuild.build_object(drivers.text(name), self._object_flags(), name)
                   for name in self.objects]
        return cbuild.build({self.name + ".c": code}, flags=flags, libraries=self.libraries,
                            library_dirs=self.library_dirs, name=self.name, objects=objects)
