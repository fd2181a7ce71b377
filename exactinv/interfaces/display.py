"""Rich display: LaTeX for papers and Jupyter, and plots (matplotlib, optional).

Exact values are typeset exactly (fractions) or, for algebraic numbers, by
their defining polynomial with a decimal that shows only certified digits.
Plots evaluate polynomials in floating point *for drawing only*; every
number printed on a plot comes from the exact result.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Sequence

import numpy as np

from ..core.digits import significant_digits
from ..core.float_hint import float_hint
from ..core.latex import latex_matrix, latex_real
from ..core.real_algebraic import RealAlgebraic
from ..core.scalars import Infinity, to_rational
from ..errors import InvalidInput, NotInvariant, Undecided
from ..invariance.ellipsoids import ellipsoid_discrete_invariance
from ..model import Ellipsoid
from ..monotonicity.radius import absolute_monotonicity_radius, taylor_coefficient_polynomials
from ..thresholds.steplength import steplength_threshold
from ..validset.engine import largest_threshold, valid_steplengths
from ..validset.families import ELLIPSOIDS, family_of

__all__ = [
    "latex_real",
    "latex_matrix",
    "to_latex",
    "plot_f_i",
    "plot_coefficients",
    "plot_valid_set",
    "plot_images",
]


def to_latex(result: Any) -> str:
    """LaTeX for any exactinv result or model object: its own ``to_latex()``.

    >>> print(to_latex(Ellipsoid([["1/4"]])))
    E = \\{x : x^T \\begin{pmatrix} \\frac{1}{4} \\end{pmatrix} x \\le 1\\}
    >>> to_latex(0.5)
    Traceback (most recent call last):
    ...
    TypeError: no LaTeX for float
    """
    method = getattr(result, "to_latex", None)
    if method is None:
        raise TypeError(f"no LaTeX for {type(result).__name__}")
    return method()


# ------------------------------------------------------------------ plots
def _plt():
    try:
        import matplotlib.pyplot as plt
    except ImportError as exc:  # pragma: no cover - the notebook extra
        raise ImportError("plots need matplotlib: pip install 'exactinv[notebook]'") from exc
    return plt


def _f(v) -> float:
    """A float to draw with (+-inf beyond the double range; never raises)."""
    return float(v) if isinstance(v, (RealAlgebraic, Infinity, float)) else float_hint(v)


def _finite(v) -> bool:
    return not isinstance(v, Infinity)


def _short(v, digits: int = 5) -> str:
    """A short label for an exact value on a plot (mathtext, no LaTeX packages):
    a small fraction as is, an algebraic number by its certified digits."""
    if isinstance(v, Infinity):
        return r"\infty" if v.sign > 0 else r"-\infty"
    if isinstance(v, RealAlgebraic):
        return v.certified_digits(digits).replace("...", r"\ldots")
    v = Fraction(v)
    if v.denominator == 1:
        return str(v.numerator)
    if v.denominator < 1000 and abs(v.numerator) < 1000:
        return rf"{v.numerator}/{v.denominator}"
    return significant_digits(v, v, digits) + r"\ldots"  # certified (truncated) digits, as everywhere


def _polyval(coeffs, x):
    acc = 0.0
    for c in reversed(coeffs):
        acc = acc * x + _f(c)
    return acc


# f_i curves and tau_i marks take the qualitative tab10 colours; tau is black
_TAU_COLOR = "black"


def plot_f_i(threshold, upto: float | None = None):
    """The f_i(dt) of a polynomial-method threshold, each divided by its lowest
    term ``abs(c_i) * dt**i`` (which keeps its sign on dt > 0 and starts every curve at
    +-1), so that the sign changes are visible whatever the sizes of the f_i.
    Each tau_i (first sign change of f_i) is marked and labelled in the colour of
    its f_i; tau = min tau_i is the black line.

    Taylor(2) on x' = -x, P = [-1, 1] (gamma* = 1/2): f_1(dt) = dt - dt^2/2
    changes sign at tau_1 = 2; f_0 and f_2 never do.

    >>> import matplotlib; matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from exactinv.model import LinearSystem, Polyhedron, methods
    >>> t = steplength_threshold(LinearSystem([[-1]]), Polyhedron([[1], [-1]], [1, 1]), methods.taylor(2))
    >>> fig = plot_f_i(t)
    >>> [text.get_text() for text in fig.axes[0].get_legend().get_texts()]
    ['$f_{0}$,  $\\\\tau_{0} = \\\\infty$', '$f_{1}$,  $\\\\tau_{1} = 2$', '$f_{2}$,  $\\\\tau_{2} = \\\\infty$', '$\\\\tau = 2$']
    >>> plt.close(fig)
    """
    plt = _plt()
    marks = [_f(r.tau) for r in threshold.table if _finite(r.tau) and r.tau != 0]
    if _finite(threshold.value) and threshold.value != 0:
        marks.append(_f(threshold.value))
    top = _f(upto) if upto else 1.25 * max(marks + [1.0])
    xs = np.linspace(0.0, top, 600)[1:]
    colors = plt.get_cmap("tab10").colors
    fig, ax = plt.subplots(figsize=(6.4, 3.8))
    for k, r in enumerate(threshold.table):
        color = colors[k % len(colors)]
        low = next((j for j, c in enumerate(r.f) if c != 0), None)
        if low is None:
            continue  # f_i = 0: no condition
        lead = abs(_f(r.f[low]))
        ys = np.array([_polyval(r.f[low:], x) / lead for x in xs])
        tau_text = _short(r.tau)
        ax.plot(xs, ys, color=color, lw=1.4, label=rf"$f_{{{r.i}}}$,  $\tau_{{{r.i}}} = {tau_text}$")
        if _finite(r.tau) and r.tau != 0 and _f(r.tau) <= top:
            t = _f(r.tau)
            ax.axvline(t, color=color, ls=":", lw=1.0)
            ax.plot([t], [0], "o", color=color, ms=5, zorder=5)
            ax.annotate(rf"$\tau_{{{r.i}}}$", (t, 0), xytext=(3, -12), textcoords="offset points", color=color,
                        fontsize=9)
    if _finite(threshold.value):
        v = _f(threshold.value)
        ax.axvline(v, color=_TAU_COLOR, ls="--", lw=1.6,
                   label=rf"$\tau = {_short(threshold.value)}$" + ("" if threshold.attained else " (not attained)"))
        ax.annotate(rf"$\tau = {_short(threshold.value)}$", (v, 1.0), xycoords=("data", "axes fraction"),
                    xytext=(3, -12), textcoords="offset points", fontsize=9, color=_TAU_COLOR)
    ax.axhline(0, color="gray", lw=0.6)
    ax.set_xlim(0, top)
    ax.set_ylim(-1.6, 1.6)
    ax.set_xlabel(r"$\Delta t$")
    ax.set_ylabel(r"$f_i(\Delta t)\,/\,(|c_i|\,\Delta t^{\,i})$")
    ax.set_title(rf"sign changes of the $f_i$ for {threshold.method.name}, $\gamma^* = {_short(threshold.gamma.value)}$",
                 fontsize=10)
    ax.legend(fontsize=7, loc="lower left", framealpha=0.9)
    fig.tight_layout()
    return fig


def plot_coefficients(method, count: int = 6, upto: float | None = None):
    """The Taylor coefficients c_j(kappa) = r^(j)(-kappa)/j! at -kappa, each scaled to [-1, 1], with rho marked.

    Forward Euler: c_0 = 1 - kappa, c_1 = 1, c_j = 0 (j >= 2), so rho = 1.

    >>> import matplotlib; matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from exactinv.model import methods
    >>> fig = plot_coefficients(methods.forward_euler(), count=3)
    >>> [text.get_text() for text in fig.axes[0].get_legend().get_texts()][-1], fig.axes[0].get_xlabel()
    ('$\\\\rho = 1$', '$\\\\kappa$')
    >>> plt.close(fig)
    """
    plt = _plt()
    rho = absolute_monotonicity_radius(method)
    top = upto or (2.0 * _f(rho.value) if not isinstance(rho.value, Infinity) and rho.value != 0 else 4.0)
    d = taylor_coefficient_polynomials(method, count)
    xs = np.linspace(0, top, 400)
    fig, ax = plt.subplots(figsize=(6, 3.6))
    h = [_f(c) for c in method.denominator]
    h_minus = np.array([_polyval([c * (-1) ** k for k, c in enumerate(h)], x) for x in xs])
    with np.errstate(divide="ignore", invalid="ignore"):
        for j, p in enumerate(d):
            coeffs = [_f(c) for c in p.coeffs()] or [0.0]
            vals = np.array([_polyval(coeffs, x) for x in xs]) / h_minus ** (j + 1)  # c_j = d_j / h(-kappa)^(j+1)
            finite = np.abs(vals[np.isfinite(vals)])
            scale = max(finite.max() if finite.size else 1.0, 1e-300)
            ax.plot(xs, np.clip(vals / scale, -1.05, 1.05), label=rf"$c_{j}(\kappa)$ (scaled)")
    if not isinstance(rho.value, Infinity):
        ax.axvline(_f(rho.value), color="black", ls="--", lw=1.5, label=rf"$\rho = {_short(rho.value)}$")
    ax.axhline(0, color="black", lw=0.6)
    ax.set_xlabel(r"$\kappa$")
    ax.set_title(f"absolute monotonicity of {method.name}")
    ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def plot_valid_set(system, polyhedron, method, upto: float | None = None):
    """The exact valid steplengths on a number line, with the paper's, the
    corrected and the exact largest threshold.  Works for every answer of
    :func:`valid_steplengths`: where P is not invariant for x' = Ax there is no
    paper threshold (the plot says so) and the valid set may still hold steps.

    Taylor(2) on x' = -x, P = [-1, 1]: r(-dt) = 1 - dt + dt^2/2 lies in [-1, 1]
    iff dt <= 2, and all three thresholds are 2.

    >>> import matplotlib; matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from exactinv.model import LinearSystem, Polyhedron, methods
    >>> fig = plot_valid_set(LinearSystem([[-1]]), Polyhedron([[1], [-1]], [1, 1]), methods.taylor(2))
    >>> fig.axes[0].get_title(), [text.get_text() for text in fig.axes[0].texts]
    ('valid steplengths of taylor(2) (green): [0, 2]', [' paper $2$', ' corrected $2$', ' largest $2$'])
    >>> plt.close(fig)
    """
    plt = _plt()
    V, L, paper, corrected, why_not = _thresholds(system, polyhedron, method)
    marks = [(paper, "paper", "gray", 0.45), (corrected, "corrected", "royalblue", 0.25),
             (L.value, "largest", "crimson", -0.35)]
    ends = [_f(x) for iv in V for x in (iv.lo, iv.hi) if _finite(x)]
    ends += [_f(v) for v, *_ in marks if v is not None and _finite(v)]
    top = _f(upto) if upto else 1.25 * max(ends + [1.0])
    fig, ax = plt.subplots(figsize=(7, 1.9))
    _draw_intervals(ax, V, top)
    _draw_marks(ax, marks, why_not, top)
    ax.set_xlim(0, top)
    ax.set_ylim(-0.6, 0.7)
    ax.set_yticks([])
    ax.set_xlabel(r"$\Delta t$")
    title = f"valid steplengths of {method.name} (green): {V.intervals!r}".replace("oo", "∞").replace(" U ", " ∪ ")
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    return fig


def _thresholds(system, polyhedron, method):
    """(valid set, largest threshold, the paper's and the corrected threshold or None, why none)."""
    V, L = valid_steplengths(system, polyhedron, method), largest_threshold(system, polyhedron, method)
    if not family_of(polyhedron).paper_applies:  # the paper is about polyhedra: no paper threshold on E
        return V, L, None, None, "the paper's theorems are about polyhedra"
    try:
        t = steplength_threshold(system, polyhedron, method)
        return V, L, t.paper, t.value, None
    except (NotInvariant, Undecided) as exc:
        return V, L, None, None, "P is not invariant for x' = Ax" if isinstance(exc, NotInvariant) else "undecided"


def _draw_intervals(ax, V, top: float) -> None:
    """The valid intervals as thick green segments (open ends hollow, infinite ends an arrow)."""
    for iv in V:
        if _f(iv.lo) > top:
            continue
        lo, hi = _f(iv.lo), min(_f(iv.hi) if _finite(iv.hi) else top, top)
        ax.plot([lo, hi], [0, 0], color="seagreen", lw=6, solid_capstyle="butt")
        ax.plot([lo], [0], "o", color="seagreen", mfc="seagreen" if iv.lo_closed else "white", zorder=5)
        if not _finite(iv.hi):
            ax.plot([top], [0], ">", color="seagreen", ms=10, clip_on=False, zorder=5)  # goes on to infinity
        elif _f(iv.hi) <= top:
            ax.plot([hi], [0], "o", color="seagreen", mfc="seagreen" if iv.hi_closed else "white", zorder=5)


def _draw_marks(ax, marks, why_not: str | None, top: float) -> None:
    """Dashed lines at the finite thresholds; infinite ones and a missing paper threshold as a note."""
    for value, label, color, y in marks:
        if value is not None and _finite(value):
            ax.axvline(_f(value), color=color, ls="--", lw=1)
            ax.text(_f(value), y, f" {label} ${_short(value)}$", color=color, fontsize=7)
    infinite = [label for value, label, *_ in marks if value is not None and not _finite(value)]
    notes = [" = ".join(infinite) + r" $=\infty$"] if infinite else []
    if why_not:
        notes.append(f"no paper threshold: {why_not}")
    if notes:
        ax.text(top, 0.5, "; ".join(notes) + " ", ha="right", fontsize=7, color="gray")


def plot_images(system, polyhedron, method, dts: Sequence[Any]):
    """A 2-D polytope P (or ellipse E) and its images A_d(dt) P; vertices mapped outside P
    (for E: the exact witness directions of the steps that fail) in red.

    Forward Euler on x' = -x: A_d(dt) = (1 - dt) I maps the square [-1, 1]^2
    onto itself for dt = 1 (to 0) and onto [-2, 2]^2 for dt = 3: all 4 vertices out.

    >>> import matplotlib; matplotlib.use("Agg")
    >>> import matplotlib.pyplot as plt
    >>> from exactinv.model import LinearSystem, Polyhedron, methods
    >>> square = Polyhedron([[1, 0], [-1, 0], [0, 1], [0, -1]], [1, 1, 1, 1])
    >>> fig = plot_images(LinearSystem([[-1, 0], [0, -1]]), square, methods.forward_euler(), [1, 3])
    >>> ax = fig.axes[0]
    >>> [text.get_text() for text in ax.get_legend().get_texts()]
    ['P', '$A_d(1)\\\\,P$', '$A_d(3)\\\\,P$']
    >>> [len(line.get_xdata()) for line in ax.lines if line.get_color() == "crimson"]
    [4]
    >>> plt.close(fig)
    """
    plt = _plt()
    if family_of(polyhedron) is ELLIPSOIDS:
        return _plot_ellipse_images(plt, system, polyhedron, method, dts)
    if polyhedron.n != 2 or not polyhedron.is_bounded:
        raise InvalidInput("polyhedron: plot_images draws bounded polygons in the plane")

    def ordered(points):
        cx = sum(p[0] for p in points) / len(points)
        cy = sum(p[1] for p in points) / len(points)
        return sorted(points, key=lambda p: math.atan2(p[1] - cy, p[0] - cx))

    steps = [to_rational(dt, f"dts[{k}]") for k, dt in enumerate(dts)]  # exact steps only: no floats
    V = [(_f(v[0]), _f(v[1])) for v in polyhedron.vertices]
    fig, ax = plt.subplots(figsize=(4.6, 4.6))
    poly = ordered(V)
    ax.fill(*zip(*poly), color="lightgray", alpha=0.7, label="P")
    cmap = plt.get_cmap("viridis")
    for k, dt in enumerate(steps):
        Ad = method.matrix(system, dt)
        images = [(sum(Ad[0][j] * v[j] for j in range(2)), sum(Ad[1][j] * v[j] for j in range(2))) for v in polyhedron.vertices]
        pts = ordered([(_f(x), _f(y)) for x, y in images])
        color = cmap(0.85 * k / max(len(steps) - 1, 1))  # the palest end of viridis is hard to see
        ax.plot(*zip(*(pts + pts[:1])), color=color, lw=1.2, label=rf"$A_d({_short(dt)})\,P$")
        outside = [(_f(x), _f(y)) for x, y in images if not polyhedron.contains([x, y])]
        if outside:
            ax.plot(*zip(*outside), "o", color="crimson", ms=5)
    ax.set_aspect("equal")
    ax.legend(fontsize=7)
    ax.set_title(f"images of P under {method.name}; red: outside P", fontsize=9)
    fig.tight_layout()
    return fig


def _plot_ellipse_images(plt, system, E: Ellipsoid, method, dts: Sequence[Any]):
    """The ellipse E and its images A_d(dt) E (floats for drawing only); for each step
    where the exact decision fails, the boundary point v/||v||_Q of its witness and its image."""
    if E.n != 2:
        raise InvalidInput("ellipsoid: plot_images draws ellipses in the plane")
    steps = [to_rational(dt, f"dts[{k}]") for k, dt in enumerate(dts)]
    Q = np.array([[_f(v) for v in row] for row in E.Q])
    C = np.linalg.inv(np.linalg.cholesky(Q)).T  # x = C u with |u| = 1 is the boundary of E
    u = np.array([np.cos(np.linspace(0, 2 * np.pi, 200)), np.sin(np.linspace(0, 2 * np.pi, 200))])
    boundary = C @ u
    fig, ax = plt.subplots(figsize=(4.6, 4.6))
    ax.fill(*boundary, color="lightgray", alpha=0.7, label="E")
    cmap = plt.get_cmap("viridis")
    for k, dt in enumerate(steps):
        Ad = np.array([[_f(v) for v in row] for row in method.matrix(system, dt)])
        color = cmap(0.85 * k / max(len(steps) - 1, 1))
        ax.plot(*(Ad @ boundary), color=color, lw=1.2, label=rf"$A_d({_short(dt)})\,E$")
        decision = ellipsoid_discrete_invariance(system, E, method, dt)
        if not decision.holds:
            w = decision.witness
            x = np.array([_f(c) for c in w.v]) / math.sqrt(_f(w.norm))
            ax.plot(*x, "o", color="crimson", ms=5)
            ax.plot(*(Ad @ x), "x", color="crimson", ms=6)
    ax.set_aspect("equal")
    ax.legend(fontsize=7)
    ax.set_title(f"images of E under {method.name}; red: a witness and its image", fontsize=9)
    fig.tight_layout()
    return fig
