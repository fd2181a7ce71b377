"""exactinv_check.reals: proved reals (rationals, +-infinity, isolated roots) and their exact order, against
python-flint's real balls."""

from fractions import Fraction as F

import flint
import pytest
from hypothesis import given
from hypothesis import strategies as st

from exactinv_check.budget import account
from exactinv_check.failure import CheckFailure, OverBudget
from exactinv_check.reals import Real

square = st.integers(2, 400).filter(lambda n: int(n ** 0.5) ** 2 != n)


def _sqrt(n):
    """sqrt(n) as the root of x^2 - n in [0, n]."""
    return Real.algebraic([F(-n), F(0), F(1)], F(0), F(n))


# ------------------------------------------------------------------ soundness
@given(square, st.fractions(min_value=0, max_value=30, max_denominator=1000))
def test_a_square_root_against_rationals_agrees_with_arb(n, q):
    truth = (flint.arb(n).sqrt() - flint.arb(q.numerator) / q.denominator)
    assert truth.lower() > 0 or truth.upper() < 0  # sqrt(n) is irrational: never equal to q
    assert _sqrt(n).compare(Real.rational(q)) == (1 if truth.lower() > 0 else -1)


@given(square, square)
def test_two_square_roots_are_ordered_as_their_radicands(m, n):
    assert _sqrt(m).compare(_sqrt(n)) == (m > n) - (m < n)


def test_infinities_and_rationals():
    assert Real(inf=1).compare(_sqrt(2)) == 1 and Real(inf=-1).compare(Real.rational(F(-10**9))) == -1
    assert Real.rational(F(3, 2)).compare(_sqrt(2)) == 1  # 1.5 > 1.414...


def test_an_interval_that_isolates_no_root_or_two_is_refused():
    with pytest.raises(CheckFailure):
        Real.algebraic([F(-2), F(0), F(1)], F(2), F(3))  # no root of x^2 - 2
    with pytest.raises(CheckFailure):
        Real.algebraic([F(-2), F(0), F(1)], F(-2), F(2))  # two roots


# ------------------------------------------------------------------ resources
def test_deciding_a_near_tie_is_charged_and_stops_at_the_accounts_limit():
    # sqrt(2) against a rational about 10^-100 away: hundreds of bisections, each charged
    q = F(14142135623730950488016887242096980785696718753769480731766797379907324784621070388503875343276415727,
          10 ** 100)
    with account() as acc:
        assert _sqrt(2).compare(Real.rational(q)) == 1
    assert acc.spent > 0
    with account(limit=acc.spent // 20):
        with pytest.raises(OverBudget):
            _sqrt(2).compare(Real.rational(q))
