"""The new presets' stability functions, derived independently from their Butcher tableaux in sympy:
R(z) = 1 + z b^T (I - z A)^{-1} e, including the tableaux with sqrt(5) and sqrt(6) (Radau IIA 3,
Lobatto IIIC 4), whose R is rational although A is not; and the order conditions R(z) - e^z = O(z^(p+1))."""

from fractions import Fraction

import pytest
import sympy as sp

from exactinv import methods as M

z = sp.Symbol("z")
s5, s6 = sp.sqrt(5), sp.sqrt(6)
R = sp.Rational

TABLEAUX = {
    "radau_iia1": ([[1]], [1], 1),
    "radau_iia3": ([[(88 - 7 * s6) / 360, (296 - 169 * s6) / 1800, (-2 + 3 * s6) / 225],
                    [(296 + 169 * s6) / 1800, (88 + 7 * s6) / 360, (-2 - 3 * s6) / 225],
                    [(16 - s6) / 36, (16 + s6) / 36, R(1, 9)]], [(16 - s6) / 36, (16 + s6) / 36, R(1, 9)], 5),
    "lobatto_iiic3": ([[R(1, 6), R(-1, 3), R(1, 6)], [R(1, 6), R(5, 12), R(-1, 12)], [R(1, 6), R(2, 3), R(1, 6)]],
                      [R(1, 6), R(2, 3), R(1, 6)], 4),
    "lobatto_iiic4": ([[R(1, 12), -s5 / 12, s5 / 12, R(-1, 12)],
                       [R(1, 12), R(1, 4), (10 - 7 * s5) / 60, s5 / 60],
                       [R(1, 12), (10 + 7 * s5) / 60, R(1, 4), -s5 / 60],
                       [R(1, 12), R(5, 12), R(5, 12), R(1, 12)]], [R(1, 12), R(5, 12), R(5, 12), R(1, 12)], 6),
    "sdirk4": ([[R(1, 4), 0, 0, 0, 0], [R(1, 2), R(1, 4), 0, 0, 0], [R(17, 50), R(-1, 25), R(1, 4), 0, 0],
                [R(371, 1360), R(-137, 2720), R(15, 544), R(1, 4), 0],
                [R(25, 24), R(-49, 48), R(125, 16), R(-85, 12), R(1, 4)]],
               [R(25, 24), R(-49, 48), R(125, 16), R(-85, 12), R(1, 4)], 4),
}


def stability_function(A, b):
    """1 + z b^T (I - z A)^{-1} e, by an LU solve (entries may hold square roots)."""
    A, b = sp.Matrix(A), sp.Matrix(b)
    s = A.shape[0]
    return 1 + z * (b.T * (sp.eye(s) - z * A).LUsolve(sp.ones(s, 1)))[0, 0]


def same(r, q):
    """r == q as rational functions: the numerator of r - q expands to 0 (sqrt(5)^2 = 5 is automatic)."""
    return sp.expand(sp.numer(sp.together(r - q))) == 0


def as_sympy(method):
    return sp.cancel(method.to_sympy(z))


@pytest.mark.parametrize("name", sorted(TABLEAUX))
def test_preset_matches_its_tableau(name):
    A, b, order = TABLEAUX[name]
    preset = as_sympy(M.preset(name))
    assert same(stability_function(A, b), preset)
    assert sp.series(preset - sp.exp(z), z, 0, order + 1).removeO() == 0  # order conditions (linear problem)


@pytest.mark.parametrize("gamma", ["1/4", "1/3", "1/2", "2/3", "1"])
def test_sdirk2_family(gamma):
    g = sp.Rational(gamma)
    r = stability_function([[g, 0], [1 - 2 * g, g]], [R(1, 2), R(1, 2)])
    assert same(r, as_sympy(M.sdirk2(gamma)))
    assert sp.series(as_sympy(M.sdirk2(gamma)) - sp.exp(z), z, 0, 3).removeO() == 0


@pytest.mark.parametrize("s", range(1, 6))
def test_ssp_sdirk_is_s_midpoint_steps(s):
    A = [[R(1, 2 * s) if i == j else R(1, s) if j < i else 0 for j in range(s)] for i in range(s)]
    r = stability_function(A, [R(1, s)] * s)
    assert same(r, ((1 + z / (2 * s)) / (1 - z / (2 * s))) ** s)
    assert same(r, as_sympy(M.ssp_sdirk(s)))


def test_radau_and_lobatto_are_pade():
    """Radau IIA s = R_{s-1,s}, Lobatto IIIC s = R_{s-2,s} (Hairer-Wanner II, IV.5)."""
    assert M.radau_iia3().numerator == M.pade(2, 3).numerator
    assert M.lobatto_iiic3().denominator == M.pade(1, 3).denominator
    assert M.lobatto_iiic4().denominator == M.pade(2, 4).denominator


def test_bad_arguments():
    from exactinv import ExactinvError
    with pytest.raises(ExactinvError, match="s: the number of stages"):
        M.ssp_sdirk(0)
    with pytest.raises(ExactinvError, match="gamma"):
        M.sdirk2(0.25)
    assert M.sdirk2(Fraction(1, 4)).denominator == M.sdirk2("1/4").denominator


def test_the_comparison_can_fail():
    A, b, _ = TABLEAUX["lobatto_iiic4"]
    assert not same(stability_function(A, b), as_sympy(M.pade(3, 3)))
    assert not same(stability_function(A, b), as_sympy(M.pade(2, 4)) + z ** 7 / 10 ** 6)
