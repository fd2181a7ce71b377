"""exactinv_check.validset: the exact valid set {h >= 0 : p_i(h) >= 0, D(h) != 0}, against sets worked out by hand
from products of linear factors with rational roots (every end known in advance)."""

from fractions import Fraction as F

import pytest
from hypothesis import given
from hypothesis import strategies as st

from exactinv_check import poly_arithmetic as pa
from exactinv_check.budget import account
from exactinv_check.failure import OverBudget
from exactinv_check.reals import Real
from exactinv_check.validset import first_end, valid_set

root = st.fractions(min_value=F(1, 8), max_value=8, max_denominator=8)


def _from_roots(roots, lead=1):
    p = [F(lead)]
    for r in roots:
        p = pa.mul(p, [-r, F(1)])  # (h - r)
    return p


def _contains(iv, h):
    """h in the interval iv, by the kernel's exact order (its ends may be algebraic numbers)."""
    x = Real.rational(h)
    above = iv.lo.compare(x) < 0 or (iv.lo_closed and iv.lo.compare(x) == 0)
    below = iv.hi is None or iv.hi.inf > 0 or x.compare(iv.hi) < 0 or (iv.hi_closed and x.compare(iv.hi) == 0)
    return above and below


def _ends(V):
    return [(iv.lo.q, None if iv.hi is None or iv.hi.inf else iv.hi.q, iv.lo_closed, iv.hi_closed) for iv in V]


def _truth(conditions, D, h):
    return pa.evaluate(D, h) != 0 and all(pa.evaluate(p, h) >= 0 for p in conditions)


# ------------------------------------------------------------------ soundness
def test_a_set_by_hand():
    # (1 - h)(2 - h) >= 0 and 3 - h >= 0:  [0, 1] U [2, 3]
    V = valid_set([F(1)], [_from_roots([F(1), F(2)]), [F(3), F(-1)]], [])
    assert _ends(V) == [(0, 1, True, True), (2, 3, True, True)]
    # a pole of D at 1/2 removes one point: [0, 1/2) U (1/2, 1]
    V = valid_set([F(1, 2), F(-1)], [[F(1), F(-1)]], [])
    assert _ends(V) == [(0, F(1, 2), True, False), (F(1, 2), 1, False, True)]


@given(st.lists(st.lists(root, min_size=1, max_size=3), min_size=1, max_size=3), st.lists(root, max_size=1))
def test_membership_agrees_with_the_definition_at_every_end_and_between(factors, poles):
    conditions = [_from_roots(rs, lead=(-1) ** len(rs)) for rs in factors]  # positive at h = 0
    D = _from_roots(poles, lead=(-1) ** len(poles))
    V = valid_set(D, conditions, [])
    points = sorted({F(0)} | {r for rs in factors for r in rs} | set(poles))
    samples = points + [(a + b) / 2 for a, b in zip(points, points[1:])] + [points[-1] + 1]
    for h in samples:
        inside = any(_contains(iv, h) for iv in V)
        assert inside == _truth(conditions, D, h), (h, V)


def test_the_first_end_is_the_end_of_the_first_interval():
    conditions = [_from_roots([F(1), F(2)]), [F(3), F(-1)]]
    end, attained = first_end([F(1)], conditions, [])
    assert end.compare(Real.rational(1)) == 0 and attained
    end, attained = first_end([F(1, 2), F(-1)], [[F(1), F(-1)]], [])  # D's root at 1/2 comes first: not attained
    assert end.compare(Real.rational(F(1, 2))) == 0 and not attained


# ------------------------------------------------------------------ resources
def test_the_work_is_charged_to_the_account_and_stops_at_its_limit():
    conditions = [_from_roots([F(k, 7), F(k + 1, 7), F(k + 2, 7)], lead=-1) for k in range(1, 30)]
    with account() as acc:
        valid_set([F(1)], conditions, [])
    assert acc.spent > 0
    with account(limit=acc.spent // 10):
        with pytest.raises(OverBudget):
            valid_set([F(1)], conditions, [])


def test_a_first_sign_change_is_remembered_only_where_it_holds():
    """p = (x - 1)(x - 3) x^40 + ... of degree > MEMO_MIN_DEGREE: its first sign change (1) is remembered for the
    certificate; a later call looking further (upper 8) reuses it, one looking only to 1/2 does not (p > 0 there), and
    a polynomial with no sign change before 1/2 is not answered from a range it was not searched on."""
    from exactinv_check.budget import MEMO_MIN_DEGREE
    base = pa.mul([F(-1), F(1)], [F(-3), F(1)])  # (x - 1)(x - 3)
    p = pa.mul(base, [F(1)] + [F(0)] * (MEMO_MIN_DEGREE + 4) + [F(1, 10 ** 6)])  # times 1 + x^(deg)/10^6 > 0
    with account() as acc:
        first, _ = first_end([F(1)], [p], [], first=[p])
        assert first.compare(Real.rational(F(1))) == 0
        spent = acc.spent
        again, _ = first_end([F(1)], [[F(8), F(-1)], p], [], first=[[F(8), F(-1)], p])
        assert again.compare(Real.rational(F(1))) == 0 and acc.spent - spent < spent
        near, _ = first_end([F(1)], [[F(1, 2), F(-1)], p], [], first=[[F(1, 2), F(-1)]])
        assert near.compare(Real.rational(F(1, 2))) == 0
