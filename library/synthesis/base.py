"""What the synthesis elements of Ebert (2015), ch. 4.3 share: the mounting parameter
K check and the start positions of the frames they read (the linkage
pre-assembly extended across revolute joints and rigid rods), used to start
the unwrapped band angles on the right branch; ports that carry no force
(Ebert 2015, Tabelle 4.3, 4.5, 4.7).
"""
import math

import casadi as ca

from acausal2d.errors import ModelDefinitionError
from acausal2d.library import planar
from acausal2d.library.linkage.base import _Assembly


def _check_K(owner, K):
    if K not in (1, -1):
        raise ModelDefinitionError("%s: mounting parameter K must be +1 or -1, got %r"
                                   % (owner, K))
    return K


def _pose_assembly(context):
    """The linkage pre-assembly (library/linkage.py) extended across
    planar.Revolute (same point on both frames) and planar.FixedTranslation."""
    asm = context.shared("linkage assembly", lambda: _Assembly(context))
    comps = list(context.model.components())
    for _ in range(len(comps)):
        progress = False
        for comp in comps:
            if isinstance(comp, planar.Revolute):
                progress |= _copy_xy(asm, comp.frame_a, comp.frame_b)
                progress |= _copy_xy(asm, comp.frame_b, comp.frame_a)
            elif isinstance(comp, planar.FixedTranslation):
                a = asm.get(comp.frame_a)
                b = asm.get(comp.frame_b)
                if a and all(k in a for k in ("x", "y", "phi")) and not (b and "x" in b):
                    c, s = ca.cos(a["phi"]), ca.sin(a["phi"])
                    asm.put(comp.frame_b, {"x": a["x"] + c * comp.r[0] - s * comp.r[1],
                                           "y": a["y"] + s * comp.r[0] + c * comp.r[1],
                                           "phi": a["phi"]})
                    progress = True
        if not progress:
            break
    return asm


def _copy_xy(asm, src, dst):
    a, b = asm.get(src), asm.get(dst)
    if a and "x" in a and "y" in a and not (b and "x" in b):
        asm.put(dst, {"x": a["x"], "y": a["y"]})
        return True
    return False


def start_xy(context, conn):
    """Numeric start position (x, y) of the frame ``conn`` from the
    parameters (fixed frames, linkage pre-assembly, revolute joints), or
    None when it cannot be found without solving the model."""
    asm = context.shared("band synthesis poses", lambda: _pose_assembly(context))
    vals = asm.get(conn)
    if not vals or "x" not in vals or "y" not in vals:
        return None
    x, y = context.evaluate([vals["x"], vals["y"]])
    return float(x), float(y)


def _direction_guess(context, a, b):
    """Angle of the direction a -> b at the start, or None."""
    pa, pb = start_xy(context, a), start_xy(context, b)
    if pa is None or pb is None or (pa[0] == pb[0] and pa[1] == pb[1]):
        return None
    return math.atan2(pb[1] - pa[1], pb[0] - pa[0])


def _zero_flows(*frames):
    out = []
    for f in frames:
        out += [f.fx == 0, f.fy == 0, f.t == 0]
    return out
