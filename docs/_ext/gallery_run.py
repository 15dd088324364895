"""One gallery entry: load, compile and simulate one model of ``models/``
with its own experiment, draw its figures (the model's declared
``figures``, else its outputs, else its states) and write its animation
page.  Runs in a worker process of :mod:`gallery` (one model per call)."""
import os
import time
import warnings

# The gallery's runs are short and each model structure runs once: the Python path, no C
# compiled for them (no background compiles outliving the build); set it to override.
os.environ.setdefault("ACAUSAL2D_NATIVE", "off")

import acausal2d  # noqa: E402
from acausal2d.io.files import safe_filename  # noqa: E402
from acausal2d.library.inputs import bind_inputs  # noqa: E402
from acausal2d.visual.animation import render_html  # noqa: E402
from acausal2d.visual.diagram import write_diagram  # noqa: E402
from acausal2d.visual.plotting import declared_figures, plot  # noqa: E402
from acausal2d.visual.scene import build_scene  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MAX_FIGURES = 3
ANIMATION_FRAMES = 200


def _figure_specs(res, model):
    """[(groups, x, title)] of the figures of a run."""
    specs = [(s["groups"], s.get("x"), s.get("title")) for s in declared_figures(model)]
    if not specs:
        names = [n for n in res.outputs if n in res] or \
            [n for n in (getattr(res, "states", None) or []) if n in res][:4] or res.names[:3]
        specs = [([[n] for n in names], None, None)]
    return specs[:MAX_FIGURES]


def _doc(obj):
    """The first paragraph of a docstring, on one line."""
    text = (obj.__doc__ or "").strip().split("\n\n")[0]
    return " ".join(text.split())


def _load_and_compile(path, name):
    """(model, the model with its free inputs bound, their names, the bound
    model compiled) of a shipped model, a DeprecationWarning raised as an
    error: a model of the gallery on a former interface (a pulley's x0, y0,
    phi0, w, the relative flange ctrR) fails the build instead of teaching
    it."""
    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        try:     # the loader and the compiler wrap warnings raised in __init__/equations()
            model = acausal2d.load_model(path, name)
            bound, inputs = bind_inputs(model)      # inputs of an FMU model: held at 0 here
            return model, bound, inputs, acausal2d.compile_model(bound)
        except acausal2d.ModelDefinitionError as exc:
            if "DeprecationWarning" in str(exc):
                raise DeprecationWarning("%s: %s" % (os.path.relpath(path, ROOT), exc)) from exc
            raise


def run_model(path, name, folder, anim_folder):
    """Simulate model ``name`` of the file ``path``; its diagram and figures
    go to ``folder``, the animation page to ``anim_folder``.  Returns a
    dict: name, doc, diagram, figures, animation, summary (or error)."""
    start = time.perf_counter()
    stem = safe_filename("_".join([os.path.splitext(os.path.basename(path))[0]] +
                                  ([name] if name else [])))
    model, bound, inputs, compiled = _load_and_compile(path, name)
    doc = _doc(type(model)).replace(os.path.abspath(path), os.path.relpath(path, ROOT))
    entry = {"name": name, "doc": doc, "figures": [], "animation": None,
             "diagram": stem + "_diagram.svg"}
    write_diagram(model, os.path.join(folder, entry["diagram"]))
    if inputs:
        entry["note"] = "Its inputs %s are held at 0 by constant sources here (as `linearize` " \
            "does); an FMU of it takes them from the importing tool." % ", ".join(sorted(inputs))
    try:
        res = compiled.simulate()
    except acausal2d.SimulationError as exc:
        res = getattr(exc, "result", None)
        if res is None:
            raise
        entry["stopped"] = str(exc).splitlines()[0]
    for k, (groups, x, title) in enumerate(_figure_specs(res, bound)):
        png = os.path.join(folder, "%s_%d.png" % (stem, k + 1))
        plot(res, groups, png, title=title, x=x)
        entry["figures"].append(os.path.basename(png))
    page = render_html(build_scene(res), max_frames=ANIMATION_FRAMES)
    os.makedirs(anim_folder, exist_ok=True)
    with open(os.path.join(anim_folder, stem + ".html"), "w", encoding="utf-8") as fh:
        fh.write(page)
    entry["animation"] = stem + ".html"
    entry["summary"] = "%d output points, %d events, %d steps; compiled, run and drawn in " \
        "%.1f s" % (len(res.time), len(res.events), res.stats.get("steps", 0),
                    time.perf_counter() - start)
    if res.stopped:
        entry["stopped"] = res.stopped
    return entry
