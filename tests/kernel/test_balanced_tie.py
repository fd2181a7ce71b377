"""exactinv_check.balanced_tie: the closed-form proof that the rightmost real pole p* of r = g/h outweighs the
poles that first reach its distance from -kappa (kappa* = the radius), checked on its own function
:func:`prove_balanced_tie`.  The methods are built here with sympy from their partial fractions
r = sum_k a_k/(z - z_k) (b_k = -a_k), so every residue and every kappa* is known before the kernel runs:
kappa* solves |z_k + kappa| = p* + kappa (sympy), and the balance is sum over the tied poles of |b_k| <= b_*."""

from fractions import Fraction as F

import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from exactinv_check.balanced_tie import prove_balanced_tie
from exactinv_check.budget import MAX_POLES, MAX_TIE_POLE_BITS, account
from exactinv_check.failure import CheckFailure, OverBudget

z, k = sp.symbols("z kappa")
small = st.fractions(min_value=F(1, 4), max_value=4, max_denominator=6)


def _rat(x):
    x = sp.Rational(x)
    return F(int(x.p), int(x.q))


def _method(terms):
    """(g, h, poles) of r = g/h = sum b_k/(z_k - z) over ``terms`` = [(pole, b)] (Gaussian rationals as sympy
    numbers), h = prod (z - z_k) monic (the proof does not use the sign of h(0)), low degree first."""
    h = sp.expand(sp.prod([z - p for p, _ in terms]))
    g = sp.expand(sum(b * sp.cancel(h / (p - z)) for p, b in terms))
    hc = [_rat(c) for c in reversed(sp.Poly(h, z).all_coeffs())]
    gc = [_rat(c) for c in reversed(sp.Poly(g, z).all_coeffs())] if g != 0 else []
    poles = [[_rat(sp.re(p)), _rat(sp.im(p))] for p, _ in terms]
    return gc, hc, poles


def _kappa_by_sympy(pstar, pole):
    """The kappa > 0 at which |pole + kappa| = p* + kappa (squared: linear in kappa)."""
    x, y = pole
    (sol,) = sp.solve(sp.Eq((x + k) ** 2 + y ** 2, (pstar + k) ** 2), k)
    return _rat(sol)


# ------------------------------------------------------------------ soundness
def test_a_pair_at_plus_minus_2i_against_a_pole_at_1_by_hand():
    # p* = 1, z = +-2i: |+-2i + kappa|^2 = 4 + kappa^2 = (1 + kappa)^2 at kappa* = 3/2; residues b = 1 at p*, and
    # (3 +- 4i)/10 on the pair (|b| = 1/2 each): 1/2 + 1/2 <= 1, a balanced tie
    g, h, poles = _method([(1, 1), (2 * sp.I, sp.Rational(3, 10) + sp.Rational(4, 10) * sp.I),
                           (-2 * sp.I, sp.Rational(3, 10) - sp.Rational(4, 10) * sp.I)])
    assert h == [F(-4), F(4), F(-1), F(1)]  # (z - 1)(z^2 + 4)
    assert prove_balanced_tie(g, h, poles) == F(3, 2)
    # the pair's residues a hair heavier: 2 |b| = 1 + 1/50 > 1 = b_*
    g, h, poles = _method([(1, 1), (2 * sp.I, sp.Rational(3, 10) + sp.Rational(41, 100) * sp.I),
                           (-2 * sp.I, sp.Rational(3, 10) - sp.Rational(41, 100) * sp.I)])
    with pytest.raises(CheckFailure, match="outweigh"):
        prove_balanced_tie(g, h, poles)


@settings(max_examples=25, deadline=None)
@given(pstar=small, x=st.fractions(min_value=-3, max_value=F(1, 5), max_denominator=5), y=small,
       u=st.fractions(min_value=-2, max_value=2, max_denominator=5), v=small, w=small)
def test_accepted_exactly_when_the_tied_pair_is_balanced_and_kappa_solves_the_distance_equation(pstar, x, y, u, v, w):
    # poles p* (residue w > 0) and x +- iy (residues u -+ iv), x < p*; the tie is at kappa_k > 0 iff |z| > p*
    pair = sp.Rational(x) + sp.I * sp.Rational(y)
    b = sp.Rational(u) + sp.I * sp.Rational(v)
    g, h, poles = _method([(sp.Rational(pstar), sp.Rational(w)), (pair, b), (sp.conjugate(pair), sp.conjugate(b))])
    if x * x + y * y <= pstar * pstar:
        with pytest.raises(CheckFailure, match="as close to 0 as p"):
            prove_balanced_tie(g, h, poles)
        return
    balanced = 4 * (u * u + v * v) <= w * w  # |b| + |conj b| <= b_*, squared (both sides >= 0)
    if balanced:
        assert prove_balanced_tie(g, h, poles) == _kappa_by_sympy(pstar, (x, y))
    else:
        with pytest.raises(CheckFailure, match="outweigh"):
            prove_balanced_tie(g, h, poles)


@settings(max_examples=15, deadline=None)
@given(pstar=small, extra=small, c=st.fractions(min_value=-2, max_value=2, max_denominator=5))
def test_an_untied_real_pole_beyond_p_star_needs_a_positive_residue(pstar, extra, c):
    # poles p*, p* + extra (residue c) and +-(p* + 1)i (tied at kappa* = 1/2 ((p*+1)^2 - p*^2)/p*, residues 1/8)
    y = sp.Rational(pstar) + 1
    g, h, poles = _method([(sp.Rational(pstar), 1), (sp.Rational(pstar + extra), sp.Rational(c)),
                           (sp.I * y, sp.Rational(1, 8)), (-sp.I * y, sp.Rational(1, 8))])
    if c > 0:
        assert prove_balanced_tie(g, h, poles) == _kappa_by_sympy(pstar, (0, pstar + 1))
    else:
        with pytest.raises(CheckFailure, match="must be real and positive with b_k > 0"):
            prove_balanced_tie(g, h, poles)


