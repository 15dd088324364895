"""``export_fmu``: a compiled model as an FMI 2.0 FMU (Model Exchange or
Co-Simulation) with native binaries for this platform and its C sources.

What runs where: the CasADi-generated C of the index-reduced equations E,
their Jacobian, the relations' crossing functions, the start values and
the alias offsets, plus the fixed C runtime in ``c/`` (Newton solves with
the selected states held, consistent initialization, the event iteration,
and for Co-Simulation an L-stable SDIRK integrator with event location).
No Python is needed to load or run the FMU.
"""
import hashlib
import os
import platform
import shutil
import tempfile
import zipfile
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from ..errors import ModelDefinitionError, translated
from ..io.files import atomic_path
from ..runtime import cbuild
from .description import model_description
from .generate import casadi_sources, model_data_header
from ..library.inputs import bind_inputs
from ..runtime.evaluator import Evaluator
from ..runtime.events import relation_owner, values_from
from ..runtime.initialize import _guess_selection, choose_initial_conditions
from .. import __version__
from ..compiled import compile_model
from ..run_checks import _experiment
from ..io.output import check_writable
from ..options import RunOptions

C_DIR = os.path.join(os.path.dirname(__file__), "c")
C_FILES = ("a2d_core.c", "a2d_core.h", "a2d_fmi2.c", "a2d_cs.c", "a2d_cs.h",
           "fmi2Functions.h", "fmi2FunctionTypes.h", "fmi2TypesPlatform.h",
           "LICENSE_fmi2_headers.txt")
KINDS = ("me", "cs")
HIDDEN = ("-fvisibility=hidden", "-DCASADI_SYMBOL_EXPORT=")
"""Compiler flags: only the fmi2 functions are exported from the binary, so
that two FMUs of acausal2d models load into one process side by side."""


class DynamicStateSelectionError(ModelDefinitionError):
    """The model's states must change during a run: not exportable."""


@dataclass
class ExportData:
    """Everything the generated files need about one model."""
    system: object
    model_name: str
    identifier: str
    doc: str
    states: list
    held0: list
    p0: np.ndarray
    input_params: dict
    structural: frozenset
    units: dict
    experiment: RunOptions
    version: str
    guid: str = ""


def _held_at_start(compiled, p):
    """The nodes consistent initialization holds (as the runtime chooses them)."""
    s = compiled.system
    st = s.structure
    ev = Evaluator(s, p)
    z = np.zeros(st.n_var)
    z[s.level0] = s.start_fn(p).full().ravel()
    d = values_from(s, ev.crossings(0.0, z, np.zeros(len(s.relations))))
    sel = _guess_selection(s, ev, 0.0, z, d) if len(s.fixed_nodes) < st.n_var - st.n_eq else None
    states = st.state_nodes(sel) if sel is not None else ()
    return choose_initial_conditions(st, s.fixed_nodes, s.priority_names, s.has_start, states)


def _static_states(compiled, name, fixed_states=False):
    """States of the selection made at the start; DynamicStateSelectionError
    if a level of it had a real choice whose block may turn singular (the
    states may have to change), unless ``fixed_states``."""
    point = compiled.initial_point()
    s = compiled.system
    dynamic = [lv for lv in point.selection.levels if lv.dynamic and _may_turn_singular(s, lv)]
    if dynamic and not fixed_states:
        cands = sorted({s.node_info[j].name for lv in dynamic for j in lv.cands})[:8]
        raise DynamicStateSelectionError(
            "%s needs dynamic state selection (the states are chosen among %s at run time and "
            "may change during a run), which an FMU with fixed states cannot follow. Give "
            "state priorities so that the states are fixed: state_select='always' on the "
            "joint whose angle or travel should be the state (as PistonEngine does on "
            "revoluteDrive), then export again; or, if the states chosen at the start serve "
            "your runs (acausal2d simulate reports 0 state re-selections), export with "
            "--fixed-states (fixed_states=True): the FMU then stops with an error where that "
            "choice turns singular." % (name, ", ".join(cands)))
    return s.structure.state_nodes(point.selection)


def _check_discrete_memory(system):
    """The FMU's event handling decides each relation by the sign of its
    crossing function: a model with latches (the friction elements'
    Modelica modes) or reinits (hard stops) is refused, naming them."""
    owners = [relation_owner(system, k) for k, r in enumerate(system.relations)
              if r.g_start is not None] + [comp for comp, *_ in system.reinits]
    names = sorted({o.describe() for o in owners if o is not None})
    if names:
        raise ModelDefinitionError(
            "%s switch modes by latches or re-initialize states at events (Modelica's friction "
            "modes, hard stops), which the FMU's event handling does not support yet; give "
            "them law='zone' (the stick zone) to export the model" % ", ".join(names))


def _may_turn_singular(system, level):
    """Can the chosen dummy block of a level with a choice become singular
    during a run?  Not if its Jacobian does not depend on the unknowns (a
    chain whose dummies are explicit functions of the states, like the
    double pendulum's body coordinates): the states chosen at the start
    then serve the whole run."""
    st = system.structure
    eqs = ca.vertcat(*[st.eq_expr[i] for i in level.eqs])
    J = ca.jacobian(eqs, ca.vertcat(*[st.var_sym[j] for j in level.chosen]))
    return bool(ca.depends_on(J, ca.vertcat(*st.var_sym)))


