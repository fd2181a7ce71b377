from fractions import Fraction
from math import comb

import flint
import pytest
import sympy
from hypothesis import assume, given
from hypothesis import strategies as st

import exactinv as ei
from exactinv.core.flintq import fmpq_matrix
from exactinv_check import check


@st.composite
def invariant_problems(draw, max_n=3):
    """Row-diagonally-dominant A on a box, seen in random coordinates x = T y
    (so P is a general parallelotope): always invariant."""
    n = draw(st.integers(1, max_n))
    A = [[Fraction(draw(st.integers(-4, 4)), draw(st.integers(1, 3))) for _ in range(n)] for _ in range(n)]
    for i in range(n):
        A[i][i] = -sum(abs(A[i][j]) for j in range(n) if j != i) - Fraction(draw(st.integers(0, 4)), draw(st.integers(1, 3)))
    T = [[draw(st.integers(-2, 2)) for _ in range(n)] for _ in range(n)]
    Tq = fmpq_matrix([[Fraction(v) for v in row] for row in T])
    assume(Tq.det() != 0)
    Aq = Tq.inv() * fmpq_matrix(A) * Tq
    box = ei.Polyhedron.box([-1] * n, [1] * n)
    GT = box.G_flint * Tq
    S = ei.LinearSystem([[Aq[i, j] for j in range(n)] for i in range(n)])
    P = ei.Polyhedron([[GT[i, j] for j in range(n)] for i in range(box.m)], box.b)
    return S, P


@given(invariant_problems(), st.integers(1, 8))
def test_taylor_threshold_is_one_over_gamma(problem, p):
    S, P = problem
    g = ei.optimal_gamma(S, P).value
    t = ei.steplength_threshold(S, P, ei.methods.taylor(p))
    assert t.value == (ei.INF if g <= 0 else 1 / g)
    assert t.attained


def _rho_by_coefficients(sigmas):
    """Independent: rho = min_j sup{k : c_j >= 0 on [0, k]}, c_j(k) = sum_m s_m C(m,j) (-k)^(m-j), via sympy."""
    kappa = sympy.Symbol("kappa")
    rho = sympy.oo
    for j in range(len(sigmas)):
        c = sympy.Poly(sum(sympy.Rational(sigmas[m]) * comb(m, j) * (-kappa) ** (m - j) for m in range(j, len(sigmas))), kappa)
        if c.is_zero:
            continue
        lowest = next(co for co in reversed(c.all_coeffs()) if co != 0)
        if lowest < 0:
            return sympy.Integer(0)
        for root, mult in sorted(_real_roots(c), key=lambda rm: rm[0]):
            if root > 0 and mult % 2 == 1:
                rho = sympy.Min(rho, root)
                break
    return rho


def _real_roots(c):
    counts = {}
    for r in c.real_roots():
        counts[r] = counts.get(r, 0) + 1
    return list(counts.items())


@given(invariant_problems(max_n=2),
       st.lists(st.fractions(min_value=0, max_value=2, max_denominator=4), min_size=1, max_size=4))
def test_nonnegative_sigma_threshold_is_rho_over_gamma(problem, tail):
    S, P = problem
    sigmas = [Fraction(1)] + tail
    g = ei.optimal_gamma(S, P).value
    assume(g > 0)
    t = ei.steplength_threshold(S, P, ei.methods.polynomial(sigmas))
    rho = _rho_by_coefficients(sigmas)
    expected = rho / sympy.Rational(g.numerator, g.denominator)
    if expected == sympy.oo:
        assert t.value == ei.INF
    else:
        lo = sympy.Rational(t.lower.numerator, t.lower.denominator)
        hi = sympy.Rational(t.upper.numerator, t.upper.denominator)
        assert (lo <= expected) and (expected <= hi)
        if isinstance(t.value, Fraction):
            assert expected == sympy.Rational(t.value.numerator, t.value.denominator)


