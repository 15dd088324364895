"""Natural frequencies, damping ratios and mode shapes of a linearisation.

The eigenvalues lambda of A (:mod:`acausal2d.analysis.linearize`) give, as
MATLAB's ``damp`` does, the natural frequency |lambda| / 2 pi, the damped
frequency |Im lambda| / 2 pi and the damping ratio -Re lambda / |lambda|;
a complex pair is one mode, a real nonzero eigenvalue an aperiodic one.
Zero eigenvalues are rigid-body modes (a free motion that meets no
stiffness): their number is the dimension of the null space of A, and
they are counted, not listed.

A mode shape is the eigenvector v mapped to every position of the
mechanism, dP/dx v, with dP/dx the sensitivities of the positions (x, y,
phi of every frame, node coordinates, 1D flange positions s and angles
phi) to the states; it is scaled to 1 + 0j at the point that moves most
(``dominant``; the largest rotation where no point moves).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..errors import translated
from .equilibrium import operating_point
from .linearize import linearize_point, signal_rows

if TYPE_CHECKING:
    from ..protocols import CompiledData, Params, Start
    from .linearize import Linearization

POSITION_SUFFIXES = (".x", ".y", ".phi", ".s")
"""Names of the positions a mode shape is given in."""
ZERO_TOL = 1e-9
"""Eigenvalues below this fraction of the largest |eigenvalue| (at least 1 1/s) are zero."""


@dataclass
class Modes:
    """``modes``: dicts (frequency_hz, damped_frequency_hz, damping_ratio,
    eigenvalue [re, im], shape {position: [re, im]}, dominant: the
    position that moves most, states: the states taking part most, by
    their nominal values) sorted by frequency;
    ``rigid_body_modes``: the number of zero eigenvalues' independent
    eigenvectors; ``linearization`` the
    :class:`~acausal2d.analysis.linearize.Linearization`; ``vectors`` the
    eigenvectors in the states (one column per mode)."""
    modes: list
    rigid_body_modes: int
    linearization: object = field(repr=False)
    vectors: np.ndarray = field(repr=False)

    def to_dict(self):
        """The JSON form of ``modes.json``."""
        lin = self.linearization
        return {"modes": self.modes, "rigid_body_modes": self.rigid_body_modes,
                "states": list(lin.states), "point": {"time": float(lin.point.t),
                                                      "kind": lin.point.kind}}

    def table(self):
        """Fixed-width text table: mode, natural and damped frequency,
        damping ratio, the position that moves most and the main states."""
        rows = [("mode", "f [Hz]", "f_d [Hz]", "damping", "largest motion", "main states")]
        for k, m in enumerate(self.modes):
            rows.append((str(k + 1), "%.6g" % m["frequency_hz"],
                         "%.6g" % m["damped_frequency_hz"],
                         "%.4g" % (m["damping_ratio"] if abs(m["damping_ratio"]) > 1e-9 else 0),
                         m["dominant"], ", ".join(m["states"])))
        widths = [max(len(r[i]) for r in rows) for i in range(6)]
        lines = ["  ".join(c.rjust(w) if i < 4 else c.ljust(w)
                           for i, (c, w) in enumerate(zip(r, widths))) for r in rows]
        lines.insert(1, "  ".join("-" * w for w in widths))
        text = "\n".join(line.rstrip() for line in lines)
        if self.rigid_body_modes:
            text += "\n%d rigid-body mode%s (zero eigenvalue)" % (
                self.rigid_body_modes, "" if self.rigid_body_modes == 1 else "s")
        return text

    def frequencies(self):
        """Natural frequencies in Hz, ascending."""
        return np.array([m["frequency_hz"] for m in self.modes])


def position_names(compiled):
    """Level-0 positions of the model: x, y, phi of frames and nodes, s and
    phi of 1D flanges (nodes and eliminated aliases named so, in m or rad)."""
    s = compiled.system
    names = [n for j, n in enumerate(s.node_names) if s.structure.var_level[j] == 0]
    names += list(s.alias_names)
    units = compiled.units
    return [n for n in names if n.endswith(POSITION_SUFFIXES) and units.get(n) in ("m", "rad")]


def _rigid_count(A):
    if not A.size:
        return 0
    sv = np.linalg.svd(A, compute_uv=False)
    return int(np.sum(sv <= ZERO_TOL * max(1.0, sv[0])))


def _dominant(shape, names):
    """Index of the largest point motion (x, y in m), or of the largest
    rotation where no point moves."""
    a = np.abs(shape)
    xy = np.array([n.endswith((".x", ".y", ".s")) for n in names], dtype=bool)
    if np.any(xy) and np.max(a[xy]) > 1e-9 * np.max(a):
        return int(np.flatnonzero(xy)[np.argmax(a[xy])])
    return int(np.argmax(a))


def _mode(lam, shape, names):
    """The dict of one mode with its shape normalised to 1 + 0j at its
    dominant entry (:func:`_dominant`)."""
    k = _dominant(shape, names) if shape.size else 0
    if shape.size and abs(shape[k]) > 0:
        shape = shape / shape[k]
    wn = abs(lam)
    return {"frequency_hz": wn / (2 * np.pi), "damped_frequency_hz": abs(lam.imag) / (2 * np.pi),
            "damping_ratio": -lam.real / wn, "eigenvalue": [float(lam.real), float(lam.imag)],
            "dominant": names[k] if shape.size else "",
            "shape": {n: [float(v.real), float(v.imag)] for n, v in zip(names, shape)
                      if abs(v) > 1e-12}}


def main_states(v, states, share=0.3, most=3):
    """Names of the states taking part most in the eigenvector ``v``
    (scaled by the states' nominal values): at least ``share`` of the
    largest, at most ``most``."""
    a = np.abs(v)
    order = [i for i in np.argsort(-a) if a[i] >= share * a.max()][:most]
    return [states[i] for i in order]


def modes_of(lin):
    """:class:`Modes` of a :class:`~acausal2d.analysis.linearize.Linearization`."""
    A = lin.A
    lam, V = np.linalg.eig(A)
    top = max(1.0, float(np.max(np.abs(lam)))) if lam.size else 1.0
    keep = [i for i in range(len(lam)) if abs(lam[i]) > ZERO_TOL * top and
            (lam[i].imag > ZERO_TOL * top or abs(lam[i].imag) <= ZERO_TOL * top)]
    keep.sort(key=lambda i: (abs(lam[i]), -lam[i].real))
    names = position_names(lin.compiled)
    P = signal_rows(lin.compiled.system, names, lin.dzdx)
    modes = []
    nominal = lin.compiled.system.nominal[[lin.compiled.system.node_names.index(n)
                                           for n in lin.states]]
    for i in keep:
        lam_i = complex(lam[i].real, lam[i].imag if abs(lam[i].imag) > ZERO_TOL * top else 0.0)
        mode = _mode(lam_i, P @ V[:, i], names)
        mode["states"] = main_states(V[:, i] / nominal, lin.states)
        modes.append(mode)
    return Modes(modes, _rigid_count(A), lin, V[:, keep])


def linearize(compiled: CompiledData, at: float | None = None, equilibrium: bool = False,
              params: Params | None = None, inputs: Sequence[str] = (),
              outputs: Sequence[str] | None = None, start: Start | None = None,
              rtol: float | None = None) -> Linearization:
    """The :class:`~acausal2d.analysis.linearize.Linearization` of
    ``compiled`` at time ``at`` of a run (the start point by default) or,
    with ``equilibrium=True``, at its static equilibrium
    (:func:`~acausal2d.analysis.equilibrium.operating_point`); ``inputs``:
    parameters taken as inputs, ``outputs``: signals (default the model's
    outputs)."""
    with translated("linearising %s" % type(compiled.model).__name__):
        point = operating_point(compiled, at, equilibrium, params, start, rtol)
        return linearize_point(compiled, point, inputs, outputs)


def modes(compiled: CompiledData, at: float | None = None, equilibrium: bool = False,
          params: Params | None = None, start: Start | None = None,
          rtol: float | None = None) -> Modes:
    """Natural frequencies and mode shapes of ``compiled`` at time ``at`` of
    a run or at its static equilibrium (see :func:`linearize`)."""
    lin = linearize(compiled, at, equilibrium, params, start=start, rtol=rtol)
    with translated("computing the modes of %s" % type(compiled.model).__name__):
        return modes_of(lin)
