"""Assessment of band curves (Ebert 2015, ch. 5, eq. 5.1-5.18): whether a
synthesised cam contour can be built, as findings, a short text report and a
plot.

The quantities come from :func:`acausal2d.library.synthesis.band_criteria`
(exact derivatives, via :func:`acausal2d.library.synthesis.functional.synthesize`
or the outputs of a ``Bandkurve(criteria=True)``).  The checks follow the
dissertation's recommendations of ch. 5.3, in its order:

1. pre-check of the transfer function: continuous up to the second
   derivative, no dwell (:func:`precheck_transfer`);
2. physical existence of the band curve: GF1 = Z (5.7) without a sign
   change (C0 of the contour), GF2 (5.9) without a sign change (C1, no
   cusp) and the dissertation's recommended flag S_Bf = sign(dl_Bf/dphi) (5.11)
   constant; a jump of the free band length is a C0 break as well;
3. space: the largest cam radius max a (5.12) against ``a_max``;
4. band stresses sigma_z (5.16) + sigma_b (5.17) <= sigma_zul (5.18) from
   the band force F_B = T/h (text of ch. 5.3, lever arm 5.13);

optionally a smallest radius of curvature of the contour (``rho_min``).

Jumps are found without a threshold on the values themselves: a quantity v
whose exact derivative v' is known is continuous between two grid points
when ``v(b) - v(a)`` equals the trapezoid ``(b - a) (v'(a) + v'(b))/2`` up to
its truncation error; a jump shows as the difference (see :func:`jumps`).
"""
from dataclasses import dataclass, field

import numpy as np
from acausal2d.visual.plotting import save_figure

__all__ = ["Finding", "BandMaterial", "Assessment", "assess", "precheck_transfer", "jumps",
           "sign_changes", "new_figure"]


@dataclass
class Finding:
    """A violated criterion: ``criterion`` (short name), ``equation`` (equation of
    Ebert 2015), ``message`` (what and where) and ``phi`` (drive parameter
    values where it happens)."""
    criterion: str
    equation: str
    message: str
    phi: list = field(default_factory=list)

    def __str__(self):
        return "%s (%s): %s" % (self.criterion, self.equation, self.message)


@dataclass
class BandMaterial:
    """Band data for the stresses of Ebert (2015), eq. 5.16-5.18: height (thickness)
    ``h_B`` [m], width ``br_B`` [m], Young's modulus ``E`` [Pa] and the
    allowed stress ``sigma_allow`` [Pa]."""
    h_B: float
    br_B: float
    E: float
    sigma_allow: float


def sign_changes(v, x):
    """Values of ``x`` between which the sign of ``v`` changes (zeros are
    skipped: a sign that touches zero and returns is no change)."""
    v = np.asarray(v, dtype=float)
    idx = np.nonzero(np.sign(v) != 0)[0]
    s = np.sign(v[idx])
    k = np.nonzero(s[1:] != s[:-1])[0]
    return [0.5 * (x[idx[j]] + x[idx[j + 1]]) for j in k]


def _mismatch(a, b, va, vb, da, db):
    return abs(vb - va - 0.5 * (b - a) * (da + db))


