"""Contours of the pulley and drum with curved contour ("Bandrolle mit
Kurvenkontur", Ebert (2015), ch. 4.4.5, eq. 4.100-4.122; the elements are in
:mod:`acausal2d.library.belt.curved`).

Contours (:class:`Contour`)
---------------------------
The contour is given in polar coordinates of the pulley frame, ``r_C(kappa)``
(Ebert 2015: "Kennlinie r_C(kappa)"), as

- :meth:`Contour.circle` -- a circle (exact: ``r_C = r``, ``s = r kappa``);
- :meth:`Contour.from_function` -- a Python function of a CasADi symbol
  (e.g. ``lambda k: a*b/ca.sqrt((b*ca.cos(k))**2 + (a*ca.sin(k))**2)``, an
  ellipse); the function is used as it is in the equations, its derivatives
  come from CasADi's automatic differentiation;
- :meth:`Contour.fourier` -- a Fourier series
  ``r_C = c0 + sum_n a_n cos(n kappa) + b_n sin(n kappa)``;
- :meth:`Contour.from_table` -- a table ``(kappa_j, r_j)`` of one period:
  the periodic cubic spline through the table (``scipy.interpolate.
  CubicSpline(bc_type="periodic")``) is sampled at 4096 points and replaced
  by its Fourier series truncated at ``n_harm`` harmonics.  We use the
  Fourier series instead of evaluating the spline piecewise because a
  piecewise ``if_else`` in the residuals is a relation, i.e. an event at
  every knot the contact point passes, and the spline's third derivative
  (needed by the index reduction: the tangency condition contains r_C' and
  is differentiated twice) would jump at every knot.  The truncation error
  of a cubic spline's series falls like ``n_harm**-4``; it is stored in
  ``Contour.fit_error`` (max deviation from the spline on the samples);
- :meth:`Contour.from_support` -- a convex contour given by the Fourier
  series of its support function ``p(psi)`` (distance from the axis to the
  tangent with outward normal angle psi), the natural description in belt
  drive synthesis; converted exactly (Newton inversion of the polar angle,
  then FFT) into a polar Fourier series;
- :class:`SupportContour` -- the same support-function description used
  directly by the element (explicit tangency and contact point, closed-form
  arc length; see its docstring).  Preferred for synthesised convex pulleys:
  the polar series of the large pulley of models/noncircular_belt_drive.py
  needs ~300 harmonics for 1e-10, its support function 24.

The contour must be star-shaped about the axis (one radius per angle); the
belt runs only on its convex parts.

Arc length (Ebert 2015, eq. 4.116-4.119)
----------------------------------------
The dissertation integrates the contact point's motion along the contour,
``dl_K = int sqrt(r_C'^2 + r_C^2) dkappa`` (4.116, 4.117).  Here the
integral is evaluated once, when the contour is built, as a closed-form
arc-length function of the contour angle (position-level, no quadrature
and no extra state during the simulation):

    s(kappa) = vbar * kappa + sum_n (A_n/n sin(n kappa) - B_n/n (cos(n kappa) - 1)),

where ``vbar + sum_n A_n cos(n kappa) + B_n sin(n kappa)`` is the Fourier
series of the speed ``sqrt(r_C^2 + r_C'^2)``, computed by FFT on a uniform
grid that is refined until the coefficients have decayed below 1e-14 of
``vbar`` (spectral accuracy for smooth contours: s' equals the speed to
about 1e-14 relative).  ``s`` is unwrapped: ``s(kappa + 2 pi) = s(kappa) +
perimeter``, so contact angles may run over any number of revolutions.
For a circle ``s = r kappa`` exactly.

Wound lengths (4.118, 4.119) with the conventions of library/belt.py
(``L`` = material paid out into the span, ``w`` the winding direction):

    ctrB1.L = w s(kappa1),   ctrB2.L = -w s(kappa2),

with kappa_i the contact angles in the pulley frame; for a circle this is
exactly the circular pulley's ``-w r (phi - kappa1_world)``.
"""
import functools
import math

import casadi as ca
import numpy as np

from acausal2d.errors import ModelDefinitionError

