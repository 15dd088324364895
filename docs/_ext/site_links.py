"""Sphinx extension: every internal link of the built site reaches its
target, checked offline when the HTML build finishes.

For each page of the output folder, the ``href`` and ``src`` of its links,
images, frames, scripts and stylesheets that point into the site (no scheme,
no host) must name a file that exists there, and a ``#fragment`` an ``id``
(or ``name``) on the target page.  Each missing target is a build warning,
so ``sphinx-build -W`` fails on it.  :func:`missing_targets` is the check
itself (``tests/test_site_links.py`` runs it on a small site and on the
built one).  Sphinx's own ``linkcheck`` builder needs the network; this
needs none and checks the fragments too.
"""
import html.parser
import os
import urllib.parse

from sphinx.util import logging

LOG = logging.getLogger(__name__)

_ATTRS = {"a": "href", "link": "href", "img": "src", "iframe": "src", "script": "src",
          "source": "src"}


class _Page(html.parser.HTMLParser):
    """The links and the ids of one page."""

    def __init__(self):
        super().__init__()
        self.links, self.ids = [], set()

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        for key in ("id", "name"):
            if attrs.get(key):
                self.ids.add(attrs[key])
        url = attrs.get(_ATTRS.get(tag, ""))
        if url:
            self.links.append(url)


def _read(path, cache):
    if path not in cache:
        page = _Page()
        with open(path, encoding="utf-8", errors="replace") as fh:
            page.feed(fh.read())
        cache[path] = page
    return cache[path]


def _internal(url):
    """(path, fragment) of a link into the site, else None."""
    parts = urllib.parse.urlsplit(url)
    if parts.scheme or parts.netloc or url.startswith(("//", "data:", "javascript:")):
        return None
    return urllib.parse.unquote(parts.path), urllib.parse.unquote(parts.fragment)


def missing_targets(site):
    """[(page, link, what is missing)] of the HTML pages under ``site``."""
    cache, missing = {}, []
    for folder, _, names in os.walk(site):
        for name in sorted(names):
            if not name.endswith(".html"):
                continue
            page_path = os.path.join(folder, name)
            for url in _read(page_path, cache).links:
                target = _internal(url)
                if target is None:
                    continue
                path, fragment = target
                full = os.path.normpath(os.path.join(folder, path)) if path else page_path
                if os.path.isdir(full):
                    full = os.path.join(full, "index.html")
                rel = os.path.relpath(page_path, site)
                if not os.path.isfile(full):
                    missing.append((rel, url, "no file %s" % os.path.relpath(full, site)))
                elif fragment and full.endswith(".html") and \
                        fragment not in _read(full, cache).ids:
                    missing.append((rel, url, "no id %r on %s" % (fragment,
                                                                   os.path.relpath(full, site))))
    return missing


def check_site(app, exception):
    """After a successful HTML build: a warning per link whose target is missing."""
    if exception is not None or app.builder.format != "html":
        return
    missing = missing_targets(app.outdir)
    for page, url, what in missing:
        LOG.warning("broken link on %s: %s (%s)" % (page, url, what))
    LOG.info("site links: %s" % ("%d missing targets" % len(missing) if missing else
                                 "every internal link reaches its target"))


def setup(app):
    app.connect("build-finished", check_site)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
