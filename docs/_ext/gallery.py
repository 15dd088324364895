"""Sphinx extension: the gallery and the API reference, written into the
source folder when the build starts.

Gallery: every model of ``models/`` (each model class of each ``*.py``
file, see :func:`acausal2d.io.loader.model_names`, and each mec2
``models/mec2/*.json``) is simulated with its own experiment in a pool of
worker processes (:mod:`gallery_run`), and ``gallery/<file>.md`` shows its
figures and its animation page.  The pages are grouped by the chapters of
the dissertation and Schnabel and Gössner's talk (:data:`GROUPS`; a file not named there is
listed under "Other models").  A model that fails is a build warning, so
``sphinx-build -W`` fails.

API reference: one page per part of the package, ``automodule`` of every
public module found by walking the package, so modules added later are
documented without editing the site.
"""
import concurrent.futures
import glob
import multiprocessing
import os
import pkgutil
import time

from sphinx.util import logging

LOG = logging.getLogger(__name__)
DOCS = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ROOT = os.path.dirname(DOCS)

GROUPS = [
    ("First models (built step by step in the documentation)",
     ["first_belt_drive", "first_rope_drive", "first_drive_train", "first_hydraulic_circuit",
      "first_linkage", "first_planar_mechanism"]),
    ("Dissertation ch. 2: joints, degree of freedom, linkages, band and rope mechanisms",
     ["four_link_mechanisms", "dof_bild_2_1", "cam_follower", "rope_drives",
      "band_mechanisms", "band_systematics"]),
    ("Dissertation ch. 3: problem examples and balancing", ["accessory_drive", "hain_spring_lever"]),
    ("Dissertation ch. 7: the VDI 2729 eight-link mechanism, balancing, belt and rope drives",
     ["eight_link_vdi2729", "cabinet_door", "db_ds_synthesis", "pulley_block",
      "noncircular_belt_drive"]),
    ("Dissertation ch. 8: cable crane and belt-driven compressor",
     ["cable_crane", "hydraulic_drum_drive", "hydraulic_cable_crane", "compressor", "clutch_motor",
      "belt_span_rig"]),
    ("Modelica PlanarMechanics references (Dymola results in tests/data/references)",
     ["pendulum", "double_pendulum", "crane_crab", "piston_engine", "piston_engine_dynamic",
      "planar_examples"]),
    ("Schnabel and Gössner's talk: nodes, constraints, constructions and mec2",
     ["talk_mechanisms", "talk_mechanisms_vdi", "talk_constructions", "talk_synthesis",
      "mec2"]),
    ("Calibration, optimisation, linearisation and FMU export",
     ["four_bar_precision", "four_bar_modes", "four_bar_torque"]),
]
"""(chapter, [model file stems]) in the order of the gallery."""

_FUNCS = "\n".join(".. autofunction:: acausal2d.%s" % f for f in (
    "load_model", "compile_model", "simulate", "check"))
_STUDIES = "\n".join(".. autofunction:: acausal2d.%s" % f for f in (
    "sweep", "study", "fit", "optimize", "export_fmu"))