def jumps(x, v, dv, rel=1e-3, refine=None):
    """Intervals of the grid ``x`` over which ``v`` jumps.  Candidates: the
    difference ``v(b) - v(a)`` departs from the trapezoid of the exact
    derivative ``dv`` by more than ``rel * (b - a) * max|dv|`` (plus 1e-9 of
    max|v|).  With ``refine`` (a function giving ``(v, dv)`` at given
    points) each candidate is bisected 30 times towards its larger
    departure: a jump keeps its departure, a kink of v' (a jump of a higher
    derivative) loses it quadratically with the interval; without it the
    candidates are returned.  Returns the interval midpoints."""
    x, v, dv = (np.asarray(a, dtype=float) for a in (x, v, dv))
    ok = np.isfinite(v) & np.isfinite(dv)
    hstep = np.diff(x)
    mis = np.abs(np.diff(v) - 0.5 * hstep * (dv[1:] + dv[:-1]))
    scale = np.max(np.abs(dv[ok])) if np.any(ok) else 0.0
    vmax = np.max(np.abs(v[ok])) if np.any(ok) else 0.0
    bad = np.nonzero((mis > rel * np.abs(hstep) * scale + 1e-9 * vmax) | ~(ok[1:] & ok[:-1]))[0]
    if refine is None:
        return [0.5 * (x[j] + x[j + 1]) for j in bad]
    return [0.5 * (x[j] + x[j + 1]) for j in bad
            if not np.isfinite(mis[j]) or _persists(x[j], x[j + 1], mis[j], refine)]


def _persists(a, b, m0, refine):
    """True if the departure m0 over [a, b] survives 30 bisections."""
    for _ in range(30):
        m = 0.5 * (a + b)
        val, der = refine(np.array([a, m, b]))
        left = _mismatch(a, m, val[0], val[1], der[0], der[1])
        right = _mismatch(m, b, val[1], val[2], der[1], der[2])
        a, b = (a, m) if left >= right else (m, b)
        if not np.isfinite(max(left, right)):
            return True
    val, der = refine(np.array([a, b]))
    return _mismatch(a, b, val[0], val[1], der[0], der[1]) > 0.25 * m0


def _column_pair(fd, k):
    """(f_k, f_(k+1) * dcam) from refine's (f array, dcam)."""
    f, dcam = fd
    return f[:, k], f[:, k + 1] * dcam


def _intervals(points):
    """Group sorted points into a readable list 'a, b, c' (at most 6)."""
    pts = ["%.4g" % p for p in points[:6]]
    return ", ".join(pts) + (" ..." if len(points) > 6 else "")


def precheck_transfer(phi, f, refine=None, dcam=1.0):
    """Pre-check of the transfer function (Ebert 2015, ch. 5.3): ``f`` is an (n, 4)
    array of its values and first three derivatives with respect to the cam
    angle over the grid ``phi`` of the drive parameter; ``dcam`` the
    derivative of the cam angle with respect to it (array or number);
    ``refine`` (optional) gives (f array, dcam) at other parameter values (to
    confirm jumps, see :func:`jumps`).  Findings for a jump of f, f' or f''
    (not C2) and for a dwell (f' = 0 over an interval)."""
    f = np.asarray(f, dtype=float)
    out = []
    for k, name in enumerate(("the transfer function", "its first derivative",
                              "its second derivative")):
        ref = None if refine is None else (lambda q, k=k: _column_pair(refine(q), k))
        at = jumps(phi, f[:, k], f[:, k + 1] * dcam, refine=ref)
        if at:
            out.append(Finding("transfer function not C2", "ch. 5.3",
                               "%s jumps near phi = %s" % (name, _intervals(at)), at))
    d1 = np.abs(f[:, 1])
    still = d1 <= 1e-9 * max(np.max(d1), 1e-300)
    run = np.nonzero(still[1:] & still[:-1])[0]
    if len(run):
        at = list(phi[run])
        out.append(Finding("dwell", "ch. 5.3", "the transfer function rests (f' = 0) over phi = "
                           "%.4g .. %.4g: a dwell cannot be built with a band"
                           % (phi[run[0]], phi[run[-1] + 1]), at))
    return out


