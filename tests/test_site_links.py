"""The offline link check of the documentation site (docs/_ext/site_links.py):
it finds a missing page, a missing image and a missing fragment on a small
site and passes its good links.  The built site's links are checked where
it is built (tests/test_site_build.py)."""
import os
import sys


ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "docs", "_ext"))

from site_links import missing_targets  # noqa: E402


def _page(path, body):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("<html><body>%s</body></html>" % body)


def test_a_small_site(tmp_path):
    site = str(tmp_path)
    _page(os.path.join(site, "index.html"),
          '<a href="guide/a.html#step-2">ok</a> <a href="guide/">folder</a> '
          '<a href="https://example.org/x.html">outside</a> <a href="#top">top</a> '
          '<a href="guide/gone.html">gone</a> <img src="fig.png"> '
          '<a href="guide/a.html#nowhere">bad fragment</a> <p id="top"></p>')
    _page(os.path.join(site, "guide", "a.html"), '<h2 id="step-2">Step 2</h2>'
          '<iframe src="../anim/x.html"></iframe><a href="../index.html">up</a>')
    _page(os.path.join(site, "guide", "index.html"), "")
    missing = missing_targets(site)
    assert sorted((page, url) for page, url, _ in missing) == [
        ("guide/a.html", "../anim/x.html"), ("index.html", "fig.png"),
        ("index.html", "guide/a.html#nowhere"), ("index.html", "guide/gone.html")]
