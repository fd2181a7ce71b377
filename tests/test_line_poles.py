"""Complex poles with exactly p*'s real part (exactinv/paper/line_poles.py, issue 22 item 4 / the gap it left):
proved on the line exactly, then decided; every certificate re-proved by the kernel, every radius checked
against the slow exact reference (c_j at rationals, many j: tests/radius_reference.py)."""

from fractions import Fraction as F

import flint
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from radius_reference import admissible, coefficients_at, from_partial_fractions, product

import exactinv as ei
from exactinv.core.real_algebraic import RealAlgebraic
from exactinv.core.scalars import INF
from exactinv.paper.line_poles import line_density, line_gcd, single_pair
from exactinv.paper.monotonicity import absolute_monotonicity_radius
from exactinv_check import check

BOTH = [F(1), F(-2), F(3, 2), F(-1, 2)]  # (1 - z)(1 - z + z^2/2): poles 1, 1 +- i


def _radius(g, h):
    r = absolute_monotonicity_radius(ei.methods.rational(g, h))
    verdict = check(r.certificate)
    assert verdict.ok, str(verdict)
    return r



def _upper(v) -> F:
    return v.upper if isinstance(v, RealAlgebraic) else v


def _lower(v) -> F:
    return v.lower if isinstance(v, RealAlgebraic) else v


def test_the_line_gcd_finds_exactly_the_poles_on_the_line():
    G = line_gcd(flint.fmpq_poly([2, -4, 3, -1]), F(1))  # -(z - 1)((z - 1)^2 + 1): y = 0, +-1
    assert G == flint.fmpq_poly([0, -1, 0, 1])
    off = flint.fmpq_poly([-2, 1])  # z - 2: no root on Re z = 1
    assert line_gcd(off, F(1)).degree() == 0


def test_the_issue_example_is_oo_with_f_touching_zero():
    """1/((1 - z)(1 - z + z^2/2)): b_* = 2, b = -1 at 1 +- i, so f(t) = 2 e^(-t) (1 - cos t) >= 0, touching 0 at
    t = 2 pi n: r(-x) is completely monotone and rho = oo (Bernstein).  The density polynomial is 4x^2."""
    Q, L, _ = line_density([F(1)], BOTH, F(1))
    assert Q == [0, 0, 4] and L == 1
    r = _radius([F(1)], BOTH)
    assert r.value == INF and r.reason == "bernstein"
    for kappa in (F(0), F(1, 2), F(3), F(40)):
        assert admissible([F(1)], BOTH, kappa, 300)


def test_a_numerator_that_tips_the_balance_gives_rho_4():
    """(1 + z/4)/((1 - z)(1 - z + z^2/2)): c_0(kappa) = r(-kappa) = (1 - kappa/4)/((1 + kappa)(1 + kappa + kappa^2/2))
    ends at kappa = 4, and every c_j stays >= 0 on [0, 4]: rho = 4 (b_* = 5/2 < 2|b| = sqrt(26)/2, so rho < oo)."""
    g = [F(1), F(1, 4)]
    r = _radius(g, BOTH)
    assert r.value == 4 and r.binding == 0
    assert admissible(g, BOTH, F(4), 400) and not admissible(g, BOTH, F(4) + F(1, 10 ** 6), 1)


def test_a_line_pair_with_an_irrational_height_decides_by_the_closed_form():
    """1/((1 - z)(1 - 2z/3 + z^2/3)): poles 1, 1 +- i sqrt 2, b_* = 3/2, b = -3/4 at the pair:
    f(t) = (3/2) e^(-t) (1 - cos(sqrt 2 t)) >= 0, rho = oo.  (1 + z/2)/(...) gives 4|b|^2 = 99/16 > b_*^2 = 81/16."""
    h = product([1, -1], [1, F(-2, 3), F(1, 3)])
    assert single_pair([F(1)], h, F(1)) == (F(3, 2), F(9, 16), F(2))
    assert _radius([F(1)], h).value == INF
    r = _radius([F(1), F(1, 2)], h)
    assert r.value != INF
    assert admissible([F(1), F(1, 2)], h, _lower(r.value) * F(999, 1000), 300)


