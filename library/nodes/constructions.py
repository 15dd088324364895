"""The four-node geometric constructions of Schnabel and Gössner's constraint library
("Lightweight prototypal mechanism simulation on the web", ch. 2.3 and the
cstr.js manual): a constraint whose length or angle is taken from another
constraint by ``ref`` (cstr.js ``len.from``, ``ang.from``) or ``delta``
(``ang.delta``).  Each helper adds constraints to a
:class:`~acausal2d.library.nodes.NodeModel` and returns the new link(s):

* :func:`parallel` - ``CD ang = from('AB')``;
* :func:`parallel_equal` - the same with ``len = from('AB')`` (CD equals AB
  as a vector);
* :func:`perpendicular` - ``CD ang = from('AB', pi/2)``;
* :func:`perpendicular_bisector` - the midpoint M of AB (``AM len =
  from('AB', 1/2), ang = from('AB')``) and the line from M at right angles
  (``MD ang = from('AB', pi/2)``);
* :func:`angle_bisector` - ``AD ang = delta('AB', 'AC', 1/2)``.

Lengths left free by a helper stay free: the constructed node slides on
the constructed line, as on Schnabel and Gössner's pages.
"""
import math

from .specs import delta, ref

__all__ = ["parallel", "parallel_equal", "perpendicular", "perpendicular_bisector",
           "angle_bisector"]


def parallel(model, cid, n1, n2, to, len=None):
    """Constraint ``cid`` from ``n1`` to ``n2`` parallel to the constraint
    ``to`` (its angle ``ang = ref(to)``); ``len`` as for ``n2``."""
    return model.n2(cid, n1, n2, len=len, ang=ref(to), draw="bar")


def parallel_equal(model, cid, n1, n2, to):
    """Constraint ``cid`` from ``n1`` to ``n2`` parallel to ``to`` and of its
    length: n1 -> n2 is the same vector as ``to``."""
    return model.n2(cid, n1, n2, len=ref(to), ang=ref(to), draw="bar")


def perpendicular(model, cid, n1, n2, to, len=None):
    """Constraint ``cid`` from ``n1`` to ``n2`` at right angles to ``to``
    (``ang = ref(to, offset=pi/2)``)."""
    return model.n2(cid, n1, n2, len=len, ang=ref(to, offset=math.pi / 2), draw="bar")


def perpendicular_bisector(model, cid, to, mid, n, len=None):
    """The perpendicular bisector of the constraint ``to`` (from its first
    node): ``mid`` is held at the midpoint (constraint ``cid + "_mid"``
    with ``len = ref(to, 1/2)``, ``ang = ref(to)``) and the constraint
    ``cid`` from ``mid`` to ``n`` is at right angles to ``to``.  Returns
    (midpoint link, bisector link)."""
    first = model._cstrs[to]["n1"]
    m = model.n2(cid + "_mid", first, mid, len=ref(to, 0.5), ang=ref(to), draw=None)
    return m, perpendicular(model, cid, mid, n, to, len=len)


def angle_bisector(model, cid, apex, n, first, second, len=None):
    """Constraint ``cid`` from ``apex`` to ``n`` halving the angle from the
    constraint ``first`` to ``second`` (``ang = delta(first, second, 1/2)``)."""
    return model.n2(cid, apex, n, len=len, ang=delta(first, second, 0.5), draw="bar")
