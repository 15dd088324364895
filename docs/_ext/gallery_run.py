"""One gallery entry: load, compile and simulate one model of ``models/``
with its own experiment, draw its figures (the model's declared
``figures``, else its outputs, else its states) and write its animation
page.  Runs in a worker process of :mod:`gallery` (one model per call)."""
import os
import time

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


def run_model(path, name, folder, anim_folder):
    """Simulate model ``name`` of the file ``path``; its diagram and figures
    go to ``folder``, the animation page to ``anim_folder``.  Returns a
    dict: name, doc, diagram, figures, animation, summary (or error)."""
    start = time.perf_counter()
    stem = safe_filename("_".join([os.path.splitext(os.path.basename(path))[0]] +
                                  ([name] if name else [])))
    model = acausal2d.load_model(path, name)
    doc = _doc(type(model)).replace(os.path.abspath(path), os.path.relpath(path, ROOT))
    entry = {"name": name, "doc": doc, "figures": [], "animation": None,
             "diagram": stem + "_diagram.svg"}
    write_diagram(model, os.path.join(folder, entry["diagram"]))
    model, inputs = bind_inputs(model)      # inputs of an FMU model: held at 0 here
    if inputs:
        entry["note"] = "Its inputs %s are held at 0 by constant sources here (as `linearize` " \
            "does); an FMU of it takes them from the importing tool." % ", ".join(sorted(inputs))
    try:
        res = acausal2d.compile_model(model).simulate()
    except acausal2d.SimulationError as exc:
        res = getattr(exc, "result", None)
        if res is None:
            raise
        entry["stopped"] = str(exc).splitlines()[0]
    for k, (groups, x, title) in enumerate(_figure_specs(res, model)):
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
