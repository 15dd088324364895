"""acausal2d component library.

- :mod:`acausal2d.library.planar`: planar multibody basics (PlanarWorld,
  Fixed, Body, FixedTranslation, FixedRotation, BodyShape, Revolute,
  Prismatic, IdealRolling).
- :mod:`acausal2d.library.planar.forces`: PlanarMechanics' Spring, Damper,
  SpringDamper, WorldForce, WorldTorque, RelativeForce.
- :mod:`acausal2d.library.planar.sensors`: PlanarMechanics' absolute and
  relative position/velocity/acceleration sensors, CutForce, CutTorque,
  Power, Distance.
- :mod:`acausal2d.library.rotational`: 1D rotational elements, with the
  gears of :mod:`~acausal2d.library.gears` (IdealGear, IdealPlanetary) and
  the friction elements of :mod:`~acausal2d.library.friction1d`
  (BearingFriction, Brake, OneWayClutch) re-exported under Modelica's names.
- :mod:`acausal2d.library.translational`: 1D translational elements, with
  friction1d's SupportFriction and MassWithStopAndFriction.
- :mod:`acausal2d.library.signals`: signal sources, FirstOrder,
  InverseBlockConstraints, and Modelica.Blocks' Step, Pulse, Gain, Add, Add3,
  Feedback, Limiter, Integrator, Derivative (:mod:`~acausal2d.library.blocks`),
  PID and LimPID (:mod:`~acausal2d.library.controllers`).
- :mod:`acausal2d.library.linkage`: VDI 2729 linkage elements (Ebert 2015, Anhang B).
- :mod:`acausal2d.library.linkage.drives`: motion presets, sources and
  measuring modules for the linkage elements.
- :mod:`acausal2d.library.belt`: belt and rope drives (Ebert 2015, ch. 4.4): elastic
  belt spans, belt with tension spring, belt with draw-off nozzle, circular
  pulleys and drums with optional bearing friction.
- :mod:`acausal2d.library.belt.curved`: pulley and drum with curved contour
  (Ebert 2015, eq. 4.100-4.122); contours from a function, a table, a Fourier
  series or a support function.
- :mod:`acausal2d.library.synthesis`: band synthesis elements DB_BD,
  DB_SD, Bandkurve (Ebert 2015, ch. 4.3); :mod:`~acausal2d.library.synthesis.functional`
  the same synthesis as a function (``synthesize``);
  :mod:`~acausal2d.library.synthesis.assessment` the criteria of ch. 5;
  :mod:`~acausal2d.library.synthesis.balancing` spring-band balancing of ch. 6;
  :mod:`~acausal2d.library.synthesis.contour_export` cam contours as CSV/SVG/DXF and
  as a CurvedDrum/CurvedPulley contour.
- :mod:`acausal2d.library.pneumatics`: gas cylinder with check valves.
- :mod:`acausal2d.library.hydraulics`: hydrostatics (pressure source, pump,
  motor, relief valve, volume, throttle, orifice).
- :mod:`acausal2d.library.belt.crane`: carriage and hook of the cable crane.
"""
