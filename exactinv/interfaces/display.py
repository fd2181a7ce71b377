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

from ..beyond.largest import largest_threshold, valid_steplengths
from ..core.algebraic import RealAlgebraic
from ..core.latex import latex_matrix, latex_real
from ..core.scalars import Infinity
from ..errors import InvalidInput
from ..paper.monotonicity import absolute_monotonicity_radius, taylor_coefficient_polynomials
from ..paper.threshold import steplength_threshold

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
    """LaTeX for any exactinv result or model object: its own ``to_latex()``."""
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
    return float(v)


def _polyval(coeffs, x):
    acc = 0.0
    for c in reversed(coeffs):
        acc = acc * x + float(c)
    return acc


def plot_f_i(threshold, upto: float | None = None):
    """The f_i(dt) of a polynomial-method threshold with tau_i and tau marked."""
    plt = _plt()
    finite = [r.tau for r in threshold.table if not isinstance(r.tau, Infinity)]
    top = upto or (2.0 * max([_f(t) for t in finite] + [_f(threshold.value) if not isinstance(threshold.value, Infinity) else 1.0]))
    xs = np.linspace(0, top, 400)
    fig, ax = plt.subplots(figsize=(6, 3.6))
    for r in threshold.table:
        scale = max(abs(float(c)) for c in r.f) or 1.0
        ax.plot(xs, [_polyval(r.f, x) / scale for x in xs], label=rf"$f_{r.i}$ (scaled)")
        if not isinstance(r.tau, Infinity) and r.tau != 0:
            ax.axvline(_f(r.tau), ls=":", lw=0.8, color="gray")
    if not isinstance(threshold.value, Infinity):
        ax.axvline(_f(threshold.value), color="crimson", lw=1.5, label=rf"$\tau = {latex_real(threshold.value, 6)}$")
    ax.axhline(0, color="black", lw=0.6)
    ax.set_xlabel(r"$\Delta t$")
    ax.set_title(rf"$f_i(\Delta t)$ for {threshold.method.name}, $\gamma^* = {latex_real(threshold.gamma.value)}$")
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    return fig


