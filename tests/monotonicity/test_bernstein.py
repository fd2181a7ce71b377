"""rho = oo by Bernstein's theorem (exactinv.monotonicity.bernstein, exactinv_check.bernstein), and repeated real poles.

Ground truth is independent of the engine: the closed form of issue 22 for (1 - z)/(1 - 2z)^4; functions built
on the Laplace side from a density f that is positive by construction (so rho = oo is known); and the slow exact
reference c_j(kappa) at rationals (tests/radius_reference.py) for every decided radius.  Every certificate is
re-proved by the kernel.
"""

from fractions import Fraction as F
from math import comb

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from radius_reference import admissible, coefficients_at

import exactinv as ei
from exactinv import methods as M
from exactinv.core.real_algebraic import RealAlgebraic
from exactinv_check.bernstein import prove_completely_monotone
from exactinv_check.failure import CheckFailure

ISSUE_EXAMPLES = {
    "(1 - z)/(1 - 2z)^4": ([1, -1], [1, -8, 24, -32, 16]),
    "(1 + z^2)/(1 - 4z/5)^4": ([1, 0, 1], [1, F(-16, 5), F(96, 25), F(-256, 125), F(256, 625)]),
}


def pmul(p, q):
    out = [F(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        for j, b in enumerate(q):
            out[i + j] += a * b
    return out


def padd(p, q):
    n = max(len(p), len(q))
    return [(p[i] if i < len(p) else F(0)) + (q[i] if i < len(q) else F(0)) for i in range(n)]


def ppow(p, k):
    out = [F(1)]
    for _ in range(k):
        out = pmul(out, p)
    return out


def _short(value, side):
    lo, hi = (value.lower, value.upper) if isinstance(value, RealAlgebraic) else (value, value)
    grid = 10 ** 7
    return F(int(lo * grid) - 50, grid) if side < 0 else F(int(hi * grid) + 51, grid)


def assert_against_reference(method, r):
    """The decided radius agrees with the slow exact reference, and the kernel re-proves the certificate."""
    num, den = method.numerator, method.denominator
    J = max(120, (r.binding or 0) + 2, (r.witness_j or 0) + 2)
    if r.value == ei.INF:
        for kappa in (F(0), F(1, 3), F(1), F(7), F(40)):
            assert admissible(num, den, kappa, J), kappa
    elif r.witness_j is not None:
        assert coefficients_at(num, den, F(0), r.witness_j + 1)[-1] < 0
    else:
        below, above = _short(r.value, -1), _short(r.value, +1)
        if below > 0:
            assert admissible(num, den, below, J)
        assert not admissible(num, den, above, J)
    report = ei.check(r.certificate)
    # the kernel proves it, or refuses (soundly) a certificate over its work budget (issue 22, item 2: budgets)
    assert report.ok or "work budget" in str(report), str(report)


# ----------------------------------------------------------------- the issue's examples
def test_closed_form_of_the_issue_matches_the_reference():
    """c_j(k) of (1 - z)/(1 - 2z)^4 is s^-4 (2/s)^(j-1) [(1+k)(2/s) C(j+3,3) - C(j+2,3)], s = 1 + 2k, j >= 1."""
    num, den = ISSUE_EXAMPLES["(1 - z)/(1 - 2z)^4"]
    for k in (F(0), F(1, 3), F(2), F(11, 2)):
        s = 1 + 2 * k
        c = coefficients_at(num, den, k, 40)
        for j in range(1, 40):
            closed = s ** -4 * (2 / s) ** (j - 1) * ((1 + k) * (2 / s) * comb(j + 3, 3) - comb(j + 2, 3))
            assert c[j] == closed > 0


@pytest.mark.parametrize("name", sorted(ISSUE_EXAMPLES))
def test_issue_examples_have_infinite_radius(name):
    num, den = ISSUE_EXAMPLES[name]
    m = M.rational(num, den, name=name)
    r = ei.absolute_monotonicity_radius(m)
    assert r.value == ei.INF and r.reason == "bernstein" and r.attained
    assert_against_reference(m, r)


def test_kernel_proves_the_single_pole_examples_by_sturm():
    for num, den in ISSUE_EXAMPLES.values():
        assert "Sturm" in prove_completely_monotone([F(c) for c in num], [F(c) for c in den])


def test_complex_pair_beyond_p_star_is_infinite():
    """1/(1 - z + z^2/4 - z^3/40): the complex pair has Re z > p*, no tail index is uniform in kappa (issue 14's
    documented Undecided case); Bernstein decides rho = oo."""
    m = M.rational([1], [1, -1, "1/4", "-1/40"])
    r = ei.absolute_monotonicity_radius(m)
    assert r.value == ei.INF and r.reason == "bernstein"
    assert_against_reference(m, r)


# ----------------------------------------------------------------- repeated real poles, any numerator
@st.composite
def repeated_pole(draw):
    mu = draw(st.integers(2, 6))
    p = draw(st.fractions(min_value=F(1, 4), max_value=3, max_denominator=6))
    den = ppow([F(1), -1 / p], mu)
    size = draw(st.integers(0, mu))
    coeff = st.fractions(min_value=-3, max_value=3, max_denominator=4)
    num = [F(1)] + draw(st.lists(coeff, min_size=size, max_size=size))
    while len(num) > 1 and num[-1] == 0:
        num.pop()
    return num, den


@settings(deadline=None, max_examples=25, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(repeated_pole())
def test_repeated_real_pole_is_decided_and_agrees_with_the_reference(case):
    num, den = case
    try:
        m = M.rational(num, den, name="repeated")
    except ei.ExactinvError:  # a common factor left a polynomial, or r(0) != 1
        return
    if m.is_polynomial:
        return
    r = ei.absolute_monotonicity_radius(m)  # never Undecided
    assert_against_reference(m, r)


# ----------------------------------------------------------------- rho = oo built on the Laplace side
@st.composite
def completely_monotone(draw):
    """r(-x) = c + beta/(x + p) + beta2/(x + p)^2 + (gamma (x + a) + delta b)/((x + a)^2 + b^2), the Laplace
    transform of f(t) = e^(-pt)(beta + beta2 t) + e^(-at)(gamma cos bt + delta sin bt) >= 0, since a > p and
    beta > |gamma| + |delta|; divided by r(0) > 0 (complete monotonicity is kept).  So rho = oo."""
    frac = st.fractions(min_value=0, max_value=3, max_denominator=6)
    p = draw(st.fractions(min_value=F(1, 4), max_value=3, max_denominator=4))
    a = p + draw(st.fractions(min_value=F(1, 8), max_value=3, max_denominator=8))
    b = draw(st.fractions(min_value=F(1, 4), max_value=4, max_denominator=4))
    gamma, delta = draw(frac) - F(3, 2), draw(frac) - F(3, 2)
    beta = abs(gamma) + abs(delta) + draw(st.fractions(min_value=F(1, 8), max_value=2, max_denominator=8))
    beta2, c = draw(frac), draw(frac)
    # in z = -x: beta/(p - z), beta2/(p - z)^2, (gamma (a - z) + delta b)/((a - z)^2 + b^2)
    lin, quad = [p, F(-1)], [a * a + b * b, -2 * a, F(1)]
    den = pmul(pmul(lin, lin), quad)
    num = padd(padd(pmul([c], den), pmul([beta], pmul(lin, quad))), pmul([beta2], quad))
    num = padd(num, pmul([gamma * a + delta * b, -gamma], pmul(lin, lin)))
    scale = den[0]
    num, den = [x / scale for x in num], [x / scale for x in den]
    r0 = num[0]
    return [x / r0 for x in num], den


@settings(deadline=None, max_examples=30, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(completely_monotone())
def test_completely_monotone_by_construction_has_infinite_radius(case):
    num, den = case
    m = M.rational(num, den, name="bernstein")
    r = ei.absolute_monotonicity_radius(m)
    assert r.value == ei.INF and r.attained
    assert_against_reference(m, r)


@st.composite
def not_completely_monotone(draw):
    """The same with beta < |gamma| (f(0) = beta + gamma < 0 when gamma < -beta): f < 0 near 0, so rho < oo."""
    p = draw(st.fractions(min_value=F(1, 2), max_value=2, max_denominator=4))
    a = p + draw(st.fractions(min_value=F(1, 4), max_value=2, max_denominator=4))
    b = draw(st.fractions(min_value=F(1, 4), max_value=3, max_denominator=4))
    beta = draw(st.fractions(min_value=F(1, 4), max_value=2, max_denominator=4))
    gamma = -beta - draw(st.fractions(min_value=F(1, 8), max_value=1, max_denominator=8))
    lin, quad = [p, F(-1)], [a * a + b * b, -2 * a, F(1)]
    den = pmul(lin, quad)
    num = padd(pmul([beta], quad), pmul([gamma * a, -gamma], lin))
    c = F(1, 2)
    num = padd(num, pmul([c], den))
    scale = den[0]
    num, den = [x / scale for x in num], [x / scale for x in den]
    return [x / num[0] for x in num], den


@settings(deadline=None, max_examples=15, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(not_completely_monotone())
def test_not_completely_monotone_has_finite_radius(case):
    num, den = case
    if num[0] <= 0:
        return
    m = M.rational(num, den, name="finite")
    try:
        r = ei.absolute_monotonicity_radius(m)
    except ei.Undecided as e:  # only an honest reason, never "not implemented"
        assert "not implemented" not in str(e)
        return
    assert r.value != ei.INF
    assert_against_reference(m, r)


# ----------------------------------------------------------------- the kernel rejects false bernstein claims
def _forged(num, den):
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"method": {"name": "rational", "numerator": [str(F(c)) for c in num],
                                   "denominator": [str(F(c)) for c in den]}},
            "claims": [{"type": "absolute_monotonicity_radius", "value": "oo", "reason": "bernstein",
                        "attained": True}]}


@pytest.mark.parametrize("num, den", [
    ([1, -3], [1, -8, 24, -32, 16]),          # one pole, P changes sign
    ([1, F(1, 2)], [1, F(-1, 2)]),            # the trapezoid: c = -1 < 0
    ([1, -1], [1, -1, F(1, 4), F(-1, 40)]),   # the principal part at p* has the wrong sign (rho = 0)
    ([1], [1, F(-2, 3), F(-1, 4)]),           # a negative pole
    ([1], [1, 0, 1, -1]),                     # complex poles with Re z < p*
    ([1, 1, 1], [1, -1]),                     # deg g > deg h
])
def test_kernel_rejects_a_false_bernstein_claim(num, den):
    rho = None
    try:
        rho = ei.absolute_monotonicity_radius(M.rational(num, den)).value
    except ei.Undecided:
        pass
    assert rho != ei.INF
    assert not ei.check(_forged(num, den)).ok
    with pytest.raises(CheckFailure):
        prove_completely_monotone([F(c) for c in num], [F(c) for c in den])


# ----------------------------------------------------------------- simple rational poles: f may touch 0
def test_density_touching_zero_with_rational_exponents_is_decided():
    """r(-x) = 3 (1/(x+1) - 4/(x+2) + 4/(x+3)): f(t) = 3 e^-t (1 - 2 e^-t)^2 >= 0 vanishes at t = ln 2 (no interval
    method can see f >= 0 there); with u = e^-t, F(u) = 3 u (1 - 2u)^2 >= 0 on (0, 1) decides rho = oo."""
    num, den = [F(1), F(-1, 2), F(1, 2)], [F(1), F(-11, 6), F(1), F(-1, 6)]
    assert pmul([F(1), F(-1)], pmul([F(1), F(-1, 2)], [F(1), F(-1, 3)])) == den
    m = M.rational(num, den)
    r = ei.absolute_monotonicity_radius(m)
    assert r.value == ei.INF and r.reason == "bernstein"
    assert "rational poles" in prove_completely_monotone(num, den)
    assert_against_reference(m, r)


def test_density_slightly_negative_with_rational_exponents_is_finite():
    """f(t) = e^-t (1 - 2 e^-t)^2 - e^-2t/2 dips below 0 around t = ln 2: rho < oo."""
    _num3, den = pmul([F(1, 2)], pmul([F(2), F(-1)], [F(3), F(-1)])), pmul(pmul([F(1), F(-1)], [F(2), F(-1)]), [F(3), F(-1)])
    # 1/(x+1) - (4 + 1/2)/(x+2) + 4/(x+3) at z = -x, over the common denominator (1-z)(2-z)(3-z)
    num = padd(padd(pmul([F(1)], pmul([F(2), F(-1)], [F(3), F(-1)])),
                    pmul([F(-9, 2)], pmul([F(1), F(-1)], [F(3), F(-1)]))),
               pmul([F(4)], pmul([F(1), F(-1)], [F(2), F(-1)])))
    num = [x / num[0] for x in num]
    den = [x / den[0] for x in den]
    m = M.rational(num, den)
    r = ei.absolute_monotonicity_radius(m)
    assert r.value != ei.INF
    assert_against_reference(m, r)
    with pytest.raises(CheckFailure):
        prove_completely_monotone(num, den)


# ----------------------------------------------------------------- an exactly balanced tie
@pytest.mark.parametrize("num, den, kappa", [
    ([1], [1, F(-2, 3), F(-1, 4)], F(4, 3)),          # poles (-4 +- 2 sqrt 13)/3: b_a = -b_*
    ([1], [1, F(-1, 2), F(-1, 2)], F(1, 2)),          # poles 1 and -2: tie at kappa = 1/2
    ([1, F(3, 4)], [1, F(-2, 3), F(-1, 4)], F(4, 3)),  # g = 0 at the poles' midpoint -4/3: equal residues (G0 = 0)
])
def test_balanced_tie_is_decided_by_the_closed_form(num, den, kappa):
    m = M.rational(num, den)
    try:
        r = ei.absolute_monotonicity_radius(m)
    except ei.Undecided:
        pytest.fail("an exactly balanced tie must be decided")
    assert r.value <= kappa
    if r.reason == "balanced-tie":
        assert r.value == kappa and r.attained
        # at kappa*, the odd-index coefficients vanish (two poles, one balanced pair) and the even ones are > 0
        c = coefficients_at(num, den, kappa, 40)
        assert all(x >= 0 for x in c) and any(x == 0 for x in c[2:])
        assert admissible(num, den, kappa - F(1, 10 ** 6), 120)
    report = ei.check(r.certificate)
    assert report.ok, str(report)


def test_kernel_rejects_a_wrong_balanced_tie():
    def cert(num, den, value):
        return {"format": "exactinv-certificate", "version": 2,
                "problem": {"method": {"name": "rational", "numerator": [str(F(c)) for c in num],
                                       "denominator": [str(F(c)) for c in den]}},
                "claims": [{"type": "absolute_monotonicity_radius", "value": value, "reason": "balanced-tie",
                            "attained": True}]}
    assert ei.check(cert([1], [1, F(-2, 3), F(-1, 4)], "4/3")).ok
    assert not ei.check(cert([1], [1, F(-2, 3), F(-1, 4)], "5/4")).ok   # not the tie
    assert not ei.check(cert([1, F(1, 5)], [1, F(-2, 3), F(-1, 4)], "4/3")).ok  # residues do not balance
    assert not ei.check(cert([1], [1, F(-1, 2), F(1, 16)], "2")).ok   # a double pole, no tie


@settings(deadline=None, max_examples=80)
@given(st.lists(st.fractions(min_value=-5, max_value=5, max_denominator=4), min_size=0, max_size=3),
       st.lists(st.fractions(min_value=-5, max_value=5, max_denominator=4), min_size=1, max_size=3),
       st.fractions(min_value=0, max_value=20, max_denominator=7), st.integers(0, 14))
def test_witness_sign_in_integers_matches_the_reference(g_tail, h_tail, kappa, j):
    from exactinv.monotonicity.bernstein import coefficient_at
    g, h = [F(1)] + g_tail, [F(1)] + h_tail
    c = coefficients_at(g, h, kappa, j + 1)
    if c is None:
        return
    assert coefficient_at(g, h, kappa, j) == (c[j] > 0) - (c[j] < 0)
