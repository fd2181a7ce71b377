from fractions import Fraction

import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

import exactinv as ei
from exactinv.core.roots import first_sign_change
from exactinv.thresholds.bisection import paper_bisection, paper_bisection_float, paper_bound


def test_erratum_e3_printed_algorithm_returns_infinity_for_1_minus_t():
    """E3: f(t) = 1 - t has its first positive zero at 1, the printed algorithm says infinity."""
    assert paper_bound([1, -1]) == 0  # t* = alpha*/alpha_q + 1 = 1/(-1) + 1
    assert paper_bisection([1, -1]).tau == ei.INF
    assert paper_bisection_float([1, -1]).tau == float("inf")
    assert first_sign_change([1, -1]) == 1


def test_erratum_e3_repaired_bound():
    assert paper_bound([1, -1], repaired=True) == 2
    res = paper_bisection([1, -1], repaired=True)
    assert res.t_l < 1 < res.t_r and res.t_r - res.t_l < Fraction(1, 2**29)
    assert abs(paper_bisection_float([1, -1], repaired=True).tau - 1) < 1e-8


def test_taylor_f_p_minus_1_is_1_minus_t_up_to_scaling():
    """f_{p-1} of a Taylor method at gamma = 1 is dt^(p-1)/(p-1)! (1 - dt): the E3 trigger."""
    from exactinv.thresholds.polynomial import f_i

    for p in range(2, 6):
        f = f_i(ei.methods.taylor(p).sigmas, Fraction(1), p - 1)
        scale = f[p - 1]
        assert [c / scale for c in f[p - 1:]] == [1, -1]


@given(st.lists(st.fractions(min_value=-6, max_value=6, max_denominator=5), min_size=1, max_size=5))
def test_exact_bisection_brackets_first_sign_change(coeffs):
    """Where the repaired algorithm applies (alpha_q != 0, f(0) = 1), its final
    bracket contains the first *distinct* positive root; on polynomials without
    tangent roots before it, that is the first sign change."""
    alphas = [Fraction(1)] + coeffs
    assume(alphas[-1] != 0)
    from exactinv.core.roots import real_roots

    roots = [(r, m) for r, m in real_roots(alphas) if r > 0]
    assume(not roots or roots[0][1] % 2 == 1)
    res = paper_bisection(alphas, epsilon=Fraction(1, 2**20), repaired=True)
    truth = first_sign_change(alphas)
    if truth == ei.INF:
        assert res.tau == ei.INF
    elif res.terminated_by.startswith("step 5"):
        assert res.t_l <= truth <= res.t_r
    else:
        assert res.tau == truth


def test_float_version_disagrees_with_exact_on_a_nearly_double_root():
    """(t - 1)^2 - 1e-20: two roots 1 +- 1e-10; the float Sturm count cannot see them."""
    eps = Fraction(1, 10**20)
    alphas = [Fraction(1) - eps, Fraction(-2), Fraction(1)]
    scale = alphas[0]
    alphas = [c / scale for c in alphas]
    exact = paper_bisection(alphas, epsilon=Fraction(1, 2**40), repaired=True)
    assert exact.t_l < 1 and first_sign_change(alphas) < 1
    floated = paper_bisection_float(alphas, epsilon=2.0**-40, repaired=True)
    assert floated.tau != exact.tau


def test_bad_input():
    with pytest.raises(ei.InvalidInput, match="f\\(0\\) = 1"):
        paper_bisection([2, -1])
    with pytest.raises(ei.InvalidInput, match="degree"):
        paper_bisection([1, 0])