def test_line_poles_beside_a_farther_pole_are_decided_by_dominance():
    """1/((1 - z)(1 - z + z^2/2)(1 - z/3)): b_* = 3 > 2|b| = 2 sqrt(9/10): p* dominates f, rho = oo; the repeated p*
    of (1 - z)^2 (1 - z + z^2/2) dominates the simple pair (t e^(-t) beats e^(-t))."""
    for h in (product(BOTH, [1, F(-1, 3)]), product([1, -1], BOTH)):
        r = _radius([F(1)], h)
        assert r.value == INF and r.reason == "bernstein"
        for kappa in (F(1, 3), F(5), F(60)):
            assert admissible([F(1)], h, kappa, 250)


def test_a_line_pole_with_a_tie_elsewhere_gives_the_tie():
    """A negative pole -2 ties with p* = 1 at kappa* = 1/2 (|-2 + k| = 1 + k); the line pair never does."""
    h = product(BOTH, [1, F(1, 2)])
    r = _radius([F(1)], h)
    assert r.value == F(1, 2) and r.reason == "tie"
    assert admissible([F(1)], h, F(1, 2), 300)


def test_an_irrational_p_star_with_a_line_pair_is_undecided_and_says_why():
    """p* = 2 - sqrt 2 and poles p* +- i (their conjugates 2 + sqrt 2 +- i): the line proof needs p* rational."""
    u2 = [F(2), F(-4), F(1)]  # (z - 2)^2 - 2 = z^2 - 4z + 2
    quartic = product([F(4), F(-4), F(1)], [F(4), F(-4), F(1)])  # (z - 2)^4 ...
    q = [a - 2 * b + (9 if i == 0 else 0) for i, (a, b) in enumerate(zip(quartic, [F(4), F(-4), F(1), 0, 0]))]
    h = product(u2, q)  # (u^2 - 2)(u^4 - 2u^2 + 9), u = z - 2
    h = [c / h[0] for c in h]
    with pytest.raises(ei.Undecided, match="rational p\\* only"):
        absolute_monotonicity_radius(ei.methods.rational([F(1)], h))


@settings(max_examples=20, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(p=st.fractions(min_value=F(1, 4), max_value=4, max_denominator=4),
       y=st.fractions(min_value=F(1, 4), max_value=3, max_denominator=4),
       b_star=st.fractions(min_value=F(1, 4), max_value=4, max_denominator=4),
       u=st.fractions(min_value=-2, max_value=2, max_denominator=4),
       v=st.fractions(min_value=-2, max_value=2, max_denominator=4),
       extra=st.sampled_from([None, "real"]))
def test_random_complex_pair_ties_are_decided_checked_and_confirmed(p, y, b_star, u, v, extra):
    """p* and a pair p* +- iy with random residues (b_*, u +- iv), optionally a farther real pole:
    decided (never Undecided), the kernel re-proves it, and the exact c_j agree: nonnegative below rho (and at
    several kappa when rho = oo), some c_j < 0 just above a finite rho."""
    if u == 0 and v == 0:
        u = F(1, 2)
    terms = [((p, F(0)), (b_star, F(0))), ((p, y), (u, v)), ((p, -y), (u, -v))]
    if extra == "real":
        terms.append(((p + 2, F(0)), (F(1), F(0))))
    g, h = from_partial_fractions(terms)
    try:
        r = _radius(g, h)
    except ei.Undecided as e:  # a resource limit, named: the witness index or the certified tail's length
        assert "j <= 8192" in str(e) or "> 4096 coefficients" in str(e), str(e)
        return
    if r.value == 0 and not r.attained:  # rho = 0, not attained: some c_j(0) < 0
        assert not admissible(g, h, F(0), r.witness_j + 1)
        return
    if r.value == INF:
        for kappa in (F(0), F(1), F(10)):
            assert admissible(g, h, kappa, 200)
        return
    below = _lower(r.value) * F(127, 128)
    assert admissible(g, h, below, 200)
    if r.binding is not None:
        above = _upper(r.value) + F(1, 10 ** 9)
        c = coefficients_at(g, h, above, r.binding + 1)
        assert c is None or c[r.binding] < 0