def plot_coefficients(method, count: int = 6, upto: float | None = None):
    """The Taylor coefficients c_j(kappa) = r^(j)(-kappa)/j! at -kappa, each scaled to [-1, 1], with rho marked."""
    plt = _plt()
    rho = absolute_monotonicity_radius(method)
    top = upto or (2.0 * _f(rho.value) if not isinstance(rho.value, Infinity) and rho.value != 0 else 4.0)
    d = taylor_coefficient_polynomials(method, count)
    xs = np.linspace(0, top, 400)
    fig, ax = plt.subplots(figsize=(6, 3.6))
    h = [float(c) for c in method.denominator]
    h_minus = np.array([_polyval([c * (-1) ** k for k, c in enumerate(h)], x) for x in xs])
    with np.errstate(divide="ignore", invalid="ignore"):
        for j, p in enumerate(d):
            coeffs = [float(c) for c in p.coeffs()] or [0.0]
            vals = np.array([_polyval(coeffs, x) for x in xs]) / h_minus ** (j + 1)  # c_j = d_j / h(-kappa)^(j+1)
            finite = np.abs(vals[np.isfinite(vals)])
            scale = max(finite.max() if finite.size else 1.0, 1e-300)
            ax.plot(xs, np.clip(vals / scale, -1.05, 1.05), label=rf"$c_{j}(\kappa)$ (scaled)")
    if not isinstance(rho.value, Infinity):
        ax.axvline(_f(rho.value), color="crimson", lw=1.5, label=rf"$\rho = {latex_real(rho.value, 6)}$")
    ax.axhline(0, color="black", lw=0.6)
    ax.set_xlabel(r"$\kappa$")
    ax.set_title(f"absolute monotonicity of {method.name}")
    ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def plot_valid_set(system, polyhedron, method, upto: float | None = None):
    """The exact valid steplengths on a number line, with the paper's, the
    corrected and the exact largest threshold."""
    plt = _plt()
    V = valid_steplengths(system, polyhedron, method)
    t = steplength_threshold(system, polyhedron, method)
    L = largest_threshold(system, polyhedron, method)
    ends = [_f(x) for iv in V for x in (iv.lo, iv.hi) if not isinstance(x, Infinity)]
    ends += [_f(v) for v in (t.paper, t.value) if not isinstance(v, Infinity)]
    top = upto or 1.25 * max(ends + [1.0])
    fig, ax = plt.subplots(figsize=(7, 1.9))
    for iv in V:
        lo, hi = _f(iv.lo), min(_f(iv.hi) if not isinstance(iv.hi, Infinity) else top, top)
        ax.plot([lo, hi], [0, 0], color="seagreen", lw=6, solid_capstyle="butt")
        ax.plot([lo], [0], "o", color="seagreen", mfc="seagreen" if iv.lo_closed else "white")
        if not isinstance(iv.hi, Infinity):
            ax.plot([hi], [0], "o", color="seagreen", mfc="seagreen" if iv.hi_closed else "white")
    for value, label, color, y in ((t.paper, "paper", "gray", 0.45), (t.value, "corrected", "royalblue", 0.25),
                                   (L.value, "largest", "crimson", -0.35)):
        if not isinstance(value, Infinity):
            ax.axvline(_f(value), color=color, ls="--", lw=1)
            ax.text(_f(value), y, f" {label} {latex_real(value, 5) if not isinstance(value, RealAlgebraic) else value.certified_digits(5)}",
                    color=color, fontsize=7)
    infinite = [label for value, label in ((t.paper, "paper"), (t.value, "corrected"), (L.value, "largest"))
                if isinstance(value, Infinity)]
    if infinite:
        ax.text(top, 0.5, " = ".join(infinite) + r" $=\infty$ ", ha="right", fontsize=7, color="gray")
    ax.set_xlim(0, top)
    ax.set_ylim(-0.6, 0.7)
    ax.set_yticks([])
    ax.set_xlabel(r"$\Delta t$")
    ax.set_title(f"valid steplengths of {method.name} (green)", fontsize=9)
    fig.tight_layout()
    return fig


def plot_images(system, polyhedron, method, dts: Sequence[Any]):
    """A 2-D polytope P and its images A_d(dt) P; vertices mapped outside P in red."""
    plt = _plt()
    if polyhedron.n != 2 or not polyhedron.is_bounded:
        raise InvalidInput("polyhedron: plot_images draws bounded polygons in the plane")

    def ordered(points):
        cx = sum(p[0] for p in points) / len(points)
        cy = sum(p[1] for p in points) / len(points)
        return sorted(points, key=lambda p: math.atan2(p[1] - cy, p[0] - cx))

    V = [(float(v[0]), float(v[1])) for v in polyhedron.vertices]
    fig, ax = plt.subplots(figsize=(4.6, 4.6))
    poly = ordered(V)
    ax.fill(*zip(*poly), color="lightgray", alpha=0.7, label="P")
    cmap = plt.get_cmap("viridis")
    for k, dt in enumerate(dts):
        Ad = method.matrix(system, Fraction(dt) if not isinstance(dt, str) else Fraction(dt))
        images = [(sum(Ad[0][j] * v[j] for j in range(2)), sum(Ad[1][j] * v[j] for j in range(2))) for v in polyhedron.vertices]
        pts = ordered([(float(x), float(y)) for x, y in images])
        color = cmap(k / max(len(dts) - 1, 1))
        ax.plot(*zip(*(pts + pts[:1])), color=color, lw=1.2, label=rf"$A_d({dt})P$")
        outside = [(float(x), float(y)) for x, y in images if not polyhedron.contains([x, y])]
        if outside:
            ax.plot(*zip(*outside), "o", color="crimson", ms=5)
    ax.set_aspect("equal")
    ax.legend(fontsize=7)
    ax.set_title(f"images of P under {method.name}; red: outside P", fontsize=9)
    fig.tight_layout()
    return fig