from .contour_checks import N_MAX, check_closed, check_increasing, not_converged



_PI = math.pi
_TWO_PI = 2.0 * math.pi


def _fourier_sx(x, base, c0, a, b):
    """c0 + sum_{j>=1} a[j-1] cos(j base x) + b[j-1] sin(j base x) as a
    CasADi expression, with the angle-addition recurrence (one cos and one
    sin evaluation).  For a symbolic ``x`` the series is expanded by a CasADi
    Function built once per number of harmonics (:func:`_fourier_function`):
    the same expression (zero coefficients drop out as constants), built in
    C++ instead of ~8 Python-level operations per harmonic."""
    if len(a) == 0:
        return c0
    if isinstance(x, ca.SX):
        return _fourier_function(len(a))(x, base, c0, ca.DM(np.asarray(a, dtype=float)),
                                         ca.DM(np.asarray(b, dtype=float)))
    out = c0
    c1, s1 = ca.cos(base * x), ca.sin(base * x)
    ck, sk = c1, s1
    for j in range(len(a)):
        if a[j] != 0.0:
            out = out + float(a[j]) * ck
        if b[j] != 0.0:
            out = out + float(b[j]) * sk
        if j + 1 < len(a):
            ck, sk = ck * c1 - sk * s1, sk * c1 + ck * s1
    return out


_GRID = 4096      # points of the numeric checks and integrals of a SupportContour


@functools.lru_cache(maxsize=8)
def _grid_trig(base, n):
    """(psi, harmonic numbers, cos, sin of their outer product) on the
    grid of :data:`_GRID` points over one revolution, read-only; computed
    as :meth:`Contour._np_series` does (identical numbers)."""
    psi = np.linspace(0.0, _TWO_PI, _GRID, endpoint=False)
    js = base * np.arange(1, n + 1, dtype=float)
    X = np.outer(psi, js)
    out = (psi, js, np.cos(X), np.sin(X))
    for arr in out:
        arr.flags.writeable = False
    return out


@functools.lru_cache(maxsize=None)
def _fourier_function(n):
    """CasADi Function (x, base, c0, a[n], b[n]) -> the series of
    :func:`_fourier_sx` with n harmonics."""
    x, base, c0 = ca.SX.sym("x"), ca.SX.sym("base"), ca.SX.sym("c0")
    a, b = ca.SX.sym("a", n), ca.SX.sym("b", n)
    c1, s1 = ca.cos(base * x), ca.sin(base * x)
    ck, sk, out = c1, s1, c0
    for j in range(n):
        out = out + a[j] * ck + b[j] * sk
        if j + 1 < n:
            ck, sk = ck * c1 - sk * s1, sk * c1 + ck * s1
    return ca.Function("fourier_%d" % n, [x, base, c0, a, b], [out])


def _series_from_samples(v, tol, n_max=None):
    """Real Fourier coefficients (c0, A_n, B_n, n = 1..) of uniform samples
    ``v`` over one period 2 pi, truncated after the last coefficient above
    ``tol`` (absolute) or at ``n_max``."""
    N = len(v)
    F = np.fft.rfft(v) / N
    c0 = float(F[0].real)
    A = 2.0 * F[1:].real
    B = -2.0 * F[1:].imag
    if N % 2 == 0:          # Nyquist term: not a clean harmonic, drop it
        A, B = A[:-1], B[:-1]
    mag = np.hypot(A, B)
    keep = np.nonzero(mag > tol)[0]
    n = int(keep[-1]) + 1 if len(keep) else 0
    if n_max is not None:
        n = min(n, n_max)
    return c0, A[:n].copy(), B[:n].copy(), mag


def _compress(A, B):
    """Harmonics that are all multiples of a common base: returns (base,
    a, b) with a[j-1], b[j-1] the coefficients of harmonic j*base."""
    idx = [n + 1 for n in range(len(A)) if A[n] != 0.0 or B[n] != 0.0]
    if not idx:
        return 1, np.zeros(0), np.zeros(0)
    base = 0
    for n in idx:
        base = math.gcd(base, n)
    m = idx[-1] // base
    a = np.array([A[j * base - 1] for j in range(1, m + 1)])
    b = np.array([B[j * base - 1] for j in range(1, m + 1)])
    return base, a, b


