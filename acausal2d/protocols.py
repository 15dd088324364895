"""Structural types (:class:`typing.Protocol`) of the objects the layers
hand each other: what the analyses, the plots and the derived signals read
of a simulation result (:class:`ResultData`; a
:class:`~acausal2d.result.Result` is one) and of a compiled model
(:class:`CompiledData`; a :class:`~acausal2d.compiled.CompiledModel` is
one), and the types of parameter and start-value arguments.

``compiled.py`` and ``result.py`` import the analysis and visual modules;
those type their arguments with these protocols instead of importing the
classes back (the package has no import circle, type-only imports included).
This module imports nothing of the package at run time."""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Protocol, Union

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from .compiler.system import System
    from .language.dsl import Component

__all__ = ["ParameterValue", "Params", "Start", "ResultData", "CompiledData"]

ParameterValue = Union[float, Sequence[float], NDArray[np.float64]]
"""A parameter's value: a number, or a vector parameter's numbers."""

Params = dict[str, ParameterValue]
"""Parameter overrides {dotted name: value} (vector parameters as a whole
or by element, ``"rod.r[0]"``)."""

Start = dict[str, float]
"""Start values {unknown's name: value} (names from
:attr:`~acausal2d.compiled.CompiledModel.start_names`)."""


class ResultData(Protocol):
    """The time series of a run as the analyses and plots read them."""

    time: NDArray[np.float64]
    outputs: list[str]
    model: CompiledData | None

    @property
    def names(self) -> list[str]:
        """Names of all time-varying columns."""

    def __getitem__(self, name: str) -> NDArray[np.float64]:
        """Values of a column, a parameter or ``"time"`` over ``time``."""

    def unit(self, name: str) -> str:
        """Declared unit of a column or parameter ('' if none)."""


class CompiledData(Protocol):
    """A compiled model as the analyses and a result read it."""

    model: Component
    system: System

    @property
    def units(self) -> dict[str, str]:
        """{column or parameter name: unit}."""

    def parameter_values(self, params: Params | None = None) -> NDArray[np.float64]:
        """The numeric parameter vector with the overrides ``params``."""

    def start_indices(self, start: Start | None) -> dict[int, float] | None:
        """``start`` as {node index: value}, checked."""
