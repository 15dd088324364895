"""Belt and rope drives: elastic belt spans, circular pulleys ("Bandrolle"),
drums and a driven rope end (Ebert 2015, ch. 4.4, eq. 4.52-4.99).

Elements and ports (names of Ebert 2015)
----------------------------------------
- :class:`Belt` -- elastic belt / rope span (eq. 4.52-4.66): mechanical
  ports ``ctr2D1``, ``ctr2D2`` (end points P1, P2) and band ports ``ctrB1``,
  ``ctrB2``.
- :class:`SpringBelt` -- inextensible band with a discrete tension spring and
  damper (eq. 4.78-4.86), same ports.
- :class:`NozzleBelt` -- elastic belt through a frictionless draw-off nozzle
  at ``ctr2D3`` (eq. 4.67-4.77).
- :class:`Band` -- inextensible band or rope section (the rigid limit of
  Belt); a link of Ebert (2015), eq. 2.1 with pins or band joints at its ends.
- :class:`GuideContour` -- circular contour over which a band slides
  without friction (Ebert 2015, Bild 2.1 b/c; band joints with f = 2).
- :class:`Pulley` -- circular pulley "Bandrolle" (eq. 4.87-4.99, the dissertation's
  interface): housing connection ``ctr2D1`` with the axis P1 placed by
  ``x10, y10, phi10, frameRef`` (Anhang A.1, :mod:`.placement`), contact
  frames ``ctrK1``, ``ctrK2``, band ports ``ctrB1``, ``ctrB2``, flanges
  ``ctrR1`` (housing) and ``ctrR2`` (pulley), winding direction ``w_i`` and
  half-planes ``enumHE1``, ``enumHE2`` (Tabelle 4.15, 4.16).
- :class:`Drum` -- circular drum with one contact point and the rope end
  fixed on the contour (Ebert 2015, end of ch. 4.4.4).
- :class:`RopeDrive` -- a rope end (point) moved along a straight line by the
  signal ``s_in`` (for pulling a rope with a drive function).
- :class:`CurvedPulley`, :class:`CurvedDrum` -- pulley and drum with curved
  contour (eq. 4.100-4.122) on a :class:`Contour` or :class:`SupportContour`;
  they have the same ports and connect to the spans in the same way.  The
  start values of spans ending on them come from :func:`tangent_any`.
- :class:`Carriage`, :class:`Hook` -- the cable crane's carriage and hook
  (Ebert 2015, ch. 8.1).

One element (or concern) per module: :mod:`.spans` (Belt, SpringBelt,
NozzleBelt), :mod:`.pulley`, :mod:`.drum`, :mod:`.rope_drive`,
:mod:`.placement` (axis placement, Anhang A.1, and start poses),
:mod:`.contour` (contour forms, closed-form arc length), :mod:`.curved`
(CurvedPulley, CurvedDrum), :mod:`.layout` (connect_band, tangents, start
values), :mod:`.crane`; :mod:`.base` holds what they share.

Band connection (Ebert 2015, ch. 4.1)
-------------------------------------
A :class:`~acausal2d.language.connectors.BandPort` carries two potentials and is
connected one-to-one:

- ``gamma``: the direction (unwrapped angle, world frame) in which the span
  *leaves* the pulley/drum at this contact, i.e. points from the contact into
  the span.  The span computes it: ``ctrB1.gamma = gamma_B`` (direction
  P1 -> P2) and ``ctrB2.gamma = gamma_B + pi``.  The dissertation hands the same
  gamma_B to both ends and lets the pulley add the mounting-variant angle
  gamma_z (Tabelle 4.16); handing the leaving direction makes the pulley
  independent of the span's orientation, so the mounting variant reduces
  to the winding direction ``w`` (see :class:`Pulley`).
- ``L``: the belt material the pulley has paid out into the span at this
  contact (Ebert 2015: gewickelte Bandlaenge l_r).  It is an absolute quantity
  (r times an unwrapped angle); only its changes matter, because every span
  integrates its own unstretched length from its initial strain (see
  :class:`Belt`).  A span end that is not connected to a band port (a rope
  end fastened to a frame) has ``L = 0``.

Use :func:`connect_band` to make both connections (frame and band port) of
one span end with one call.

Start values and the mounting variant
-------------------------------------
The span angle gamma is an unwrapped variable determined by the position
equations ``x_P2 - x_P1 = l cos(gamma)``, ``y_P2 - y_P1 = l sin(gamma)``
(no atan2; eq. 4.57 without its branch cut), so it needs a start value on the
right branch.  When a model is compiled, :func:`prepare_belts` (called
automatically) evaluates the tangent construction from the parameter values
at that moment -- pulley axes (``x10, y10`` placed on the start pose of
what carries them, :class:`~acausal2d.library.belt.placement.StartPoses`),
radii, winding directions, fixed points, start values of bodies -- and sets the start values of each
span's gamma and length and the full-turn offset of each pulley's wrap
angle.  Per-instance start values given by the user (``gamma=start(...)``)
are kept.  These numbers are evaluated once at compile time: changing
geometry parameters later with ``simulate(params=...)`` keeps the branch and
winding sense chosen at compile time (the dissertation also evaluates its
additional angles once at the start of the simulation).

Bearing friction
----------------
:class:`Pulley` and :class:`Drum` take ``friction=True`` to add a Coulomb
bearing friction torque ``mu * r_pin * |F_bearing|`` (Ebert 2015, ch. 7.3.1)
opposing the rotation relative to the housing.  Sticking is not modelled by
events; the sign function is regularised as
``w_rel / sqrt(w_rel**2 + omega_s**2)`` with a small ``omega_s`` (default
1e-3 rad/s).  The relative error of the friction torque is
``0.5*(omega_s/w_rel)**2`` at speed ``w_rel``, so quasi-static results at
speeds above 100*omega_s are Coulomb-exact to 5e-5; a pulley at rest carries
no friction torque (it creeps slowly instead of sticking).  ``|F_bearing|`` is
regularised by 1e-6 N so that the torque stays differentiable at zero load.
"""
from .spans import Belt, NozzleBelt, SpringBelt
from .pulley import Pulley
from .spans import Band
from .pulley import GuideContour
from .drum import Drum
from .rope_drive import RopeDrive
from .layout import (Layout, belt_layout, connect_band, open_belt_closed_form, tangent,
                     tangent_any)
from .contour import Contour, SupportContour
from .curved import CurvedDrum, CurvedPulley
from .crane import Carriage, Hook, cycloid, move, span_geometry

__all__ = ["Belt", "SpringBelt", "NozzleBelt", "Pulley", "Drum", "RopeDrive",
           "connect_band", "belt_layout", "Layout", "tangent", "tangent_any", "open_belt_closed_form",
           "Contour", "SupportContour", "CurvedPulley", "CurvedDrum",
           "Carriage", "Hook", "cycloid", "move", "span_geometry"]
__all__ += ["Band", "GuideContour"]