def export_data(model, inputs=None, fixed_states=False, options=None, params=None):
    """:class:`ExportData` of a model instance (its RealInputs bound, see
    :func:`~acausal2d.library.inputs.bind_inputs`); ``options`` (a
    :class:`~acausal2d.options.RunOptions`) give the FMU's default
    experiment (stop time, tolerance) instead of the model's; ``params``
    the parameter values exported (a parameter the compiler reads compiles
    the model again with its value, as a run does)."""
    name = type(model).__name__
    model, input_params = bind_inputs(model, inputs)
    compiled = compile_model(model).for_values(params)
    _check_discrete_memory(compiled.system)
    p = compiled.parameter_values(params)
    with translated("preparing %s for export" % name):
        states = _static_states(compiled, name, fixed_states)
        held0 = _held_at_start(compiled, p)
    doc = (type(model).__doc__ or name).strip().splitlines()[0]
    structural = frozenset(n for n, *_ in compiled.parameters if compiled.is_structural(n))
    return ExportData(compiled.system, name, name, doc, list(states), list(held0), p,
                      input_params, structural, compiled.units,
                      (options or RunOptions()).resolved(_experiment(model)), __version__)


def write_sources(data, folder, kind):
    """All C sources and modelDescription.xml of the FMU into ``folder``
    (``folder/sources``); returns the source folder."""
    src = os.path.join(folder, "sources")
    os.makedirs(src, exist_ok=True)
    sizes = casadi_sources(data.system, src)
    for f in C_FILES:
        shutil.copy(os.path.join(C_DIR, f), src)
    digest = hashlib.sha256()
    for f in sorted(os.listdir(src)):
        with open(os.path.join(src, f), "rb") as fh:
            digest.update(fh.read())
    digest.update(kind.encode())
    digest.update(model_data_header(data, sizes).encode())     # numbers, with guid ""
    h = digest.hexdigest()
    data.guid = "{%s-%s-%s-%s-%s}" % (h[:8], h[8:12], h[12:16], h[16:20], h[20:32])
    with open(os.path.join(src, "a2d_model_data.h"), "w") as fh:
        fh.write(model_data_header(data, sizes))
    with open(os.path.join(folder, "modelDescription.xml"), "w") as fh:
        fh.write(model_description(data, kind))
    return src


def _platform_folder():
    bits = "64" if platform.architecture()[0] == "64bit" else "32"
    system = {"Linux": "linux", "Darwin": "darwin", "Windows": "win"}.get(platform.system(),
                                                                            "linux")
    return system + bits, {"linux": ".so", "darwin": ".dylib", "win": ".dll"}[system]


def build_binary(data, folder, src):
    """Compile the sources into binaries/<platform>/<identifier>.<so|dylib|dll>
    (with :mod:`acausal2d.runtime.cbuild`: the compiler found at export time,
    builds cached by content; the packed copy checked against the digest
    recorded at the build, so a damaged cache is never packed)."""
    plat, ext = _platform_folder()
    out = os.path.join(folder, "binaries", plat)
    os.makedirs(out, exist_ok=True)
    sources = {}
    for f in sorted(os.listdir(src)):
        if f.endswith((".c", ".h")):
            with open(os.path.join(src, f), encoding="utf-8") as fh:
                sources[f] = fh.read()
    target = os.path.join(out, data.identifier + ext)
    return cbuild.copy_verified(cbuild.build(sources, flags=HIDDEN, libraries=("m",),
                                             name="fmu-" + data.identifier), target)


def export_fmu(model: Any, kind: str = "me", out: "str | None" = None, inputs: Any = None,
               fixed_states: bool = False, options: "RunOptions | None" = None,
               params: Any = None) -> str:
    """Export ``model`` (a model instance) as an FMI 2.0 FMU file.

    kind: ``"me"`` (Model Exchange) or ``"cs"`` (Co-Simulation); out: the
    .fmu path (default ``<ModelName>.fmu``); inputs: {RealInput name: start
    value}; fixed_states: export a model with dynamic state selection with
    the states chosen at the start (the FMU stops with an error where they
    no longer serve); options: a :class:`~acausal2d.options.RunOptions`
    whose stop_time and rtol become the FMU's default experiment (default:
    the model's ``experiment``); params: {parameter: value} exported
    instead of the model's values (a parameter the compiler reads is a
    constant of the FMU, so this is how another value of it is exported).
    Returns the path.  Raises
    :class:`DynamicStateSelectionError` for a model whose states may have to
    change during a run (unless ``fixed_states``)."""
    if kind not in KINDS:
        raise ModelDefinitionError("kind must be 'me' (Model Exchange) or 'cs' (Co-Simulation), "
                                   "got %r" % (kind,))
    if out is not None:
        _check_target(out)                 # before the model is compiled and built
    data = export_data(model, inputs, fixed_states, options, params)
    out = out or data.identifier + ".fmu"
    _check_target(out)
    with tempfile.TemporaryDirectory() as tmp:
        src = write_sources(data, tmp, kind)
        build_binary(data, tmp, src)
        with atomic_path(out) as part:     # removed on any failure, Ctrl-C included
            with zipfile.ZipFile(part, "w", zipfile.ZIP_DEFLATED) as z:
                for root, _, files in os.walk(tmp):
                    for f in files:
                        full = os.path.join(root, f)
                        z.write(full, os.path.relpath(full, tmp))
    return out


def _check_target(out):
    """The .fmu path ``out`` can be written: not a folder, in an existing,
    writable folder (checked before the build)."""
    if os.path.isdir(out):
        raise ModelDefinitionError("--out %s is a folder; give the path of the .fmu file "
                                   "(e.g. %s)" % (out, os.path.join(out, "Model.fmu")))
    folder = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(folder):
        raise ModelDefinitionError("cannot write %s: the folder %s does not exist" % (out, folder))
    check_writable(folder, "the folder of --out")
