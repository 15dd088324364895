"""Checks of a contour before it is used: a polar contour
``r_C(kappa)`` closes after one turn (and repeats after each of its
``symmetry`` sectors), its table angles increase monotonically over less
than one turn, and its arc-length series converges within a bounded number
of harmonics -- each refused with a :class:`ModelDefinitionError` that
names the gap, the angle and what to change, instead of a contour that
does not close (a spiral's follower lift differs after one turn) or a
series of tens of thousands of harmonics built for a minute.
"""
import math

import numpy as np

from acausal2d.errors import ModelDefinitionError

_TWO_PI = 2.0 * math.pi
_SAMPLES = 64          # angles at which the closure is compared
_CLOSE_TOL = 1e-9      # relative to the largest radius: round-off of a periodic function ~1e-15
N_MAX = 65536          # samples of the arc-length series at most (32767 harmonics)


def _period_text(symmetry, named=False):
    text = "2 pi" if symmetry == 1 else "2 pi/%d" % symmetry
    return text + (" (symmetry=%d)" % symmetry if named and symmetry > 1 else "")


def check_closed(contour, symmetry):
    """Raise unless ``contour.r`` (and its slope ``contour.dr``) repeats
    after one sector ``2 pi/symmetry``: compared at :data:`_SAMPLES`
    angles of a sector, to :data:`_CLOSE_TOL` of the largest radius (the
    slope: of the tangent angle atan(r'/r)).  The error names the largest
    gap, where it is and the period expected."""
    period = _TWO_PI / symmetry
    k = np.linspace(0.0, period, _SAMPLES, endpoint=False)
    r0, r1 = contour.r(k), contour.r(k + period)
    if not (np.all(np.isfinite(r0)) and np.all(np.isfinite(r1))):
        raise ModelDefinitionError("Contour.from_function: the radius is not finite at every "
                                   "angle of one turn (e.g. kappa = %.6g)"
                                   % k[np.argmax(~np.isfinite(r0) | ~np.isfinite(r1))])
    scale = max(float(np.max(np.abs(np.concatenate([r0, r1])))), 1e-300)
    gap = np.abs(r1 - r0)
    j = int(np.argmax(gap >= (1.0 - 1e-6) * gap.max()))     # the first of equal gaps
    if gap[j] > _CLOSE_TOL * scale:
        raise ModelDefinitionError(
            "Contour.from_function: the contour does not close: r(kappa + %s) = %.6g m but "
            "r(kappa) = %.6g m at kappa = %.6g, a gap of %.6g m (largest over the sector); give "
            "a function with period %s (of cos(kappa) and sin(kappa), e.g. a Fourier series)%s"
            % (_period_text(symmetry), r1[j], r0[j], k[j], gap[j], _period_text(symmetry, True),
               "" if symmetry == 1 else " or the right symmetry"))
    t0 = np.arctan(contour.dr(k) / r0)
    t1 = np.arctan(contour.dr(k + period) / r1)
    turn = np.abs(t1 - t0)
    j = int(np.argmax(turn >= (1.0 - 1e-6) * turn.max()))
    if turn[j] > _CLOSE_TOL:
        raise ModelDefinitionError(
            "Contour.from_function: the contour closes with a kink: its tangent turns by %.6g "
            "deg at kappa = %.6g (slope r' = %.6g m/rad after %s, %.6g m/rad before); give a "
            "smooth function with period %s" % (
                math.degrees(t1[j] - t0[j]), k[j], contour.dr(k + period)[j],
                _period_text(symmetry), contour.dr(k)[j], _period_text(symmetry, True)))


def check_increasing(kappa):
    """Raise unless the table angles ``kappa`` increase strictly over less
    than one turn; the error names the first pair that does not, or the
    overlap of the last angle with the first plus 2 pi."""
    steps = np.diff(kappa)
    bad = np.nonzero(steps <= 0)[0]
    if len(bad):
        j = int(bad[0])
        raise ModelDefinitionError(
            "Contour.from_table: kappa must increase strictly (monotone polar angle), but "
            "kappa[%d] = %.9g is followed by kappa[%d] = %.9g; sort the table or remove the "
            "repeated angle" % (j, kappa[j], j + 1, kappa[j + 1]))
    if kappa[-1] - kappa[0] >= _TWO_PI:
        raise ModelDefinitionError(
            "Contour.from_table: kappa must cover less than one turn (one period, the first "
            "point is not repeated), but kappa[-1] - kappa[0] = %.9g >= 2 pi, an overlap of "
            "%.6g rad; drop the last point if it repeats the first"
            % (kappa[-1] - kappa[0], kappa[-1] - kappa[0] - _TWO_PI))


def not_converged(contour, mag, c0, tol):
    """The error for an arc-length series that has not reached ``tol``
    (relative to the mean speed ``c0``) with :data:`N_MAX` samples: the
    contour is not smooth (a kink or a corner); names where its slope r'
    jumps most between neighbouring angles of a 4096-point grid."""
    k = np.linspace(0.0, _TWO_PI, 4097)
    dr = contour.dr(k)
    jump = np.abs(np.diff(dr))
    j = int(np.argmax(jump))
    return ModelDefinitionError(
        "Contour.from_function: the contour is not smooth: its arc-length series still has "
        "harmonics of %.3g of the mean radius after %d (needs %.0e); its slope r' jumps by "
        "%.6g m/rad near kappa = %.6g (a kink or a corner there).  Give a smooth function, "
        "or a table (Contour.from_table smooths it by a spline)" % (
            float(np.max(mag[len(mag) // 2:])) / c0, len(mag), tol, jump[j],
            0.5 * (k[j] + k[j + 1])))
