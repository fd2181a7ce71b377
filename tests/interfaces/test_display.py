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


def test_plot_f_i_marks_every_tau_in_distinct_colours():
    plt = pytest.importorskip("matplotlib.pyplot")
    from matplotlib.colors import to_rgba

    t = ei.steplength_threshold(S, P, M.taylor(4))
    fig = display.plot_f_i(t)
    ax = fig.axes[0]
    curves = [line for line in ax.lines if str(line.get_label()).startswith("$f_")]
    assert len(curves) == len(t.table)
    colours = [to_rgba(line.get_color()) for line in curves]
    tau_line = next(line for line in ax.lines if str(line.get_label()).startswith(r"$\tau ="))
    assert len(set(colours)) == len(colours) and to_rgba(tau_line.get_color()) not in colours
    texts = {a.get_text() for a in ax.texts}
    assert {r"$\tau_{1}$", r"$\tau_{3}$", r"$\tau = 1$"} <= texts  # tau_1 = 1.596..., tau_3 = 1 = tau
    # the curves are divided by their lowest term: every one starts at +-1 and the axis stays readable
    assert all(abs(abs(line.get_ydata()[0]) - 1) < 0.01 for line in curves)
    assert ax.get_xlim()[1] > 1.6 and ax.get_ylim() == (-1.6, 1.6)
    plt.close(fig)


def test_plot_valid_set_for_every_answer():
    """x' = x leaves [-1, 1]: no paper threshold, but backward Euler's valid set is [0, 0] U [2, oo)."""
    plt = pytest.importorskip("matplotlib.pyplot")
    S1, P1 = ei.LinearSystem([[1]]), ei.Polyhedron.box([-1], [1])
    assert repr(ei.valid_steplengths(S1, P1, M.backward_euler()).intervals) == "[0, 0] U [2, oo)"
    fig = display.plot_valid_set(S1, P1, M.backward_euler())
    ax = fig.axes[0]
    assert "∪ [2, ∞)" in ax.get_title() and any("not invariant" in a.get_text() for a in ax.texts)
    assert ax.get_xlim()[1] > 2
    plt.close(fig)


@pytest.mark.parametrize("dt", [0.5, float("nan"), "x"])
def test_plot_images_refuses_inexact_steps(dt):
    pytest.importorskip("matplotlib.pyplot")
    with pytest.raises(ei.InvalidInput, match=r"dts\[1\]"):
        display.plot_images(S, P, M.taylor(2), ["1/2", dt])
