"""Sphinx configuration of the acausal2d documentation site.

Build (warnings are errors): ``python -m sphinx -W --keep-going -b html docs
docs/_build/html`` after ``pip install -e ".[docs]"``.  MyST Markdown pages,
the tutorial notebook executed by myst-nb, the API reference by autodoc,
and the gallery written by ``_ext/gallery.py`` (every model of ``models/``
run at build time).
"""
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "_ext"))

import acausal2d  # noqa: E402

project = "acausal2d"
author = "The acausal2d authors"
copyright = "2026, The acausal2d authors"
release = version = acausal2d.__version__

extensions = ["myst_nb", "sphinx.ext.autodoc", "gallery", "site_links"]
source_suffix = {".md": "myst-nb", ".ipynb": "myst-nb"}
exclude_patterns = ["_build", "jupyter_execute", "**.ipynb_checkpoints"]
root_doc = "index"

myst_enable_extensions = ["dollarmath"]
myst_heading_anchors = 3

nb_execution_mode = "force"            # the tutorial runs at every build
nb_execution_timeout = 600
nb_execution_raise_on_error = True
nb_execution_show_tb = True

autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_typehints = "none"

html_theme = "furo"
html_title = "acausal2d %s" % release
html_static_path = []
html_extra_path = [os.path.join(HERE, "_build", "extra")]      # the gallery's animation pages
os.makedirs(html_extra_path[0], exist_ok=True)


_BARS = re.compile(r"(?<![\\`|\w])\|(?=[^\s|])([^|`\n]*?[^\s|\\])\|(?![`|\w])")


def _escape_bars(text):
    """``text`` with every ``|x|`` outside inline literals escaped."""
    parts = text.split("``")
    for k in range(0, len(parts), 2):              # the even parts are outside ``...``
        parts[k] = _BARS.sub(r"\\|\1\\|", parts[k])
    return "``".join(parts)


def _absolute_values(app, what, name, obj, options, lines):
    """Docstrings write absolute values and norms as ``|det|``, ``|p2 - p1|``:
    plain text, not reStructuredText substitutions, so the bars are
    escaped before the docstring is parsed (inside inline literals they
    stay as written)."""
    lines[:] = _escape_bars("\n".join(lines)).split("\n")     # literals may span lines


def setup(app):
    app.connect("autodoc-process-docstring", _absolute_values)
