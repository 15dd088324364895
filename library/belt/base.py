"""What every element of the belt library shares: start values and wrap-angle
turns from the tangent construction of all belts of the model at t0
(:func:`acausal2d.library.belt.layout.belt_layout`, computed once per
flattening); see :mod:`acausal2d.library.belt` for the band connection.
"""
from typing import Optional
from acausal2d import Component

from .layout import _PI, _num, belt_layout  # noqa: F401  (_PI, _num: for the elements)


class _BandElement(Component):
    """Base of the belt-library elements: start values and wrap-angle turns
    from the tangent construction of all belts of the model at t0
    (:func:`belt_layout`, computed once per flattening)."""
    _layout_kind: Optional[str] = None      # "span", "nozzle" or "wheel": its part in the layout

    def derived_parameters(self, context):
        return context.shared("belt layout", lambda: belt_layout(context.model)) \
            .params.get(id(self), {})

    def guesses(self, context):
        return context.shared("belt layout", lambda: belt_layout(context.model)) \
            .guesses.get(id(self), {})

