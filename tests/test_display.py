"""Rich display: every repr renders, shows the exact value and is well-formed LaTeX; plots return figures."""

from fractions import Fraction

import pytest

import exactinv as ei
from exactinv import display
from exactinv import methods as M

S = ei.LinearSystem([[-1, 1], [-1, -1]])
P = ei.Polyhedron.box([-1, -1], [1, 1])


def _well_formed(latex: str) -> None:
    assert latex.startswith("$") and latex.endswith("$")
    depth = 0
    for ch in latex:
        depth += {"{": 1, "}": -1}.get(ch, 0)
        assert depth >= 0
    assert depth == 0
    assert latex.count(r"\begin") == latex.count(r"\end")


@pytest.mark.parametrize("obj, expected", [
    (S, r"\dot x"),
    (P, r"\le"),
    (ei.optimal_gamma(S, P), r"\gamma^* = 1"),
    (ei.steplength_threshold(S, P, M.taylor(3)), r"\tau = 1"),
    (ei.largest_threshold(S, P, M.taylor(2)), r"1.4142135623\ldots"),
    (ei.forward_euler_threshold(S, P), "= 1"),
    (ei.absolute_monotonicity_radius(M.trapezoid()), r"\rho = 2"),
    (ei.continuous_invariance(S, P), "invariant"),
    (ei.discrete_invariance([[1, 1], [0, 1]], P), "not invariant"),
    (ei.valid_steplengths(S, P, M.taylor(1)), "[0, 1]"),
    (M.trapezoid(), r"\frac"),
    (ei.real_roots([-2, 0, 1])[1][0], "x^{2}-2"),
])
def test_latex_reprs(obj, expected):
    latex = obj._repr_latex_()
    _well_formed(latex)
    assert expected in latex


def test_latex_of_the_f_i_table():
    latex = ei.steplength_threshold(S, P, M.taylor(3)).to_latex()
    assert r"\begin{array}" in latex and r"\frac{1}{6}\Delta t^{3}" in latex and "x^{3}-3x^{2}+6x-6" in latex


def test_plots_return_figures():
    plt = pytest.importorskip("matplotlib.pyplot")
    figs = [
        display.plot_f_i(ei.steplength_threshold(S, P, M.taylor(4))),
        display.plot_coefficients(M.trapezoid()),
        display.plot_valid_set(S, P, M.taylor(2)),
        display.plot_images(S, P, M.taylor(2), [Fraction(1, 2), 2]),
    ]
    for fig in figs:
        assert fig.axes and fig.axes[0].lines
        plt.close(fig)
    with pytest.raises(ValueError):
        display.plot_images(S, ei.Polyhedron([[-1, 0], [0, -1]], [0, 0]), M.taylor(2), [1])
