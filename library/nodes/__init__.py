"""The node/constraint front end of Schnabel and Gössner's talk "Lightweight prototypal
mechanism simulation on the web" (Schnabel/Goessner; cstr.js and mec2):

- :mod:`.model`: :class:`NodeModel`, models written as nodes and
  constraints; :mod:`.specs`: the values a constraint takes (speed, drive,
  ref, delta, between, at_least, at_most);
- :mod:`.elements`: what a :class:`NodeModel`
  compiles into -- nodes (point masses, talk eq. 5), two-node constraints
  in polar form (eq. 3), the included angle, holds, drives, couplings and
  the loads of mec2;
- :mod:`.drives`: mec2's drive laws (Dt, Dz, t0, repeat, bounce, seq);
- :mod:`.correction`: Schnabel and Gössner's position correction (eq. 3-16).
"""
from .elements import (AngleDrive, AngleHold, Coupling, IncludedAngle, LengthDrive, LengthHold,
                       Link, Node, NodeForce, NodePort, NodeSpring)
from .specs import (NodeAssemblyError, at_least, at_most, between, delta, drive, mec2_drive,
                    ref, speed)
from .model import NodeModel

__all__ = ["NodeModel", "speed", "drive", "mec2_drive", "ref", "delta", "between", "at_least",
           "at_most", "NodeAssemblyError", "NodePort", "Node", "Link", "IncludedAngle",
           "AngleHold", "LengthHold", "AngleDrive", "LengthDrive", "Coupling", "NodeForce",
           "NodeSpring"]
