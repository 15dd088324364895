"""Events in the element's own words: ``Brake 'brake': stuck -> sliding
forward at t = 0.5000033 s``.

At an event the relations that switched belong to components (the owner
of the equation that holds each).  A component that describes its
operating mode (:meth:`~acausal2d.language.dsl.Component.describe_mode`) is named
with its mode just before and just after the event; the mode is read off
the motion a short time ``NUDGE`` (relative to the run's time span) before
and after the event instant, under the relation values of each side, so
that a mode bounded by the relation that switched (a stick zone's edge) is
told apart.  This is a description only: no decision of the run depends
on it.  Other components get a generic sentence: the condition that
switched, with the component's own variable names, or, where its text is
not plain arithmetic, the variables it tests.  The raw relation
expressions stay in ``Result.events`` (and ``--verbose`` prints them).
"""
import re

import casadi as ca

from ..language.dsl import Component

NUDGE = 1e-7
"""How far (relative to the run's time span) before and after an event the
modes are read."""

_PLAIN = re.compile(r"^[\w.\s+\-*/()<=>,]*$")
_CASADI = ("@", "?", "sq(", "!", "||", "&&")


def _relative(text, path):
    """``text`` with the component's own prefix ``path.`` dropped from names."""
    return text.replace(path + ".", "") if path else text


def is_plain(text):
    """Whether a condition's text reads as plain arithmetic (no CasADi
    shared subexpressions, ternaries or internal function names)."""
    return bool(_PLAIN.match(text)) and not any(tok in text for tok in _CASADI) \
        and "rel" not in re.findall(r"[A-Za-z_]+", text)


def _tested_variables(system, k, path):
    """Names (relative to ``path``) of the unknowns relation k tests."""
    g = system.relations[k].g
    names = sorted({str(s) for s in ca.symvar(g)} & set(system.names))
    return [_relative(n, path) for n in names] or ["time"]


def _as_condition(text):
    """The condition a relation's text stands for: ``max(a, b)`` is true
    where a > b, ``min(a, b)`` where a < b, ``sign(a)`` where a > 0."""
    for head, fmt in (("max(", "%s > %s"), ("min(", "%s < %s"), ("sign(", "%s > 0")):
        if text.startswith(head) and text.endswith(")"):
            inner = text[len(head):-1]
            if head == "sign(":
                return fmt % inner
            depth = 0
            for i, ch in enumerate(inner):
                depth += {"(": 1, ")": -1}.get(ch, 0)
                if ch == "," and depth == 0:
                    return fmt % (inner[:i].strip(), inner[i + 1:].strip())
    return text


def generic_words(system, k, value, path):
    """One relation's switch in words: ``condition 'delta <= 0' became
    true``, or ``its condition on w, w_s switched (now false)``."""
    rel = system.relations[k]
    text = _as_condition(_relative(rel.text, path))
    state = "true" if value else "false"
    if is_plain(text):
        return "condition '%s' became %s" % (text, state)
    return "its condition on %s switched (now %s)" % (", ".join(_tested_variables(system, k, path)),
                                                      state)


class _Values:
    """``value(name)`` of a component: its variables at node values z and
    its parameters."""

    def __init__(self, system, p, z, comp):
        self.system, self.p, self.z, self.comp = system, p, z, comp

    def __call__(self, name):
        full = "%s.%s" % (self.comp.path, name) if self.comp.path else name
        s = self.system
        if full in s.param_index:
            return float(self.p[s.param_index[full]])
        return s.value(full, self.z, self.p)


def _mode(comp, system, p, z):
    """The component's mode at node values z, or None (no hook, or it
    cannot tell)."""
    try:
        return comp.describe_mode(_Values(system, p, z, comp))
    except (KeyError, ValueError, IndexError, ZeroDivisionError):
        return None


def describe_event(run, changed, z_left, d_left, z, d):
    """The sentence of one event of ``run`` (a
    :class:`~acausal2d.runtime.simulation.Simulation` at its event time):
    the relations ``changed`` switched from ``d_left`` (nodes ``z_left``)
    to ``d`` (nodes ``z``)."""
    from .events import node_rates, relation_owner
    system, t = run.system, run.t
    groups = {}
    for k in changed:
        owner = relation_owner(system, k)
        groups.setdefault(id(owner), (owner, []))[1].append(k)
    h = NUDGE * max(run.t_end - float(run.times[0]), abs(t), 1e-300)
    parts = []
    for owner, rels in groups.values():
        words = None
        if owner is not None and type(owner).describe_mode is not _default_mode():
            before = _mode(owner, system, run.p,
                           z_left - h * node_rates(run.ev, t, z_left, d_left))
            after = _mode(owner, system, run.p, z + h * node_rates(run.ev, t, z, d))
            if before and after and before != after:
                words = "%s -> %s" % (before, after)
        if words is None:
            path = owner.path if owner is not None else ""
            words = "; ".join(generic_words(system, k, d[k], path) for k in rels)
        parts.append("%s: %s" % (owner.describe() if owner is not None else "a connection",
                                 words))
    return "; ".join(parts)


def _default_mode():
    return Component.describe_mode


def event_line(t, words):
    """``WORDS at t = T s`` as the command line prints it."""
    return "%s at t = %.7g s" % (words, t)


def check_words(text):
    """Whether an event text is free of CasADi syntax (for tests)."""
    return not any(tok in text for tok in _CASADI) and not re.search(r"\brel\d+\b", text)