class _SupportFunction:
    """``p(psi) = p0 + sum_j a[j-1] cos(j base psi) + b[j-1] sin(j base psi)``;
    calling it gives ``(p, p', p'')`` at the angles ``psi``."""

    def __init__(self, p0, a, b, base):
        self.p0, self.a, self.b = p0, a, b
        self.js = base * np.arange(1, len(a) + 1, dtype=float)

    def __call__(self, psi):
        js, a, b = self.js, self.a, self.b
        C = np.cos(np.outer(psi, js))
        S = np.sin(np.outer(psi, js))
        p = self.p0 + C @ a + S @ b
        dp = (-S * js) @ a + (C * js) @ b
        d2p = (-C * js ** 2) @ a + (-S * js ** 2) @ b
        return p, dp, d2p


def _normal_angles(support, kap, x):
    """Normal angles psi whose contour points lie at the polar angles
    ``kap`` (Newton from ``x``)."""
    for _ in range(60):
        p, dp, d2p = support(x)
        cx, sx = np.cos(x), np.sin(x)
        X = p * cx - dp * sx
        Y = p * sx + dp * cx
        cross = np.cos(kap) * Y - np.sin(kap) * X
        step = cross / ((p + d2p) * np.cos(kap - x))
        x = x - step
        if np.max(np.abs(step)) < 1e-14:
            return x
    raise ModelDefinitionError("Contour.from_support: the polar angle could not be "
                               "inverted (contour not star-shaped about the axis?)")