API_PAGES = [
    ("run", "Load, compile and simulate",
     "A model file or class in, a compiled model out; run it as often as you like.",
     [_FUNCS], ["acausal2d!", "acausal2d.compiled"]),
    ("result", "Result: signals, plots, files", "What a run returns.", [], ["acausal2d.result"]),
    ("run-options", "RunOptions: stop time, tolerances, limits",
     "One value for the settings of every run.", [], ["acausal2d.options"]),
    ("compare", "Compare with a reference", "A result against a reference curve in a tube.",
     [".. autofunction:: acausal2d.compare"], ["acausal2d.analysis.compare"]),
    ("studies", "Sweeps, studies, fit, optimize, FMU export",
     "Many runs of one compiled model.", [_STUDIES], []),
    ("modelling", "Writing models: components, connectors, parameters",
     "The modelling language: what a model class is made of.", [], ["acausal2d.language"]),
    ("errors", "Errors", "What a failed call raises.", [], ["acausal2d.errors"]),
    ("library", "Library overview", "The component library, by domain on the pages that follow.",
     [], ["acausal2d.library!"]),
    ("library-planar", "Library: planar bodies, joints, forces and cams",
     "Modelica PlanarMechanics in Python.", [], ["acausal2d.library.planar"]),
    ("library-linkage", "Library: VDI 2729 linkage elements",
     "DAN, SAN, FGP and the dyads (Ebert 2015, ch. 4.2, Anhang B).", [],
     ["acausal2d.library.linkage"]),
    ("library-belt", "Library: belts, pulleys, drums and ropes",
     "Belt and rope drives (Ebert 2015, ch. 4.4).", [], ["acausal2d.library.belt"]),
    ("library-synthesis", "Library: band synthesis and balancing",
     "Cam contours for a prescribed motion (Ebert 2015, ch. 4.3, 5, 6).", [],
     ["acausal2d.library.synthesis"]),
    ("library-drive-train", "Library: drive trains, signals and controllers",
     "1D rotational and translational elements, sources and controllers (Modelica's names).",
     [], ["acausal2d.library.rotational", "acausal2d.library.translational",
          "acausal2d.library.gears", "acausal2d.library.friction1d", "acausal2d.library.signals",
          "acausal2d.library.blocks", "acausal2d.library.controllers",
          "acausal2d.library.inputs"]),
    ("library-fluid", "Library: hydraulics and pneumatics", "Fluid power.", [],
     ["acausal2d.library.hydraulics", "acausal2d.library.pneumatics"]),
    ("library-nodes", "Library: nodes, constraints and mec2",
     "Mechanisms as nodes and constraints (Schnabel and Gössner).", [],
     ["acausal2d.library.nodes"]),
    ("analysis", "Analysis", "Checks, studies, fits, linearisation and kinematics.", [],
     ["acausal2d.analysis"]),
    ("visual", "Plots, animation, notebooks", "", [], ["acausal2d.visual"]),
    ("files", "Files: models, tables, result files", "", [], ["acausal2d.io"]),
    ("fmu", "FMU export", "", [], ["acausal2d.fmu"]),
    ("explore", "The explore page", "", [], ["acausal2d.explore"]),
    ("command-line", "Command line", "", [], ["acausal2d.cli"]),
    ("compiler", "Compiler", "", [], ["acausal2d.compiler"]),
    ("runtime", "Runtime", "", [], ["acausal2d.runtime"]),
    ("internals", "Helpers: arguments, derived values, progress, threads, protocols", "", [],
     ["acausal2d.arguments", "acausal2d.derived", "acausal2d.progress", "acausal2d.threads",
      "acausal2d.protocols"]),
]
"""(file stem, title, one line, [reStructuredText blocks], [modules]) of the API
reference's pages, in the order a user reaches for them.  A module name matches
itself and its submodules; with a trailing ``!`` only itself.  A public module no
page names is documented on the page "Other modules"."""


def _write(path, text):
    """Write ``text`` unless the file already holds it (no needless rebuilds)."""
    os.makedirs(os.path.dirname(path), exist_ok=True)
    try:
        with open(path, encoding="utf-8") as fh:
            if fh.read() == text:
                return
    except OSError:
        pass
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text)


# ---------------------------------------------------------------- gallery
def _model_files():
    """{stem: [(path, model name or None)]} of models/ (mec2 files under 'mec2')."""
    from acausal2d.io.loader import model_names
    files = {}
    for path in sorted(glob.glob(os.path.join(ROOT, "models", "*.py"))):
        names = model_names(path)
        if names:
            files[os.path.splitext(os.path.basename(path))[0]] = [(path, n) for n in names]
    mec2 = sorted(glob.glob(os.path.join(ROOT, "models", "mec2", "*.json")))
    if mec2:
        files["mec2"] = [(p, None) for p in mec2]
    return files


def _cache_key(path, name):
    """Hash of what an entry depends on: the model file, the package's
    sources (any module may change the run) and the gallery runner."""
    import hashlib
    import acausal2d
    digest = hashlib.sha256()
    sources = sorted(glob.glob(os.path.join(os.path.dirname(acausal2d.__file__), "**", "*.py"),
                               recursive=True) +
                     glob.glob(os.path.join(ROOT, "library", "**", "*.py"), recursive=True))
    for source in [path, os.path.join(DOCS, "_ext", "gallery_run.py")] + sources:
        with open(source, "rb") as fh:
            digest.update(fh.read())
    digest.update(str(name).encode())
    return digest.hexdigest()[:20]


def _cached(cache, key, folder, anim_folder):
    """The entry stored under ``key`` with its files copied back, or None."""
    import json
    import shutil
    try:
        with open(os.path.join(cache, key + ".json"), encoding="utf-8") as fh:
            entry = json.load(fh)
        for png in entry["figures"] + [entry["diagram"]]:
            shutil.copy2(os.path.join(cache, png), os.path.join(folder, png))
        os.makedirs(anim_folder, exist_ok=True)
        shutil.copy2(os.path.join(cache, entry["animation"]),
                     os.path.join(anim_folder, entry["animation"]))
    except (OSError, ValueError, KeyError):
        return None
    return entry