@given(invariant_problems(max_n=2), st.sampled_from(["taylor", "heun", "ssprk33", "rk4", "ssprk31", "sigma"]))
def test_discrete_check_succeeds_at_lower(problem, name):
    S, P = problem
    method = {
        "taylor": ei.methods.taylor(3), "heun": ei.methods.heun(), "ssprk33": ei.methods.ssprk33(),
        "rk4": ei.methods.rk4(), "ssprk31": ei.methods.ssprk_s1(3), "sigma": ei.methods.polynomial([1, 1, "1/3", "1/30"]),
    }[name]
    t = ei.steplength_threshold(S, P, method)
    dt = t.lower if t.lower != ei.INF else Fraction(1000)
    result = ei.discrete_invariance(S, P, method, dt)
    assert result.holds
    # and H~ = sum sigma_k (dt H)^k is a certificate (paper, Theorem 3.4)
    g = t.gamma
    if g.value != -ei.INF:
        H = fmpq_matrix(g.H) * flint.fmpq(dt.numerator, dt.denominator)
        Ht = flint.fmpq_mat(P.m, P.m)
        power = flint.fmpq_mat(P.m, P.m, [int(i == j) for i in range(P.m) for j in range(P.m)])
        for s in method.sigmas:
            Ht += power * flint.fmpq(s.numerator, s.denominator)
            power = power * H
        assert all(v >= 0 for v in Ht.entries())
        assert Ht * P.G_flint == P.G_flint * fmpq_matrix(method.matrix(S, dt))


def test_box_example_table_and_certificate():
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    t = ei.steplength_threshold(S, P, ei.methods.taylor(3))
    assert t.value == 1 and t.binding == 2 and t.gamma.value == 1
    tau0 = t.table[0].tau  # f_0 = 1 - t + t^2/2 - t^3/6: one real root
    assert isinstance(tau0, ei.RealAlgebraic) and Fraction(159, 100) < tau0 < Fraction(160, 100)
    assert [r.tau for r in t.table[1::2]] == [ei.INF, ei.INF]  # f_1, f_3
    assert check(t.certificate).ok
    assert t.lower == t.upper == 1


def test_f_i_symbolic_partition_of_unity():
    """Paper eq. (21): sum_i gamma^i f_i(dt) = 1."""
    for method in (ei.methods.taylor(5), ei.methods.polynomial([1, 2, "-1/3", 4])):
        fs = ei.steplength_threshold(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), method).f_symbolic()
        dt, gamma = sympy.symbols("Delta_t gamma", positive=True)
        assert sympy.expand(sum(gamma**i * f for i, f in enumerate(fs))) == 1


def test_erratum_e5_zero_sigma():
    """E5: r(z) = 1 + z^2.  f_1 = -2 gamma dt^2 has no positive zero, so the paper's
    "first positive zero" gives tau = oo; but A_d = 1 + dt^2 > 1 leaves [-1, 1] for every dt > 0."""
    S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
    method = ei.methods.polynomial([1, 0, 1])
    t = ei.steplength_threshold(S, P, method)
    assert t.value == 0 and t.table[1].tau == 0
    assert ei.first_sign_change(t.table[1].f) == ei.INF  # the paper's tau_1
    bad = ei.discrete_invariance(S, P, method, Fraction(1, 1000))
    assert not bad.holds and bad.witness.value == 1 + Fraction(1, 10**6)


def test_erratum_e6_gamma_nonpositive_with_negative_sigma():
    """E6: Theorem 3.13 (gamma* <= 0 => tau = oo) fails for r(z) = 1 + z - z^2 on the orthant with A = [[0,1],[1,0]]."""
    S = ei.LinearSystem([[0, 1], [1, 0]])
    P = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
    method = ei.methods.polynomial([1, 1, -1])
    assert ei.optimal_gamma(S, P).value == 0
    t = ei.steplength_threshold(S, P, method)
    assert t.value == 0
    bad = ei.discrete_invariance(S, P, method, 2)  # A_d = [[-3, 2], [2, -3]]
    assert not bad.holds
    assert method.matrix(S, 2) == ((-3, 2), (2, -3))
    assert check(t.certificate).ok
    ok = ei.steplength_threshold(S, P, ei.methods.taylor(3))
    assert ok.value == ei.INF


def test_not_invariant_raises_with_witness():
    S, P = ei.LinearSystem([[1]]), ei.Polyhedron.box([-1], [1])
    with pytest.raises(ei.NotInvariant) as info:
        ei.steplength_threshold(S, P, ei.methods.taylor(2))
    assert info.value.witness.x in ((1,), (-1,))


def test_bad_method_argument():
    with pytest.raises(ei.InvalidInput, match="method"):
        ei.steplength_threshold(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), "taylor")
