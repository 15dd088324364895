"""Synthesis of band mechanisms (Ebert 2015, ch. 4.3), assessment (ch. 5) and
spring-band balancing (ch. 6), one element or method per module:

- :mod:`.dbbd` -- DB~BD (eq. 4.2-4.34), :mod:`.dbsd` -- DB~SD (eq.
  4.35-4.49), :mod:`.bandkurve` -- Bandkurve (eq. 4.50/4.51, 3.7-3.9),
  :mod:`.base` -- what the three share;
- :mod:`.functional` -- the same synthesis as CasADi expressions of the
  drive angle (``synthesize``), no simulation;
- :mod:`.assessment` -- the criteria of Ebert (2015), ch. 5;
- :mod:`.balancing` -- spring-band balancing of Ebert (2015), ch. 6;
- :mod:`.contour_export` -- cam plates as CSV/SVG/DXF and closed contours
  for CurvedDrum/CurvedPulley.

Concept (Ebert 2015, ch. 4.3 intro, 4.3.1)
------------------------------------------
Synthesis is purely kinematic.  The inversion is split in two phases: an
element computes, in world coordinates, the path of a material point P3 of
the band ("Spurpunkt") from the prescribed motions of the cam plane and of
the output link; :class:`Bandkurve` turns that path back about the cam axis
(the involute, "Evolvente", eq. 4.50/4.51) and computes its evolute, the
sought cam contour ("Bandkurve", eq. 3.7/3.8).  Every mechanical port
transmits no force and no torque (Ebert 2015, Tabelle 4.3, 4.5, 4.7).

- :class:`DB_BD` -- cam and circular roller ("DB~BD", eq. 4.2-4.34);
- :class:`DB_SD` -- cam and a tension spring in the band or a draw-off
  nozzle ("DB~SD", eq. 4.35-4.49);
- :class:`Bandkurve` -- involute, evolute and optionally the criteria of
  Ebert (2015), ch. 5 (eq. 5.1-5.17).

A band fastened to a rocker, a slider or a coupler point of any linkage
(Ebert 2015, Bild 4.7; DB~DS, DBDD structures) needs no special element: connect
that point's frame of the linkage model (e.g. ``SAN.ctr2D2``,
``DDD.ctr2D3`` with an FGP for a coupler point) directly to
``Bandkurve.ctr2D2`` -- the point *is* the material point of the band.

Ports and flows
---------------
Input ports (``ctr2D1``, ``ctr2D2`` of DB~BD and DB~SD, both ports of
Bandkurve) must be connected; the element reads their potentials and sets
their flows to zero (no reaction on the mechanism that prescribes the
motion).  The output port ``ctr2D3`` of DB~BD / DB~SD prescribes the
material point (x, y, phi = 0); its flows come from the connection, i.e.
zero when it is connected to Bandkurve.  Prescribe the motions with the
library's drives, e.g. the cam plane (the dissertation's preset "Drehpunkt A0") as
``planar.Fixed`` + ``planar.Revolute(use_flange=True)`` driven by a
``linkage_drives.Preset`` or ``rotational.Position``, and a ground point
(spring pivot "Drehpunkt B0") as ``planar.Fixed``.

The cam must turn (``der(ctr2D1.phi) != 0``): the derivatives with respect
to the cam angle are ``der(x)/der(phi_P1)`` (Ebert 2015, ch. 4.3.4: the cam is
driven at constant speed, 1 rad/s in example 7.2.1).  The prescribed motions
must be C2 for the evolute and C3 for the criteria of ch. 5 (the compiler
differentiates them exactly; the dissertation's fourth derivatives for the radius
of curvature of the cam are avoided, see :class:`Bandkurve`).

Differences from the printed equations
--------------------------------------
Verified numerically (finite differences and the closed-form checks of the
tests):

- DB~BD: 4.12 ``H6 = sqrt(H5 - r4^2)``, 4.13 ``H7 = H6^2 - r4^2 + H5``, 4.16
  ``H10 = ...``, the swapped H13/H14 of 4.31-4.34 and the K-signed 4.24
  ``x_s = x_s0 + K r4 (dphi_P2 - dgamma_B)``.  The pole construction
  4.6-4.22 and the special case 4.29-4.34 are replaced by their common
  homogeneous form (:func:`dbbd_band`): no switch, no singularity at i = 1.
- DB~SD: 4.37 ``H3 = H1^2 + H2^2`` and the K-signed 4.47/4.48 ``P3 = P2 +
  K (x + x0) e(gamma_B)``; 4.39-4.46 in explicit form (:func:`dbsd_band`),
  smooth through h = 0 (no sign(h) relation).
"""
from .base import start_xy
from .dbbd import DB_BD, dbbd_band
from .dbsd import DB_SD, dbsd_band
from .bandkurve import CRITERIA, Bandkurve, band_criteria, evolute_terms, involute

__all__ = ["DB_BD", "DB_SD", "Bandkurve", "dbbd_band", "dbsd_band", "involute",
           "evolute_terms", "band_criteria", "CRITERIA", "start_xy"]
