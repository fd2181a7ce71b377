"""Random rational r = g/h with a positive real pole (degree <= 4): the engine's radius agrees with the slow
exact reference (c_j(kappa) at rationals just below and above rho), and the Undecided rate is printed."""

from fractions import Fraction

import mpmath
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from radius_reference import admissible, coefficients_at, tie_kappa

import exactinv as ei
from exactinv import methods as M
from exactinv.core.real_algebraic import RealAlgebraic

STATS = {"decided": 0, "undecided": 0}
small = st.fractions(min_value=-3, max_value=3, max_denominator=6)


@st.composite
def methods(draw):
    p = draw(st.fractions(min_value=Fraction(1, 4), max_value=4, max_denominator=8))
    q = [Fraction(1)] + draw(st.lists(small, min_size=0, max_size=3))
    den = [Fraction(0)] * (len(q) + 1)
    for i, c in enumerate(q):  # (1 - z/p) q(z)
        den[i] += c
        den[i + 1] -= c / p
    num = [Fraction(1)] + draw(st.lists(small, min_size=0, max_size=4))
    return M.rational(num, den, name="random")


def _short(value, side):
    lo, hi = (value.lower, value.upper) if isinstance(value, RealAlgebraic) else (value, value)
    grid = 10 ** 7
    return Fraction(int(lo * grid) - 50, grid) if side < 0 else Fraction(int(hi * grid) + 51, grid)


@settings(deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(methods())
def test_radius_agrees_with_the_slow_reference(m):
    try:
        r = ei.absolute_monotonicity_radius(m)
    except ei.Undecided:
        STATS["undecided"] += 1
        return
    STATS["decided"] += 1
    num, den = m.numerator, m.denominator
    J = max(80, (r.binding or 0) + 2, (r.witness_j or 0) + 2)
    if r.value == ei.INF:
        assert all(admissible(num, den, Fraction(k), J) for k in (1, 10))
        return
    if r.witness_j is not None:
        assert coefficients_at(num, den, Fraction(0), r.witness_j + 1)[-1] < 0
        return
    below, above = _short(r.value, -1), _short(r.value, +1)
    if below > 0:
        assert admissible(num, den, below, J)
    if r.reason == "tie":
        assert abs(mpmath.mpf(float(r.value)) - tie_kappa(num, den)) < 1e-9
    else:
        assert not admissible(num, den, above, J)


def test_undecided_rate_is_printed():
    total = STATS["decided"] + STATS["undecided"]
    print(f"\nradius on random rational r (degree <= 4, a positive real pole): "
          f"{STATS['undecided']} of {total} Undecided ({100 * STATS['undecided'] / max(total, 1):.1f}%)")
    assert total == 0 or STATS["undecided"] <= total // 2
