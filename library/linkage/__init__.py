"""Linkage elements after VDI 2729 with masses (Ebert 2015, ch. 4.2, Anhang A, B),
one element per module, named after its section of Anhang B:

- :mod:`.dan` -- DAN, rotary drive (B.1); :mod:`.san` -- SAN, linear drive
  (B.2); :mod:`.fgp` -- FGP, guided link point (B.3);
- the Assur dyads :mod:`.ddd` (B.4), :mod:`.dds` (B.5), :mod:`.dsd` (B.6),
  :mod:`.ssd` (B.7), :mod:`.sds` (B.8);
- :mod:`.base` -- what they share: pre-assembly with K, frame placement
  (Anhang A.1), mass data (A.2, A.3), balances of massless housings and
  guides, drawing helpers;
- :mod:`.drives` -- motion presets, torque/force sources and measuring
  modules.

Conventions (common to all elements)
------------------------------------
* Ports carry the dissertation's names: ``ctr2D1`` .. ``ctr2D4`` are planar frames
  (:class:`~acausal2d.language.connectors.Frame`: x, y, phi; fx, fy, t = force and
  torque acting *on the element* from the connected part, world frame);
  ``ctrR1``/``ctrR2`` are 1D rotational and ``ctrT1``/``ctrT2`` 1D
  translational flanges.
* Ports drawn with a triangle in the dissertation (bearing housings and guides,
  Tabelle 4.1) are fixed to ground while unconnected; ports drawn with a
  plug (the moving planes of links and sliders) are free (zero force) while
  unconnected.
* Frame placement (Anhang A.1, eqs. A.1-A.9): the point ``Pn`` of an input
  port n is placed against the frame of its connection (CKS) by the
  parameters ``xn0, yn0, phin0`` (Anhang C names, e.g. ``x10, y10, phi10``).
  ``frameRefn="relative"`` (default, SimulationX ``EnumType.relativ``) takes
  them as constant coordinates in the connection frame (A.1-A.3, A.7-A.9);
  ``frameRefn="global"`` takes them as global start coordinates and converts
  them to constant relative coordinates with the connection's pose at t0
  (A.4-A.6).  An unconnected port's CKS is the global frame, so both choices
  then give the global point ``(xn0, yn0)`` with angle ``phin0``.
  Output ports (the point frames PCSn of Anhang C: DAN, SAN, FGP port 2;
  the dyads' ports 3 and 4) take ``xn0, yn0, phin0`` as the offset of the
  element's point Pn in the port's connection frame: A.7-A.9 with the
  connection frame as the unknown, the port force acting at the connection
  point (A.16-A.18); only ``frameRefn="relative"`` (a point the element
  computes has no global start pose of its own to give).
* Each element states the position-level kinematics in point-direction form
  (Bild 4.3: ``x_P = x_P1 + l cos(phi)``), the force and moment balances of
  its bodies and their mass data (Anhang A.2/A.3), nothing else: velocities
  and accelerations are produced by the compiler's index reduction.  Angles
  are unwrapped unknowns; no atan2 appears in any residual.
* Centre-of-gravity coordinates (``xS..``, ``yS..``) and body angles are
  variables of every element, so results contain them (e.g. for energy
  checks).  Inertia terms are ``m der(der(xS))`` and ``J der(der(phi))`` with
  J about the centre of gravity (A.27-A.29); gravity comes from the model's
  :class:`~acausal2d.library.planar.PlanarWorld` (default {0, -9.81} m/s²,
  the dissertation's g_x, g_y defaults).
* Massless bearing housings and guides (Anhang B intro) pass forces from the
  joint to their port; their moment balance about the connection point
  includes the offset of the placed point (A.16-A.18).

Assembly and the parameter K (ch. 4.2.1, Bild 4.3)
--------------------------------------------------
Before the first simulation the elements are assembled once, in the
sequential order of VDI 2729, from the ground-fixed ports and the drives'
start angles (parameters ``phiL0``/``xS0`` or a connected motion preset):
each element evaluates the VDI closed-form position formulas (DDD: B.42-B.52,
DDS: B.71-B.86, DSD: B.119-B.125; with the assembly parameter ``K``) as
CasADi expressions of the parameters and uses them as START values of its
angle/travel unknowns and port coordinates.  The initialization then solves
the point-direction equations from these guesses, so K picks the branch;
afterwards the motion is continuous (a dead centre is passed through, not
flipped).  Start values follow parameter changes made with
``simulate(params=...)`` without recompiling.  A user start value
(``DDD(phiL1=start(...))``) overrides the assembled guess.

Drawing and topology
--------------------
``shapes()`` draws what the VDI symbol shows, with result signals only:
links between the element's points, revolute joints (white circles) at its
pins, sliders on dashed guides for prismatic pairs, a ground symbol at each
triangle port that is unconnected (fixed to ground), the rigid arm from the
connection point to the placed point when a connected port has an offset,
and a small disc at each centre of gravity of a massive link that lies off
the pins.  Unconnected placed points are the parameters ``(xn0, yn0)``.  A
point that is no result signal -- the placed point Pn of DAN/SAN/FGP/SSD/SDS
and the DDS guide origin when that port is connected with an offset -- is
drawn at the connection point (guides are then left out).  The slider foot
points ``xPS, yPS`` (SAN, DSD), ``xPS1, yPS1`` (SSD, SDS) and ``xPS2, yPS2``
(SSD) are variables for this purpose.

``topology()`` (Ebert 2015, eq. 2.1) uses the element's *output* frames as its
links: every moving body of an element has exactly one plug port (DAN crank
``ctr2D2``; SAN slider ``ctr2D2``; DDD links ``ctr2D3``/``ctr2D4``; DDS link
``ctr2D3``, slider ``ctr2D4``; DSD guide ``ctr2D3``, slider ``ctr2D4``;
SSD/SDS sliders ``ctr2D3``/``ctr2D4``), and the triangle ports (housings,
guides) are the plane of the predecessor they are mounted on.  So the inner
pin P of a dyad needs no frame of its own: it is the joint between the two
output frames, and a dyad adds 2 links and 3 joints (f = 1 each) between its
input ports.  Unconnected triangle ports are declared ``("ground", ...)``.
FGP is rigid with its predecessor (``("rigid", [ctr2D1, ctr2D2])``).  The
motion presets declare nothing: eq. 2.1 counts the mechanism's DOF, which
a drive uses up but does not remove from the chain.

Sign conventions differing from the dissertation's text (typos there):
slider foot points are ``PS = P_guide + x_G (cos phi_U, sin phi_U)`` in all
elements (the dissertation's B.10/B.99 print ``x_P1 - x_G cos``, contradicting B.126,
B.158, B.197); the DSD start direction uses ``H6 = (H2 H4 - v H1)/H3`` so that
it is consistent with B.132/B.133.
"""
from .base import AssemblyError
from .dan import DAN
from .san import SAN
from .fgp import FGP
from .ddd import DDD, vdi_ddd
from .dds import DDS, vdi_dds
from .dsd import DSD, vdi_dsd
from .ssd import SSD, solve_ssd
from .sds import SDS, solve_sds

__all__ = ["DAN", "SAN", "FGP", "DDD", "DDS", "DSD", "SSD", "SDS", "AssemblyError",
           "vdi_ddd", "vdi_dds", "vdi_dsd", "solve_ssd", "solve_sds"]