class Assessment:
    """Result of :func:`assess`: ``findings`` (list of :class:`Finding`),
    ``ok`` (no finding), ``values`` (summary numbers), the per-point arrays
    in ``series`` and the synthesis ``synthesis``; :meth:`report` and
    :meth:`plot`."""

    def __init__(self, synthesis, findings, values, series, limits):
        self.synthesis = synthesis
        self.findings = findings
        self.values = values
        self.series = series
        self.limits = limits

    @property
    def ok(self):
        """True if no criterion is violated."""
        return not self.findings

    def has(self, criterion):
        """True if a finding of ``criterion`` (substring) was raised."""
        return any(criterion in f.criterion for f in self.findings)

    def report(self):
        """Short text report of all criteria (Ebert 2015, ch. 5.3 order)."""
        v, syn = self.values, self.synthesis
        phi = syn.phi
        lines = ["Band curve assessment (Ebert 2015, ch. 5) of %s over phi = %.4g .. %.4g (%d points)"
                 % (syn.structure.name or "the structure", phi[0], phi[-1], len(phi))]

        def row(text, crit):
            bad = [f for f in self.findings if f.criterion in crit]
            lines.append("  %-62s %s" % (text, "VIOLATED" if bad else "ok"))
        if syn.transfer is not None:
            row("transfer function C2 and without dwell (ch. 5.3)",
                ("transfer function not C2", "dwell"))
        row("GF1 = Z (5.7) keeps its sign (%s)" % v["GF1 sign"], ("GF1",))
        row("GF2 (5.9) keeps its sign (%s)" % v["GF2 sign"], ("GF2",))
        row("S_Bf = sign(dl_Bf/dphi) (5.11) constant (%s), l_Bf without jumps" % v["S_Bf"],
            ("S_Bf", "free band length jumps"))
        lines.append("  free band length l_Bf (5.3):     %.4g .. %.4g m" % v["l_Bf range"])
        amax = self.limits.get("a_max")
        row("largest cam radius max a (5.12) = %.4g m%s"
            % (v["max a"], "" if amax is None else " (allowed %.4g m)" % amax), ("space",))
        lines.append("  effective lever arm h (5.13):    %.4g .. %.4g m" % v["h range"])
        lines.append("  radius of curvature of the cam (5.17): min %.4g m" % v["min rho_cam"])
        if "rho_min" in self.limits:
            row("contour radius of curvature >= %.4g m" % self.limits["rho_min"], ("curvature",))
        if "max utilisation" in v:
            row("band stress (5.16-5.18): max (sigma_z + sigma_b)/sigma_zul = %.3g"
                % v["max utilisation"], ("stress",))
        lines.append("Findings:" if self.findings else
                     "Findings: none -- the band curve can be built")
        lines += ["  - %s" % f for f in self.findings]
        return "\n".join(lines)

    def plot(self, path):
        """Write the assessment plot (contour with involute, free band length
        and its change, GF1/GF2/S_Bf, space and lever arm, stresses) as a
        PNG file (written atomically); returns ``path``."""
        fig, axes = new_figure(2, 2, (11, 8))
        _plot_contour(axes[0, 0], self.synthesis)
        _plot_band_length(axes[0, 1], self)
        _plot_limit_functions(axes[1, 0], self)
        _plot_space(axes[1, 1], self)
        fig.suptitle("Band curve assessment (Ebert 2015, ch. 5): %s"
                     % ("ok" if self.ok else "%d finding(s)" % len(self.findings)))
        fig.tight_layout()
        save_figure(fig, path, dpi=100)
        return path