def test_three_tied_poles_one_real_and_a_farther_pair_by_hand():
    # p* = 1; -4 reaches distance 1 + kappa at kappa = (4 - 1)/2 = 3/2, as +-2i do: all three are tied and their
    # |b_k| add up: 3/10 + 1/4 + 1/4 = 4/5 <= 1 is balanced, 6/10 + 1/4 + 1/4 = 11/10 > 1 is not
    b = sp.Rational(3, 20) + sp.Rational(4, 20) * sp.I  # |b| = 1/4
    pair = [(2 * sp.I, b), (-2 * sp.I, sp.conjugate(b))]
    assert prove_balanced_tie(*_method([(1, 1), (-4, sp.Rational(-3, 10))] + pair)) == F(3, 2)
    with pytest.raises(CheckFailure, match="outweigh"):
        prove_balanced_tie(*_method([(1, 1), (-4, sp.Rational(-6, 10))] + pair))
    # +-3i reach it later (kappa = 4): not tied and not real, so their terms are not known to stay positive
    far = [(3 * sp.I, sp.Rational(1, 100)), (-3 * sp.I, sp.Rational(1, 100))]
    with pytest.raises(CheckFailure, match="a pole that is not tied must be real and positive"):
        prove_balanced_tie(*_method([(1, 1)] + pair + far))


def test_forged_pole_lists_are_rejected_for_their_reason():
    terms = [(1, 1), (2 * sp.I, sp.Rational(1, 4)), (-2 * sp.I, sp.Rational(1, 4))]
    g, h, poles = _method(terms)
    assert prove_balanced_tie(g, h, poles) == F(3, 2)
    cases = [
        ([poles[0], [F(0), F(2)], [F(0), F(-21, 10)]], "not the roots of h"),  # one pole moved
        ([poles[0], poles[1], poles[1]], "not distinct"),
        (poles[:2], "number of poles is not deg h"),
        ([poles[0], poles[1], [0, -2]], "pair \\[re, im\\] of exact rationals"),  # an int, not a Fraction
        ([poles[0], poles[1], [F(0), F(-2), F(0)]], "pair \\[re, im\\] of exact rationals"),
        (tuple(poles), "must list 2 to"),
    ]
    for forged, reason in cases:
        with pytest.raises(CheckFailure, match=reason):
            prove_balanced_tie(g, h, forged)
    with pytest.raises(CheckFailure, match="principal part at p\\* has the wrong sign"):  # b_* < 0
        prove_balanced_tie(*_method([(1, -1), (2 * sp.I, sp.Rational(1, 4)), (-2 * sp.I, sp.Rational(1, 4))]))
    with pytest.raises(CheckFailure, match="no positive real pole"):
        prove_balanced_tie(*_method([(-1, 1), (2 * sp.I, 1), (-2 * sp.I, 1)]))
    with pytest.raises(CheckFailure, match="no pole has Re z < p\\*"):  # p* = 1 and a larger real pole only
        prove_balanced_tie(*_method([(1, 1), (3, 1)]))


def test_an_irrational_residue_modulus_is_bounded_above_never_rounded_down():
    # pair residues 1 +- i: |b| = sqrt 2 each, 2 sqrt 2 = 2.828...; b_* = 2.83 is enough, 2.828 is not
    for w, ok in ((F(283, 100), True), (F(2828, 1000), False), (F(2829, 1000), True)):
        g, h, poles = _method([(1, sp.Rational(w)), (2 * sp.I, 1 + sp.I), (-2 * sp.I, 1 - sp.I)])
        if ok:
            assert prove_balanced_tie(g, h, poles) == F(3, 2)
        else:
            with pytest.raises(CheckFailure, match="outweigh"):
                prove_balanced_tie(g, h, poles)


# ------------------------------------------------------------------ resources
def test_too_many_or_too_long_poles_are_refused_before_any_product():
    many = [[F(j + 1), F(0)] for j in range(MAX_POLES + 1)]
    with account() as acc:
        with pytest.raises(CheckFailure, match=f"2 to {MAX_POLES} poles"):
            prove_balanced_tie([F(1)], [F(1)] * (MAX_POLES + 2), many)
        long = [[F(1), F(0)], [F(0), F(2 ** MAX_TIE_POLE_BITS + 1, 3)], [F(0), F(-2)]]
        with pytest.raises(CheckFailure, match=f"exceed {MAX_TIE_POLE_BITS} bits"):
            prove_balanced_tie([F(1)], [F(1)] * 4, long)
    assert acc.spent == 0  # nothing multiplied


def test_the_products_over_q_i_are_charged_before_they_run():
    g, h, poles = _method([(1, 1), (2 * sp.I, sp.Rational(1, 4)), (-2 * sp.I, sp.Rational(1, 4))])
    with account() as acc:
        assert prove_balanced_tie(g, h, poles) == F(3, 2)
    assert acc.spent > 0
    with account(limit=acc.spent // 2):
        with pytest.raises(OverBudget, match="balanced tie's products"):
            prove_balanced_tie(g, h, poles)
