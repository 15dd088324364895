"""Issue 31: the README is short and points into the documentation, its
example runs as printed, the tutorial notebook of the site executes
(nbclient) and shows a figure, the licence matches pyproject.toml, and the
site's sources are laid out so that pages added under docs/guide/ build."""
import json
import os
import re

import pytest
from conftest import assert_copied

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOCS = os.path.join(ROOT, "docs")


def read(*parts):
    with open(os.path.join(ROOT, *parts), encoding="utf-8") as fh:
        return fh.read()


def test_readme_is_short_with_working_links():
    text = read("README.md")
    assert len(text.splitlines()) <= 250
    links = re.findall(r"\]\(([^)#:]+)\)", text)
    assert "docs/getting-started.md" in links and "LICENSE" in links
    missing = [link for link in links if not os.path.exists(os.path.join(ROOT, link))]
    assert not missing, missing
    assert "python -m sphinx -W" in text             # the one command that builds the site


def test_license_matches_pyproject():
    assert read("LICENSE").startswith("MIT License\n")
    assert 'license = {text = "MIT"}' in read("pyproject.toml")
    assert read("CHANGELOG.md").startswith("# Changelog\n")


def test_readme_example_runs_as_printed(tmp_path, monkeypatch):
    """The fifteen-line example, in a folder holding models/ and the
    shipped references: it writes its files and its comparison passes."""
    code = re.findall(r"```python\n(.*?)```", read("README.md"), re.S)
    assert len(code) == 1 and len(code[0].splitlines()) <= 15
    os.symlink(os.path.join(ROOT, "models"), tmp_path / "models")
    os.symlink(os.path.join(ROOT, "tests"), tmp_path / "tests")
    monkeypatch.chdir(tmp_path)
    scope = {}
    exec(compile(code[0], "README.md", "exec"), scope)
    assert scope["cmp"].passed and len(scope["cmp"].rows) == 2
    for name in ("w.png", "result.csv", "result.mat", "animation.html"):
        assert (tmp_path / "out" / name).stat().st_size > 1000, name
    assert_copied(scope["heavy"].parameters["bodyPiston.m"], 5.0)      # the value given


def _outputs(cell):
    return cell.get("outputs", [])


def test_tutorial_notebook_executes_and_shows_figures(tmp_path):
    """docs/tutorial.ipynb run by nbclient as the site's build runs it:
    no cell fails, the plot cell holds a PNG figure, the result displays
    as an HTML table with an inline figure, the animation as an iframe, and
    the energy of the loss-free four-bar stays constant to the tolerance
    of the run (rtol 1e-6 by default: 1e-4 of the largest kinetic energy
    leaves a factor of 100)."""
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.read(os.path.join(DOCS, "tutorial.ipynb"), as_version=4)
    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    cells = [c for c in nb.cells if c.cell_type == "code"]
    errors = [o for c in cells for o in _outputs(c) if o.output_type == "error"]
    assert not errors, errors
    data = [o.get("data", {}) for c in cells for o in _outputs(c)]
    assert any("image/png" in d for d in data)
    html = [d["text/html"] for d in data if "text/html" in d]
    assert any("<table>" in h and "data:image/png;base64," in h for h in html)
    assert any(h.startswith("<iframe srcdoc=") for h in html)
    text = "".join(o.get("text", "") for c in cells for o in _outputs(c))
    drift = float(re.search(r"the total varies by ([0-9.e+-]+) of it", text).group(1))
    assert drift < 1e-4
    assert "2 of 2 signals passed" in text            # the .mat file read back


def test_site_sources():
    """index.md lists the user guide, globs docs/guide/*.md (pages other
    topics add) and the generated gallery and API reference; each page
    under docs/guide/ has exactly one top-level title."""
    index = read("docs", "index.md")
    assert ":glob:\n\nguide/*" in index
    for entry in ("getting-started", "tutorial", "gallery/index", "api/index",
                  "coming-from-modelica", "changelog", "speed", "coverage"):
        assert re.search(r"^%s$" % re.escape(entry), index, re.M), entry
    for name in os.listdir(os.path.join(DOCS, "user-guide")):
        assert re.search(r"^user-guide/%s$" % re.escape(name[:-3]), index, re.M), name
    guide = os.path.join(DOCS, "guide")
    pages = [n for n in os.listdir(guide) if n.endswith(".md")]
    assert pages
    for name in pages:
        prose = re.sub(r"^```.*?^```", "", read("docs", "guide", name), flags=re.M | re.S)
        titles = re.findall(r"^# ", prose, re.M)
        assert len(titles) == 1, name
    nb = json.loads(read("docs", "tutorial.ipynb"))
    assert all(not c.get("outputs") for c in nb["cells"])     # executed at build time