def new_figure(rows=1, cols=1, size=(7, 4.5)):
    """A matplotlib Figure (object API, Agg canvas attached: the caller's
    backend is left alone) and its axes ``fig.subplots(rows, cols)``, for
    the plots of the band synthesis; write it with
    :func:`acausal2d.visual.plotting.save_figure`."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    fig = Figure(figsize=size)
    FigureCanvasAgg(fig)
    return fig, fig.subplots(rows, cols)


def _plot_contour(ax, syn):
    ax.plot(syn.x_u, syn.y_u, "-", color="steelblue", lw=2.5, label="evolute = cam contour")
    ax.plot(syn.x_e, syn.y_e, "-", color="darkorange", lw=1.2, label="involute")
    for j in np.linspace(0, len(syn.phi) - 1, 7).astype(int):
        ax.plot([syn.x_u[j], syn.x_e[j]], [syn.y_u[j], syn.y_e[j]], ":", color="gray", lw=0.8)
    ax.plot([0], [0], "k+", ms=12, mew=2, label="cam pivot")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title("cam frame (BKS): contour, involute, free band")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)


def _plot_band_length(ax, a):
    s, phi = a.series, a.synthesis.phi
    ax.plot(phi, s["l_Bf"], color="steelblue", label="free band length l_Bf [m]")
    ax.plot(phi, s["dl_Bf"], color="darkorange", label="dl_Bf/dphi [m/rad]")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel("phi [rad]")
    ax.set_title("free band length and its change (5.3, 5.10)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)


def _plot_limit_functions(ax, a):
    s, phi = a.series, a.synthesis.phi
    for name, color in (("Z", "steelblue"), ("GF2", "darkorange")):
        v = s[name]
        m = np.max(np.abs(v[np.isfinite(v)])) if np.any(np.isfinite(v)) else 1.0
        ax.plot(phi, v / (m or 1.0), color=color,
                label="%s / max|%s|" % ("GF1" if name == "Z" else name, "GF1" if name == "Z"
                                        else name))
    ax.plot(phi, s["S_Bf"], "k--", lw=1, label="S_Bf")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_ylim(-1.15, 1.15)
    ax.set_xlabel("phi [rad]")
    ax.set_title("limit functions GF1, GF2 and S_Bf (5.7, 5.9, 5.11)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)


def _plot_space(ax, a):
    s, phi = a.series, a.synthesis.phi
    ax.plot(phi, s["a"], color="steelblue", label="cam radius a [m] (5.12)")
    ax.plot(phi, s["h"], color="darkorange", label="lever arm h [m] (5.13)")
    if a.limits.get("a_max") is not None:
        ax.axhline(a.limits["a_max"], color="red", ls="--", lw=1, label="a_max")
    ax.set_xlabel("phi [rad]")
    ax.set_title("space and lever arm")
    ax.grid(True, alpha=0.3)
    if "utilisation" in s:
        ax2 = ax.twinx()
        ax2.plot(phi, s["utilisation"], color="purple", lw=1, label="stress utilisation")
        ax2.set_ylabel("(sigma_z + sigma_b)/sigma_zul")
        ax2.legend(fontsize=8, loc="lower right")
    ax.legend(fontsize=8, loc="upper left")


def _stresses(syn, band, torque, force, series):
    """Band force and stresses (5.13, 5.16-5.18) into ``series``."""
    h = series["h"]
    if force is not None:
        F = force(syn.cam) if callable(force) else np.asarray(force, dtype=float)
    else:
        T = torque(syn.cam) if callable(torque) else np.asarray(torque, dtype=float)
        F = np.abs(T) / h
    series["F_B"] = F * np.ones_like(h)
    series["sigma_z"] = series["F_B"] / (band.h_B * band.br_B)                  # 5.16
    series["sigma_b"] = band.E * band.h_B / (2 * series["rho_cam"])              # 5.17
    series["utilisation"] = (series["sigma_z"] + series["sigma_b"]) / band.sigma_allow  # 5.18


def _transfer_at(syn, q):
    v = syn.evaluate(q)
    return np.column_stack([v["f%d" % k] for k in range(4)]), v["dcam"]


def _lbf_at(syn, q):
    v = syn.evaluate(q)
    return v["l_Bf"], v["dl_Bf"] * v["dcam"]


def _existence(syn, s):
    """Findings of the physical existence (GF1, GF2, S_Bf, jumps)."""
    phi, out = syn.phi, []
    at = sign_changes(s["Z"], phi)
    if at:
        out.append(Finding("GF1", "eq. 5.7", "GF1 = Z changes sign near phi = %s: the "
                           "contour breaks apart (C0)" % _intervals(at), at))
    at = sign_changes(s["GF2"], phi)
    if at:
        out.append(Finding("GF2", "eq. 5.9", "GF2 changes sign near phi = %s: the contour has "
                           "a cusp (C1)" % _intervals(at), at))
    at = sign_changes(s["dl_Bf"], phi)
    if at:
        out.append(Finding("S_Bf", "eq. 5.11", "S_Bf = sign(dl_Bf/dphi) changes near phi = %s "
                           "(min l_Bf = %.3g m): the band curve cannot be built; if l_Bf -> 0 "
                           "the material point reaches the contour (check x0)"
                           % (_intervals(at), np.min(s["l_Bf"])), at))
    at = jumps(phi, s["l_Bf"], s["dl_Bf"] * syn.dcam, refine=lambda q: _lbf_at(syn, q))
    if at:
        out.append(Finding("free band length jumps", "eq. 5.3, 5.11", "l_Bf jumps near phi = "
                           "%s: the contour breaks apart (C0)" % _intervals(at), at))
    return out


def _signs(v):
    s = set(np.sign(v[np.isfinite(v)]).astype(int).tolist()) - {0}
    return "/".join("%+d" % k for k in sorted(s)) or "0"


def assess(synthesis, a_max=None, band=None, torque=None, force=None, rho_min=None):
    """Assess the band curve of ``synthesis`` (a
    :class:`~acausal2d.library.synthesis.functional.BandSynthesis`) after Ebert (2015),
    ch. 5.3.  Optional limits: ``a_max`` (largest allowed cam radius, 5.12),
    ``rho_min`` (smallest radius of curvature of the contour); band stresses
    (5.16-5.18) with ``band`` (a :class:`BandMaterial`) and the cam torque
    ``torque`` (array over the grid or function of the cam angle; F_B = |T|/h)
    or the band force ``force``.  Returns an :class:`Assessment`."""
    syn = synthesis
    s = {k: np.asarray(v, dtype=float) for k, v in syn.criteria.items()}
    phi = syn.phi
    findings = []
    if syn.transfer is not None:
        findings += precheck_transfer(phi, syn.transfer, refine=lambda q: _transfer_at(syn, q),
                                      dcam=syn.dcam)
    findings += _existence(syn, s)
    limits = {"a_max": a_max}
    if a_max is not None and np.max(s["a"]) > a_max:
        at = list(phi[s["a"] > a_max])
        findings.append(Finding("space", "eq. 5.12", "the cam radius a reaches %.4g m > a_max = "
                                "%.4g m near phi = %s" % (np.max(s["a"]), a_max,
                                                          _intervals(at)), at))
    if rho_min is not None:
        limits["rho_min"] = rho_min
        if np.min(s["rho_cam"]) < rho_min:
            at = list(phi[s["rho_cam"] < rho_min])
            findings.append(Finding("curvature", "eq. 5.17", "the contour is curved more "
                                    "tightly than rho_min = %.4g m near phi = %s"
                                    % (rho_min, _intervals(at)), at))
    values = {"GF1 sign": _signs(s["Z"]), "GF2 sign": _signs(s["GF2"]), "S_Bf": _signs(s["dl_Bf"]),
              "l_Bf range": (float(np.min(s["l_Bf"])), float(np.max(s["l_Bf"]))),
              "max a": float(np.max(s["a"])),
              "h range": (float(np.min(s["h"])), float(np.max(s["h"]))),
              "min rho_cam": float(np.min(s["rho_cam"]))}
    if band is not None and (torque is not None or force is not None):
        _stresses(syn, band, torque, force, s)
        values["max utilisation"] = float(np.max(s["utilisation"]))
        if values["max utilisation"] > 1.0:
            at = list(phi[s["utilisation"] > 1.0])
            findings.append(Finding("stress", "eq. 5.18", "sigma_z + sigma_b exceeds sigma_zul "
                                    "near phi = %s" % _intervals(at), at))
    return Assessment(syn, findings, values, s, limits)
