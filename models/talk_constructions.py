"""The four-node geometric constructions of Schnabel and Gössner's constraint library
(talk ch. 2.3 and the cstr.js manual, whose example places A (0,0),
B (80,20), C (20,30), D (100,40)), all in one node model (C moved to (-40,50) and one end node
per construction, so that the five do not overlap) so that they move together: the segment AB turns about A at
1 turn/s (its angle driven, its length held) and the segment AC at -1/3
turn/s, and every construction follows.

* parallel: C -> Dp parallel to AB (length held);
* parallel of equal length: C -> De is the vector A -> B;
* perpendicular: C -> Do at right angles to AB (length held);
* perpendicular bisector: Mb the midpoint of AB, Mb -> Db at right angles
  to AB (length held);
* angle bisector: A -> Da halves the angle from AB to AC (length held).

Helpers in :mod:`acausal2d.library.nodes.constructions`;
``acausal2d simulate models/talk_constructions.py`` draws them,
``tests/test_talk_synthesis.py`` checks each on its defining property."""
import math

from acausal2d.library.nodes import NodeModel, speed
from acausal2d.library.nodes.constructions import (angle_bisector, parallel, parallel_equal,
                                                   perpendicular, perpendicular_bisector)

TURN = 2 * math.pi


class FourNodeConstructions(NodeModel):
    """Parallel, parallel of equal length, perpendicular, perpendicular
    bisector and angle bisector of the turning segment AB (coordinates in
    mm, one turn of AB per second)."""
    length_unit = 1e-3
    experiment = {"stop_time": 1.0, "intervals": 360, "rtol": 1e-8}
    outputs = ["Dp.x", "Dp.y", "Da.x", "Da.y"]
    figures = [{"signals": [["De.x", "De.y"], ["Db.x", "Db.y"]], "x": "AB.w",
                "title": "constructed points over the angle of AB", "name": "constructions"}]

    def __init__(self, **kw):
        super().__init__(**kw)
        for nid, x, y, m in (("A", 0, 0, "base"), ("B", 80, 20, 1), ("C", -40, 50, 1),
                             ("Dp", 0, 60, 0), ("De", 40, 70, 0), ("Do", -50, 90, 0),
                             ("Mb", 40, 10, 0), ("Db", 20, 90, 0), ("Da", 60, 40, 0)):
            self.node(nid, x, y, base=True) if m == "base" else self.node(nid, x, y, m=m)
        self.n2("AB", "A", "B", len="const", ang=speed(TURN))
        self.n2("AC", "A", "C", len="const", ang=speed(-TURN / 3))
        parallel(self, "CDp", "C", "Dp", "AB", len="const")
        parallel_equal(self, "CDe", "C", "De", "AB")
        perpendicular(self, "CDo", "C", "Do", "AB", len="const")
        perpendicular_bisector(self, "MbDb", "AB", "Mb", "Db", len="const")
        angle_bisector(self, "ADa", "A", "Da", "AB", "AC", len="const")