def _store(cache, key, entry, folder, anim_folder):
    import json
    import shutil
    os.makedirs(cache, exist_ok=True)
    for png in entry["figures"] + [entry["diagram"]]:
        shutil.copy2(os.path.join(folder, png), os.path.join(cache, png))
    shutil.copy2(os.path.join(anim_folder, entry["animation"]),
                 os.path.join(cache, entry["animation"]))
    with open(os.path.join(cache, key + ".json"), "w", encoding="utf-8") as fh:
        json.dump(entry, fh)


def _run_all(files, folder, anim_folder):
    """{(path, name): entry or exception} of every model, on 2 workers;
    entries whose sources did not change since the last build of this
    folder come from ``_build/gallery-cache``."""
    from gallery_run import run_model
    cache = os.path.join(DOCS, "_build", "gallery-cache")
    jobs = [job for stem in files for job in files[stem]]
    keys = {job: _cache_key(*job) for job in jobs}
    out = {job: _cached(cache, keys[job], folder, anim_folder) for job in jobs}
    todo = [job for job in jobs if out[job] is None]
    LOG.info("gallery: %d models, %d from the cache, %d to run on 2 workers"
             % (len(jobs), len(jobs) - len(todo), len(todo)))
    ctx = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(max_workers=2, mp_context=ctx) as pool:
        futures = {pool.submit(run_model, path, name, folder, anim_folder): (path, name)
                   for path, name in todo}
        for k, fut in enumerate(concurrent.futures.as_completed(futures)):
            job = futures[fut]
            try:
                out[job] = fut.result()
                _store(cache, keys[job], out[job], folder, anim_folder)
            except Exception as exc:       # reported as a warning: -W fails the build
                out[job] = exc
            LOG.info("gallery: [%d/%d] %s %s%s" % (k + 1, len(todo), os.path.relpath(job[0], ROOT),
                                                   job[1] or "", " failed" if
                                                   isinstance(out[job], Exception) else ""))
    return out


def _entry_text(path, name, entry):
    """The Markdown of one model on its file's page."""
    rel = os.path.relpath(path, ROOT)
    title = name or os.path.basename(path)
    command = "acausal2d simulate %s%s" % (rel, " --model " + name if name else "")
    lines = ["## %s" % title, "", entry["doc"] or "", "", "```", command, "```", "",
             "![diagram of %s](%s)" % (title, entry["diagram"]), ""]
    for png in entry["figures"]:
        lines += ["![%s](%s)" % (title, png), ""]
    lines += ["```{raw} html",
              "<iframe src=\"../gallery-animations/%s\" loading=\"lazy\" "
              "style=\"width:100%%;height:520px;border:1px solid #ccc\" "
              "title=\"animation of %s\"></iframe>" % (entry["animation"], title),
              "<p><a href=\"../gallery-animations/%s\">The animation on a page of its own</a></p>"
              % entry["animation"], "```", ""]
    if entry.get("note"):
        lines += [entry["note"], ""]
    if entry.get("stopped"):
        lines += ["The run stops early: %s" % entry["stopped"], ""]
    lines += ["*%s.*" % entry["summary"], ""]
    return "\n".join(lines)


def _file_doc(stem, models):
    """The first paragraph of a model file's docstring, on one line."""
    if stem == "mec2":
        return "Mechanisms in mec2's JSON format (Schnabel and Gössner), imported as node models."
    import ast
    with open(models[0][0], encoding="utf-8") as fh:
        doc = ast.get_docstring(ast.parse(fh.read())) or ""
    return " ".join(doc.strip().split("\n\n")[0].split())


def _first_sentence(text):
    """The first sentence of ``text`` (a full stop before a capital ends it; "eq. 4.1",
    "ch. 2" and "e.g. a" do not)."""
    import re
    first = re.split(r"(?<=[a-z0-9)\]])\.\s+(?=[A-Z])", text, maxsplit=1)[0]
    if len(first) > 140 and first.find(": ") > 30:          # a long one: up to its colon
        first = first[:first.find(": ")]
    if len(first) > 160 and first.find(" (") > 30:          # still long: up to its first aside
        first = first[:first.find(" (")]
    return first.rstrip(":. ") + "."


def _file_page(stem, models, results):
    """The page of one model file (or of the mec2 models)."""
    doc = _file_doc(stem, models)
    title = "mec2 models" if stem == "mec2" else "%s.py" % stem
    parts = ["# %s" % title, "", doc, ""]
    for path, name in models:
        entry = results[(path, name)]
        if isinstance(entry, Exception):
            LOG.warning("gallery: %s %s failed: %s: %s" % (path, name or "", type(entry).__name__,
                                                           entry))
            continue
        if not entry["figures"]:
            LOG.warning("gallery: %s %s drew no figure" % (path, name or ""))
        parts.append(_entry_text(path, name, entry))
    return "\n".join(parts)