class Contour:
    """Polar contour ``r_C(kappa)`` of a curved pulley (see the module
    docstring).  Build it with one of the class methods.

    Numeric methods take numpy arrays: :meth:`r`, :meth:`dr`, :meth:`s`,
    :meth:`point`, :meth:`support_angle`, :meth:`mass_properties`.
    Attributes: ``perimeter``, ``r_mean`` (perimeter / 2 pi), ``kind``,
    ``fit_error`` (tables only), ``n_terms`` (harmonics of the arc-length
    series)."""

    def __init__(self, builder, kind, s_series=None, symmetry=1, coefficients=None):
        self.coefficients = coefficients
        k = ca.SX.sym("kappa")
        r = builder(k)
        if not isinstance(r, ca.SX):
            r = ca.SX(r)
        dr = ca.jacobian(r, k)
        d2r = ca.jacobian(dr, k)
        self.kind = kind
        self.fit_error = 0.0
        self._builder = builder
        self._F = ca.Function("contour_r", [k], [r, dr, d2r])
        if s_series is None:
            s_series = self._arc_length_series(symmetry)
        self._s_series = s_series
        vbar, base, a, b = s_series
        self.perimeter = _TWO_PI * vbar
        self.r_mean = vbar
        self.n_terms = len(a)
        # arc length: s = vbar k + sum_j a_j/(j base) sin(j base k)
        #                         - b_j/(j base) (cos(j base k) - 1)
        js = base * np.arange(1, len(a) + 1, dtype=float)
        sa = -np.asarray(b) / js if len(a) else np.zeros(0)
        sb = np.asarray(a) / js if len(a) else np.zeros(0)
        s_const = float(-np.sum(sa))
        s_expr = vbar * k + _fourier_sx(k, base, s_const, sa, sb)
        self._S = ca.Function("contour_s", [k], [s_expr])
        self._s_np = (vbar, base, s_const, sa, sb)

    # ---------------------------------------------------------- builders
    @classmethod
    def circle(cls, r):
        """Circle of radius ``r`` about the axis (exact arc length r kappa)."""
        r = float(r)
        return cls(lambda k: r + 0.0 * k, "circle", s_series=(r, 1, np.zeros(0), np.zeros(0)))

    @classmethod
    def from_function(cls, func, symmetry=1):
        """Contour from ``func(kappa)``, a Python function building the radius
        from a CasADi SX symbol with CasADi operations (2 pi-periodic and
        smooth).  ``symmetry`` (optional) is the number of identical sectors
        (the function's period is 2 pi / symmetry); it only speeds up the
        arc-length series.  A function that does not close after one sector
        (a spiral), closes with a kink, or is not smooth is refused, naming
        the gap (:mod:`~acausal2d.library.belt.contour_checks`)."""
        return cls(func, "function", symmetry=symmetry)

    @classmethod
    def fourier(cls, c0, a=(), b=(), base=1):
        """``r_C = c0 + sum_j a[j-1] cos(j base kappa) + b[j-1] sin(j base
        kappa)`` (``base`` = number of identical sectors)."""
        a = np.asarray(a, dtype=float)
        b = np.asarray(b, dtype=float)
        if b.size == 0:
            b = np.zeros_like(a)
        if a.size == 0:
            a = np.zeros_like(b)
        if a.shape != b.shape:
            raise ModelDefinitionError("Contour.fourier: a and b need the same length")
        c0 = float(c0)
        return cls(lambda k: _fourier_sx(k, base, c0, a, b), "fourier", symmetry=base,
                   coefficients=(c0, a, b, base))

    @staticmethod
    def _np_series(x, c0, a, b, base, order):
        """Fourier series (order 0) or its derivatives (order 1, 2), numpy."""
        js = base * np.arange(1, len(a) + 1, dtype=float)
        X = np.outer(np.ravel(x), js)
        v = Contour._trig_series(c0, a, b, js, np.cos(X), np.sin(X), order)
        return v.reshape(np.shape(x))

    @staticmethod
    def _trig_series(c0, a, b, js, C, S, order):
        """The series of :meth:`_np_series` from cos/sin of its arguments."""
        if order == 0:
            v = c0 + C @ a + S @ b
        elif order == 1:
            v = (-S * js) @ a + (C * js) @ b
        else:
            v = (-C * js ** 2) @ a + (-S * js ** 2) @ b
        return v

    @classmethod
    def from_table(cls, kappa, r, n_harm=64):
        """Contour from a table of one period: ``kappa`` strictly increasing
        over less than 2 pi, ``r`` the radii.  Periodic cubic spline through
        the table, represented by its Fourier series with ``n_harm``
        harmonics (module docstring); ``fit_error`` is the largest deviation
        of the series from the spline."""
        from scipy.interpolate import CubicSpline
        kappa = np.asarray(kappa, dtype=float)
        r = np.asarray(r, dtype=float)
        if kappa.ndim != 1 or kappa.shape != r.shape or len(kappa) < 4:
            raise ModelDefinitionError("Contour.from_table: kappa and r must be 1-D tables "
                                       "of equal length (at least 4 points)")
        check_increasing(kappa)
        if np.any(r <= 0):
            raise ModelDefinitionError("Contour.from_table: radii must be positive")
        kk = np.append(kappa, kappa[0] + _TWO_PI)
        rr = np.append(r, r[0])
        spline = CubicSpline(kk, rr, bc_type="periodic")
        N = 4096
        x = np.linspace(0.0, _TWO_PI, N, endpoint=False)
        v = spline(kappa[0] + np.mod(x - kappa[0], _TWO_PI))
        c0, A, B, _ = _series_from_samples(v, 0.0, n_max=n_harm)
        con = cls.fourier(c0, A, B)
        con.kind = "table"
        con.fit_error = float(np.max(np.abs(con.r(x) - v)))
        return con

    @classmethod
    def from_support(cls, p0, a=(), b=(), base=1, tol=1e-14):
        """Convex contour from its support function ``p(psi) = p0 + sum_j
        a[j-1] cos(j base psi) + b[j-1] sin(j base psi)`` (psi: angle of the
        outward normal in the pulley frame).  The contour point of normal psi
        is ``p n + p' t`` (n, t the unit normal and tangent); its polar
        radius is sampled at uniform polar angles (Newton inversion of the
        polar angle) and transformed into a polar Fourier series, truncated
        at ``tol`` times the mean radius.  Requires ``p + p'' > 0``."""
        a = np.asarray(a, dtype=float)
        b = np.asarray(b, dtype=float)
        p_and_derivs = _SupportFunction(p0, a, b, base)
        psi = np.linspace(0.0, _TWO_PI, 4096, endpoint=False)
        p, dp, d2p = p_and_derivs(psi)
        if np.min(p + d2p) <= 0.0:
            raise ModelDefinitionError("Contour.from_support: the support function does not "
                                       "describe a convex contour (min p + p'' = %.3g)"
                                       % np.min(p + d2p))
        # polar angle of the contour point over psi (monotone for convex
        # contours), extended by one period on both sides for interpolation
        X = p * np.cos(psi) - dp * np.sin(psi)
        Y = p * np.sin(psi) + dp * np.cos(psi)
        kd = np.unwrap(np.arctan2(Y, X))
        kd_ext = np.concatenate([kd - _TWO_PI, kd, kd + _TWO_PI])
        psi_ext = np.concatenate([psi - _TWO_PI, psi, psi + _TWO_PI])
        N = 512
        while True:
            kap = np.linspace(0.0, _TWO_PI, N, endpoint=False)
            x = np.interp(kap + _TWO_PI * np.floor((kd[0] - kap) / _TWO_PI + 1.0),
                          kd_ext, psi_ext)
            x = _normal_angles(p_and_derivs, kap, x)
            p, dp, _ = p_and_derivs(x)
            rad = np.hypot(p, dp)
            c0, A, B, mag = _series_from_samples(rad, 0.0)
            if mag[len(mag) // 2:].max() < tol * c0 or N >= 8192:
                break
            N *= 2
        keep = np.nonzero(mag > tol * c0)[0]
        n = int(keep[-1]) + 1 if len(keep) else 0
        bb, aa, cb = _compress(A[:n], B[:n])
        con = cls.fourier(c0, aa, cb, base=bb)
        con.kind = "support"
        con.support = (float(p0), a, b, base)
        return con

    # ---------------------------------------------------------- arc length
    def _arc_length_series(self, symmetry, tol=1e-14):
        if self.kind == "function":         # the other kinds are periodic series
            check_closed(self, max(1, int(symmetry)))
        N = 256 * max(1, int(symmetry))
        while True:
            x = np.linspace(0.0, _TWO_PI, N, endpoint=False)
            r, dr = self.r(x), self.dr(x)
            if np.any(r <= 0):
                raise ModelDefinitionError("contour radius must be positive everywhere")
            v = np.sqrt(r * r + dr * dr)
            c0, A, B, mag = _series_from_samples(v, 0.0)
            if mag[len(mag) // 2:].max() < tol * c0:
                break
            if N >= N_MAX:
                raise not_converged(self, mag, c0, tol)
            N *= 2
        keep = np.nonzero(mag > tol * c0)[0]
        n = int(keep[-1]) + 1 if len(keep) else 0
        base, a, b = _compress(A[:n], B[:n])
        return c0, base, a, b

    # ---------------------------------------------------------- symbolic
    def r_dr_sym(self, kappa):
        """(r_C, dr_C/dkappa) as CasADi expressions of ``kappa``."""
        r, dr, _ = self._F(kappa)
        return r, dr

    def s_sym(self, kappa):
        """Arc length s(kappa) as a CasADi expression."""
        return self._S(kappa)

    # ---------------------------------------------------------- numeric
    def _eval(self, F, x, i=0):
        x = np.asarray(x, dtype=float)
        if self.coefficients is not None and F is self._F:
            c0, a, b, base = self.coefficients
            return self._np_series(x, c0, a, b, base, i)
        if F is getattr(self, "_S", None):
            vbar, base, s_const, sa, sb = self._s_np
            return vbar * x + self._np_series(x, s_const, sa, sb, base, 0)
        out = (F.map(x.size) if x.size > 1 else F)(x.reshape(1, -1))   # map: ~10x faster
        if isinstance(out, (list, tuple)):
            out = out[i]
        return np.asarray(out).reshape(x.shape)

    def r(self, kappa):
        """Radius r_C(kappa) (numpy)."""
        return self._eval(self._F, kappa, 0)

    def dr(self, kappa):
        """dr_C/dkappa (numpy)."""
        return self._eval(self._F, kappa, 1)

    def d2r(self, kappa):
        """d2r_C/dkappa2 (numpy)."""
        return self._eval(self._F, kappa, 2)

    def s(self, kappa):
        """Arc length from kappa = 0 (numpy, unwrapped)."""
        return self._eval(self._S, kappa)

    def point(self, kappa):
        """Contour point (x, y) in the pulley frame."""
        r = self.r(kappa)
        return r * np.cos(kappa), r * np.sin(kappa)

    def support_angle(self, theta):
        """Contour angle kappa of the support point in the direction theta
        (pulley frame): the point maximising r_C(kappa) cos(kappa - theta),
        where the tangent is perpendicular to that direction.  Returned in
        (theta - pi, theta + pi]."""
        theta = float(theta)
        k = theta + np.linspace(-_PI, _PI, 721)
        h = self.r(k) * np.cos(k - theta)
        x = float(k[int(np.argmax(h))])
        for _ in range(50):
            xa = np.array([x])
            r, dr, d2r = (float(f(xa)[0]) for f in (self.r, self.dr, self.d2r))
            d, c = math.sin(x - theta), math.cos(x - theta)
            g = dr * c - r * d
            dg = d2r * c - 2 * dr * d - r * c
            step = g / dg
            x -= step
            if abs(step) < 1e-15:
                break
        return theta + math.remainder(x - theta, _TWO_PI)

    def mass_properties(self, thickness, density):
        """(m, J about the centre of gravity, (x_S, y_S)) of a plain disc with
        this contour, ``thickness`` [m] and ``density`` [kg/m^3] (polar
        integrals r^2/2, r^3/3, r^4/4 over kappa; trapezoidal rule over the
        period, spectrally accurate)."""
        N = 4096
        k = np.linspace(0.0, _TWO_PI, N, endpoint=False)
        r = self.r(k)
        w = _TWO_PI / N * thickness * density
        m = w * np.sum(r ** 2 / 2)
        xs = w * np.sum(r ** 3 / 3 * np.cos(k)) / m
        ys = w * np.sum(r ** 3 / 3 * np.sin(k)) / m
        J0 = w * np.sum(r ** 4 / 4)
        return float(m), float(J0 - m * (xs * xs + ys * ys)), (float(xs), float(ys))


class SupportContour:
    """Convex contour given by its support function (module docstring)

        p(psi) = p0 + sum_j a[j-1] cos(j base psi) + b[j-1] sin(j base psi),

    psi the angle of the outward normal in the pulley frame.  Used by
    :class:`CurvedPulley` with the normal angle as the contact parameter,
    which makes every contact relation explicit (the same form as the
    circular pulley, eq. 4.87-4.96):

    - tangency: the outward normal at K1 is the leaving direction turned by
      w*pi/2, so ``phi + psi1 = gamma1 + w pi/2`` and ``phi + psi2 = gamma2 -
      w pi/2`` (no iteration, no branch choice);
    - contact point: ``K = P1 + R(phi) (p n(psi) + p'(psi) t(psi))`` (n, t
      unit normal and tangent);
    - arc length (4.116, 4.117) in closed form, since the contour's speed
      over psi is the radius of curvature p + p'':
      ``s(psi) = p0 psi + sum_j (a_j sin(j base psi) - b_j (cos(j base psi)
      - 1))/(j base) + p'(psi) - p'(0)``, exact for the finite series.

    This is the preferred description for synthesised (convex) pulleys:
    a polar series of the same contour may need hundreds of harmonics where
    the support function has a few dozen (see models/noncircular_belt_drive.py).
    ``p + p''`` must be positive (checked).  :meth:`polar` gives the
    equivalent polar :class:`Contour`.
    """

    def __init__(self, p0, a=(), b=(), base=1):
        a = np.asarray(a, dtype=float)
        b = np.asarray(b, dtype=float)
        if b.size == 0:
            b = np.zeros_like(a)
        if a.size == 0:
            a = np.zeros_like(b)
        if a.shape != b.shape:
            raise ModelDefinitionError("SupportContour: a and b need the same length")
        self.p0, self.a, self.b, self.base = float(p0), a, b, int(base)
        self.kind = "support"
        self.perimeter = _TWO_PI * self.p0
        self.r_mean = self.p0
        rho = self._p_grid(0) + self._p_grid(2)
        if np.min(rho) <= 0.0:
            raise ModelDefinitionError("SupportContour: not a convex contour (min p + p'' = %.3g)"
                                       % np.min(rho))
        self.rho_min = float(np.min(rho))

    def p(self, psi, order=0):
        """Support function or its derivatives (numpy)."""
        return Contour._np_series(np.asarray(psi, dtype=float), self.p0 if order == 0 else 0.0,
                                  self.a, self.b, self.base, order)

    def _p_grid(self, order=0):
        """:meth:`p` on the grid of :func:`_grid_trig` (the same numbers;
        the cos/sin table is shared by the contours and the model builds)."""
        _, js, C, S = _grid_trig(self.base, len(self.a))
        return Contour._trig_series(self.p0 if order == 0 else 0.0, self.a, self.b, js, C, S,
                                    order)

    def _sym(self, psi):
        js = self.base * np.arange(1, len(self.a) + 1, dtype=float)
        p = _fourier_sx(psi, self.base, self.p0, self.a, self.b)
        dp = _fourier_sx(psi, self.base, 0.0, self.b * js, -self.a * js)
        return p, dp

    def _s_coeffs(self):
        js = self.base * np.arange(1, len(self.a) + 1, dtype=float)
        # s = p0 psi + sum (a sin - b (cos - 1))/js + p'(psi) - p'(0)
        #   = p0 psi + const + sum (b js - b/js) cos + (a/js - a js) sin
        sa = self.b * js - self.b / js
        sb = self.a / js - self.a * js
        const = float(np.sum(self.b / js) - np.sum(self.b * js))
        return const, sa, sb

    def s(self, psi):
        """Arc length from psi = 0 (numpy, unwrapped)."""
        psi = np.asarray(psi, dtype=float)
        const, sa, sb = self._s_coeffs()
        return self.p0 * psi + Contour._np_series(psi, const, sa, sb, self.base, 0)

    def s_sym(self, psi):
        """Arc length as a CasADi expression of the normal angle."""
        const, sa, sb = self._s_coeffs()
        return self.p0 * psi + _fourier_sx(psi, self.base, const, sa, sb)

    def point(self, psi):
        """Contour point (x, y) of normal angle psi in the pulley frame."""
        psi = np.asarray(psi, dtype=float)
        p, dp = self.p(psi), self.p(psi, 1)
        c, s = np.cos(psi), np.sin(psi)
        return p * c - dp * s, p * s + dp * c

    def support_angle(self, theta):
        """Contact parameter of the support point in direction theta: the
        normal angle itself."""
        return float(theta)

    def mass_properties(self, thickness, density):
        """(m, J about the centre of gravity, (x_S, y_S)) of a plain disc with
        this outline (Green's theorem over the parametrised contour)."""
        N = _GRID
        psi = _grid_trig(self.base, len(self.a))[0]
        p, dp = self._p_grid(0), self._p_grid(1)
        c, s = np.cos(psi), np.sin(psi)
        x, y = p * c - dp * s, p * s + dp * c          # point(psi)
        rho = p + self._p_grid(2)
        dx, dy = -np.sin(psi) * rho, np.cos(psi) * rho
        h = _TWO_PI / N * thickness * density
        m = h * np.sum(0.5 * (x * dy - y * dx))
        xs = h * np.sum(0.5 * x * x * dy) / m
        ys = h * np.sum(-0.5 * y * y * dx) / m
        J0 = h * np.sum((x ** 3 * dy - y ** 3 * dx) / 3.0)
        return float(m), float(J0 - m * (xs * xs + ys * ys)), (float(xs), float(ys))

    def polar(self, tol=1e-14):
        """The same contour as a polar :class:`Contour`."""
        return Contour.from_support(self.p0, self.a, self.b, self.base, tol=tol)
