"""User-facing text speaks the project's own words: no "seed", "the talk",
"issue N", "spec", source line ranges or paths outside the repository in
the documentation (sources and, if built, the site), the command line's
help, the messages' templates (the prose string literals of the package
and its library) and the docstrings of the package, the library, the
models, the benchmarks and the documentation's extensions.  The bibliography and the
glossary name the works these words came from and are exempt.

Identifiers are not jargon: a random generator's seed (``seed=0``, "random
seed", "fixed seeds"), a variable or file named ``spec`` or ``specs``
(``model.specs``, ``specs.py``) and "spec" for a value that specifies
something (a figure spec, a sweep's spec string) are fine; the patterns
below match the internal words as prose: the specification documents
("the spec", "spec section 1.6", "spec_talk_nodes.md")."""
import argparse
import ast
import glob
import html.parser
import os
import re

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXEMPT_PAGES = {"glossary", "bibliography"}

WORDS = [
    ("seed", re.compile(r"(?<![\w.`'\"-])(?<!\w\()(?<!\w\[)(?<!random )(?<!rng )(?<!fixed )(?<!the random )"
                        r"seeds?\b(?![\w=(`\"\]-])(?!\)\s*[:=,.\]])(?!\s*=)(?!'(?!s\b))(?! (?:of|for) the (?:random|noise|generator))",
                        re.I)),
    ("the talk", re.compile(r"\bthe talk\b(?!-)", re.I)),
    ("issue N", re.compile(r"\bissues? #?\d+", re.I)),
    ("spec", re.compile(r"\bthe specs?\b|\bspec(?:'s|s)?(?: section| transcription| table| \d)|"
                        r"\bspec_\w+\.md", re.I)),
    ("line numbers", re.compile(r"\blines? \d+ ?(?:-|–|to|\.\.) ?\d+", re.I)),
    ("path outside the repository", re.compile(r"\.\./shared\b|/work/|\bshared/(?:specs|seeds)|"
                                               + re.escape(ROOT))),
]


def jargon(text):
    """[(word, excerpt)] of the internal words in ``text`` (line breaks read as spaces)."""
    text = " ".join(text.split())
    found = []
    for word, pattern in WORDS:
        for m in pattern.finditer(text):
            found.append((word, " ".join(text[max(0, m.start() - 50):m.end() + 30].split())))
    return found


def test_the_patterns_tell_words_from_identifiers():
    prose = ["the seed's Bild 4.1", "(seed ch. 2)", "as the talk shows", "after issue 17",
             "the spec's section 1.6", "see lines 2428-2440", "../shared/specs/x.md",
             "structure (seed)  output"]
    for text in prose:
        assert jargon(text), text
    identifiers = ["a random seed", "fixed seeds", "``seed=0``", "rng = default_rng(seed)",
                   "spec = specs.speed(2)", "library/nodes/specs.py", "the `spec` argument",
                   "a bad spec raises", "per figure spec",
                   "seeded", "seedless", "'seed'", "the talk-back", "f(x, seed)."]
    assert [t for t in identifiers if jargon(t)] == []


# ---------------------------------------------------------------- documentation
def _doc_sources():
    paths = glob.glob(os.path.join(ROOT, "docs", "**", "*.md"), recursive=True)
    paths += [os.path.join(ROOT, name) for name in ("README.md", "CHANGELOG.md",
                                                    os.path.join("docs", "tutorial.ipynb"))]
    skip = (os.sep + "_build" + os.sep, os.sep + "gallery" + os.sep, os.sep + "api" + os.sep,
            os.sep + "jupyter_execute" + os.sep)
    return sorted(p for p in paths if not any(s in p for s in skip)
                  and os.path.splitext(os.path.basename(p))[0] not in EXEMPT_PAGES)


@pytest.mark.parametrize("path", _doc_sources(), ids=lambda p: os.path.relpath(p, ROOT))
def test_documentation_sources(path):
    with open(path, encoding="utf-8") as fh:
        assert jargon(fh.read()) == []


class _Text(html.parser.HTMLParser):
    """The visible text of a page (no scripts, styles or attributes)."""

    def __init__(self):
        super().__init__()
        self.parts, self._skip = [], 0

    def handle_starttag(self, tag, attrs):
        self._skip += tag in ("script", "style")

    def handle_endtag(self, tag):
        self._skip -= tag in ("script", "style") and self._skip > 0

    def handle_data(self, data):
        if not self._skip:
            self.parts.append(data)


def site_jargon(site):
    """[(page, jargon)] of the built site's pages in the folder ``site``
    (the build in tests/test_site_build.py); the glossary, the bibliography
    and Sphinx's own folders are exempt."""
    bad = []
    for path in glob.glob(os.path.join(site, "**", "*.html"), recursive=True):
        rel = os.path.relpath(path, site)
        if rel.split(os.sep)[0] in ("_sources", "_static", "_modules") or \
                os.path.splitext(os.path.basename(rel))[0] in EXEMPT_PAGES:
            continue
        parser = _Text()
        with open(path, encoding="utf-8") as fh:
            parser.feed(fh.read())
        bad += [(rel, hit) for hit in jargon(" ".join(parser.parts))]
    return bad


# ---------------------------------------------------------------- command line
def _parsers():
    from acausal2d.cli import build_parser
    top = build_parser()
    out = [("acausal2d", top)]
    for action in top._actions:
        if isinstance(action, argparse._SubParsersAction):
            out += sorted(action.choices.items())
    return out


def test_command_line_help():
    bad = []
    for name, parser in _parsers():
        bad += [(name, hit) for hit in jargon(parser.format_help())]
    assert len(_parsers()) > 10
    assert bad == []


# ---------------------------------------------------------------- code
def _sources():
    files = []
    for folder in ("acausal2d", "library", "models", "benchmarks", os.path.join("docs", "_ext")):
        files += glob.glob(os.path.join(ROOT, folder, "**", "*.py"), recursive=True)
    real = {os.path.realpath(p): p for p in files}          # acausal2d/library is library/
    return sorted(real)


def _strings(tree):
    """(kind, line, text) of the docstrings and the prose string literals of a module."""
    docs = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant) \
                    and isinstance(body[0].value.value, str):
                docs.add(id(body[0].value))
                yield "docstring", body[0].value.lineno, body[0].value.value
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs \
                and " " in node.value.strip():
            yield "string", node.lineno, node.value


@pytest.mark.parametrize("path", _sources(), ids=lambda p: os.path.relpath(p, ROOT))
def test_docstrings_and_messages(path):
    with open(path, encoding="utf-8") as fh:
        tree = ast.parse(fh.read())
    models = os.sep + "models" + os.sep in path
    bad = []
    for kind, line, text in _strings(tree):
        if models and kind == "string":
            continue            # a model's string literals are its data, not messages
        bad += [(line, kind, hit) for hit in jargon(text)]
    assert bad == []