def _thumbnail(models, results):
    """The first figure drawn for a file's models (None if none ran)."""
    for job in models:
        entry = results.get(job)
        if isinstance(entry, dict) and entry.get("figures"):
            return entry["figures"][0]
    return None


def _index_page(files, results):
    """The gallery's index: per chapter, each file with a still of its first
    figure and the first sentence of its docstring, linked to its page."""
    known = {s for _, stems in GROUPS for s in stems}
    groups = [(title, [s for s in stems if s in files]) for title, stems in GROUPS]
    groups.append(("Other models", sorted(set(files) - known)))
    parts = ["# Gallery", "",
             "Every model of `models/`, simulated with its own experiment when this site was "
             "built: its figures (the model's declared figures, else its outputs, else its "
             "states) and its animation.  The command under each title runs it.", ""]
    for title, stems in groups:
        if not stems:
            continue
        parts += ["## " + title, "", "```{toctree}", ":hidden:", ""] + stems + ["```", ""]
        for stem in stems:
            name = "mec2 models" if stem == "mec2" else stem + ".py"
            thumb = _thumbnail(files[stem], results)
            if thumb:
                parts += ["```{image} %s" % thumb, ":width: 260px", ":alt: %s" % name,
                          ":target: %s.html" % stem, "```", ""]
            parts += ["**[%s](%s.md)**: %s" % (name, stem, _first_sentence(
                _file_doc(stem, files[stem]))), ""]
    return "\n".join(parts)


def write_gallery(app):
    """Run every model and write gallery/*.md (figures beside them) and the
    animation pages (copied to the site's gallery-animations/)."""
    start = time.perf_counter()
    folder = os.path.join(DOCS, "gallery")
    anim_folder = os.path.join(DOCS, "_build", "extra", "gallery-animations")
    os.makedirs(folder, exist_ok=True)
    files = _model_files()
    results = _run_all(files, folder, anim_folder)
    for stem, models in files.items():
        _write(os.path.join(folder, stem + ".md"), _file_page(stem, models, results))
    _write(os.path.join(folder, "index.md"), _index_page(files, results))
    LOG.info("gallery: %d models of %d files in %.1f s"
             % (len(results), len(files), time.perf_counter() - start))


# ---------------------------------------------------------------- API reference
def _public_modules():
    import acausal2d
    names = ["acausal2d"]
    for info in pkgutil.walk_packages(acausal2d.__path__, "acausal2d."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            names.append(info.name)
    return sorted(names)


def _matches(module, names):
    return any(module == n.rstrip("!") or (not n.endswith("!") and module.startswith(n + "."))
               for n in names)


def write_api(app):
    """api/index.md and the pages of :data:`API_PAGES` (plus "Other modules")."""
    modules = _public_modules()
    stems, used = [], set()
    for stem, title, line, blocks, names in API_PAGES:
        mods = [m for m in modules if m not in used and _matches(m, names)]
        used.update(mods)
        rst = list(blocks) + [".. automodule:: %s" % m for m in mods if m != "acausal2d"]
        body = "".join("```{eval-rst}\n%s\n```\n\n" % b for b in rst)
        _write(os.path.join(DOCS, "api", stem + ".md"), "# %s\n\n%s\n\n%s" % (title, line, body))
        stems.append(stem)
    rest = [m for m in modules if m not in used]
    if rest:
        stems.append("other")
        _write(os.path.join(DOCS, "api", "other.md"), "# Other modules\n\n" + "\n".join(
            "```{eval-rst}\n.. automodule:: %s\n```\n" % m for m in rest))
    for old in glob.glob(os.path.join(DOCS, "api", "*.md")):     # pages of an earlier layout
        if os.path.basename(old)[:-3] not in stems + ["index"]:
            os.remove(old)
    _write(os.path.join(DOCS, "api", "index.md"),
           "# API reference\n\nGenerated from the docstrings of every public module, in the "
           "order you reach for them: load, compile and simulate a model, its result and run "
           "options, comparing, studies; then the modelling language, the library by domain "
           "and the package's parts.\n\n```{toctree}\n:maxdepth: 1\n\n%s\n```\n"
           % "\n".join(stems))


def _relative_paths(app, what, name, obj, options, signature, return_annotation):
    """A default value that is a path in this checkout (``install(dest=PREBUILT)``)
    shown relative to the repository, not as the build machine's folder."""
    if signature and ROOT + os.sep in signature:
        return signature.replace(ROOT + os.sep, ""), return_annotation
    return None


def setup(app):
    app.connect("autodoc-process-signature", _relative_paths)
    app.connect("builder-inited", write_api)
    app.connect("builder-inited", write_gallery)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
