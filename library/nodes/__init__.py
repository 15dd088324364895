"""The node/constraint front end of the talk "Lightweight prototypal
mechanism simulation on the web" (Schnabel/Goessner; cstr.js and mec2):

- :mod:`.elements`: what a :class:`acausal2d.language.nodes.NodeModel`
  compiles into -- nodes (point masses, talk eq. 5), two-node constraints
  in polar form (eq. 3), the included angle, holds, drives, couplings and
  the loads of mec2;
- :mod:`.drives`: mec2's drive laws (Dt, Dz, t0, repeat, bounce, seq);
- :mod:`.correction`: the talk's position correction (eq. 3-16).
"""
from .elements import (AngleDrive, AngleHold, Coupling, IncludedAngle, LengthDrive, LengthHold,
                       Link, Node, NodeForce, NodePort, NodeSpring)

__all__ = ["NodePort", "Node", "Link", "IncludedAngle", "AngleHold", "LengthHold",
           "AngleDrive", "LengthDrive", "Coupling", "NodeForce", "NodeSpring"]
