"""acausal2d component library.

- :mod:`acausal2d.library.planar`: planar multibody basics (PlanarWorld,
  Fixed, Body, FixedTranslation, Revolute, Prismatic).
- :mod:`acausal2d.library.rotational`: 1D rotational elements.
- :mod:`acausal2d.library.translational`: 1D translational elements.
- :mod:`acausal2d.library.signals`: signal sources.
"""
