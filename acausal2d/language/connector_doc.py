"""The connectors of a component class, for ``help()`` and for the error of
an unknown attribute.

Connectors are created in a component's ``__init__`` (some only with an
option, e.g. ``Revolute(use_flange=True)``), so the class body does not
declare them: :func:`connector_table` makes an instance with the defaults
and one per boolean option switched on, and lists what each has.  The
docstring is computed when it is first read (:class:`LazyDoc`), never at
import, and cached per class.
"""
import inspect

from ..errors import Acausal2dError


def _connectors_of(cls, kwargs):
    """{name: connector} of an instance made with ``kwargs``, or None when
    the class cannot be made that way."""
    try:
        return dict(cls(**kwargs)._connectors)
    except (Acausal2dError, TypeError, ValueError, ArithmeticError, LookupError,
            AttributeError, RuntimeError):
        return None


def _boolean_options(cls):
    """Keyword arguments of ``cls.__init__`` whose default is False."""
    try:
        params = inspect.signature(cls.__init__).parameters.values()
    except (TypeError, ValueError):
        return []
    return [p.name for p in params if p.default is False]


def connector_rows(cls):
    """[(name, kind, variables, condition)] of the connectors an instance of
    ``cls`` has with its defaults, then those that a boolean option adds
    (condition ``"option=True"``)."""
    base = _connectors_of(cls, {})
    if base is None:
        return []
    rows = [(n, type(c).kind, ", ".join(type(c).potentials + type(c).flows), "")
            for n, c in base.items()]
    for option in _boolean_options(cls):
        more = _connectors_of(cls, {option: True}) or {}
        rows += [(n, type(c).kind, ", ".join(type(c).potentials + type(c).flows),
                  "%s=True" % option) for n, c in more.items() if n not in base]
    return rows


def connector_table(cls):
    """The 'Connectors' section of ``help(cls)``, or '' for none."""
    rows = connector_rows(cls)
    if not rows:
        return ""
    width = max(len(r[0]) for r in rows)
    lines = ["    %-*s  %s (%s)%s" % (width, n, kind, variables,
                                    "  [with %s]" % cond if cond else "")
             for n, kind, variables, cond in rows]
    return "\n\nConnectors (kind and variables):\n" + "\n".join(lines)


class LazyDoc:
    """A class's ``__doc__`` computed when first read: the declaration
    tables (``make(cls)``) and the connectors (:func:`connector_table`)."""

    def __init__(self, make):
        self.make = make
        self.cache = {}

    def __get__(self, obj, cls=None):
        cls = cls if cls is not None else type(obj)
        if cls not in self.cache:
            self.cache[cls] = None          # a component whose __init__ reads its own __doc__
            text = (self.make(cls) or "") + connector_table(cls)
            self.cache[cls] = text.lstrip("\n") or None
        return self.cache[cls]
