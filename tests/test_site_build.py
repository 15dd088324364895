"""The documentation site builds in a plain clone with the README's command
(Sphinx, warnings as errors: a model of the gallery that fails, a broken
cross-reference or a notebook cell that raises fails it), every model file
of ``models/`` has its gallery page with a figure and an animation per
model, no internal link of the built site misses its target, and its pages
speak the project's own words (tests/test_user_words.py).

The build runs every model of the gallery and executes the notebooks: a few
minutes of CPU, so it runs among the other tests (``FIRST`` in
tests/conftest.py starts it early) instead of before them.  It runs with the
environment a user has (not the suite's ``ACAUSAL2D_NATIVE=now``): the gallery's
models on the Python path, as docs/_ext/gallery_run.py sets it."""
import glob
import os
import re
import shlex
import subprocess
import sys

import pytest
from test_plain_clone import ROOT, make_clone
from test_user_words import site_jargon

sys.path.insert(0, os.path.join(ROOT, "docs", "_ext"))
from site_links import missing_targets  # noqa: E402


def readme_docs_command():
    """The README's documentation command after its install: ``python -m
    sphinx ...`` as argv."""
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as fh:
        lines = [line.strip() for line in fh if "python -m sphinx" in line]
    assert len(lines) == 1, lines
    return shlex.split(lines[0].split("&&")[-1])


def test_the_site_builds_in_a_plain_clone(tmp_path):
    repo = make_clone(tmp_path)
    argv = readme_docs_command()
    assert argv[:3] == ["python", "-m", "sphinx"] and "-W" in argv
    env = {k: v for k, v in os.environ.items() if k != "ACAUSAL2D_NATIVE"}   # as a user runs it
    proc = subprocess.run([sys.executable] + argv[1:], cwd=repo, env=env, capture_output=True,
                          text=True, timeout=1800)
    said = proc.stdout[-4000:] + proc.stderr[-8000:]
    assert proc.returncode == 0, said
    assert "Traceback" not in proc.stderr, said
    site = os.path.join(repo, argv[-1])
    models = {os.path.basename(p)[:-3] for p in glob.glob(os.path.join(repo, "models", "*.py"))}
    pages = {os.path.basename(p)[:-5] for p in glob.glob(os.path.join(site, "gallery", "*.html"))}
    assert models - {"measured_data"} <= pages, sorted(models - pages)   # a data writer, no model
    frames = []
    for stem in pages - {"index"}:
        with open(os.path.join(site, "gallery", stem + ".html"), encoding="utf-8") as fh:
            text = fh.read()
        runs = re.findall(r'<iframe src="\.\./gallery-animations/([^"]+)"', text)
        assert runs and len(re.findall(r"<img [^>]*src=", text)) >= len(runs), stem
        frames += runs
    assert len(frames) == len(set(frames)) >= 100          # one animation page per model
    assert missing_targets(site) == []
    assert site_jargon(site) == []


DEPRECATED = '''
from acausal2d import Component
from acausal2d.library.belt import Pulley


class OldPulley(Component):
    def __init__(self):
        super().__init__()
        self.pulley = Pulley(r=0.1, J=1e-4, x0=0.2, y0=-1.0)
'''


def test_a_shipped_model_on_a_former_interface_fails_the_gallery(tmp_path):
    """The gallery loads and compiles each model with DeprecationWarning as an
    error (its run is a build warning, so the -W build fails), naming the file."""
    from gallery_run import _load_and_compile
    path = tmp_path / "old_pulley.py"
    path.write_text(DEPRECATED, encoding="utf-8")
    with pytest.raises(DeprecationWarning) as err:
        _load_and_compile(str(path), "OldPulley")
    assert "old_pulley.py" in str(err.value) and "x0" in str(err.value)
