"""Planar multibody elements with the semantics of the Modelica library
PlanarMechanics (frames resolved in the world frame, phi and t
counter-clockwise positive), one concern per module:

- :mod:`.base`: rotations (Ebert 2015, Anhang A.1), the gravity field
  :class:`PlanarWorld`, connection queries.
- :mod:`.parts`: Fixed, Body, FixedTranslation, FixedRotation, BodyShape.
- :mod:`.joints`: Revolute, Prismatic, IdealRolling.
- :mod:`.cam`: CamFollower, the cam joint K of Ebert (2015), Tab. 2.1.
- :mod:`.forces`: Spring, Damper, SpringDamper, LineSpringDamper,
  WorldForce, WorldTorque, RelativeForce.
- :mod:`.sensors`: absolute and relative position/velocity/acceleration
  sensors, CutForce, CutTorque, Power, Distance.

``from acausal2d.library.planar import Body`` gives the parts and joints;
forces and sensors are imported from their modules.
"""
from .base import PlanarWorld, is_connected, resolve, rotate
from .parts import Body, BodyShape, Fixed, FixedRotation, FixedTranslation, fixed_of
from .joints import IdealRolling, Prismatic, Revolute



def modelica_names():
    """The Modelica array-name aliases the planar components declare (class
    attribute ``modelica_names``, e.g. Body's ``r[1]`` -> ``x``): a dict
    from the Modelica name of a component's variable to the list of our
    names it may stand for.  :func:`acausal2d.compare` matches reference
    columns such as ``body.r[1]`` by it."""
    table = {}
    for module in (parts, joints, forces, sensors):
        for obj in vars(module).values():
            for key, ours in (getattr(obj, "modelica_names", None) or {}).items() \
                    if isinstance(obj, type) else ():
                if ours not in table.setdefault(key, []):
                    table[key].append(ours)
    return table


__all__ = ["modelica_names", "PlanarWorld", "fixed_of", "is_connected", "resolve", "rotate", "Body", "BodyShape",
           "Fixed", "FixedRotation", "FixedTranslation", "IdealRolling", "Prismatic", "Revolute"]
from .cam import CamFollower  # noqa: E402
from . import forces, joints, parts, sensors
__all__ += ["CamFollower"]
