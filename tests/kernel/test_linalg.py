"""The kernel's fraction-free exact linear algebra and its work budgets
(exactinv_check/linalg.py, ellipsoids.py, polys.py, rationals.py): the new
integer routines agree with independent exact computations, a computation over
a budget is a clean rejection naming the budget, and r = 1 is decided.
"""


import copy
import json
import random
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.certificates import certificate
from exactinv_check import check
from exactinv_check.ellipsoids import condition_polynomials, psd
from exactinv_check.linalg import characteristic_polynomial, integer_characteristic_polynomial, integer_determinant
from exactinv_check.rationals import describe

sp = pytest.importorskip("sympy")


small = st.integers(-6, 6)


def _square(draw, n):
    return [[draw(small) for _ in range(n)] for _ in range(n)]


@st.composite
def integer_matrices(draw, top=6):
    return _square(draw, draw(st.integers(0, top)))


@st.composite
def symmetric_rational(draw):
    n = draw(st.integers(1, 5))
    B = [[Fraction(draw(small), draw(st.integers(1, 3))) for _ in range(n)] for _ in range(draw(st.integers(0, n + 1)))]
    shift = Fraction(draw(st.integers(-3, 3)), draw(st.integers(1, 4)))
    # B^T B (PSD, often singular) shifted by a multiple of I: PD, PSD or indefinite
    return [[sum((b[i] * b[j] for b in B), Fraction(0)) + (shift if i == j else 0) for j in range(n)] for i in range(n)]


def _ellipsoid_cert(A, Q, claims, method=None):
    problem = {"A": A, "Q": Q}
    if method is not None:
        problem["method"] = {"numerator": method[0], "denominator": method[1]}
    return {"format": "exactinv-certificate", "version": 2, "problem": problem, "claims": claims}


def _identity(n):
    return [["1" if i == j else "0" for j in range(n)] for i in range(n)]


def _dense(n, seed, diagonal):
    rng = random.Random(seed)
    return [[str(rng.randint(-3, 3) + (diagonal if i == j else 0)) for j in range(n)] for i in range(n)]


ROT = ei.LinearSystem([[-1, -2], [2, -1]])


DISC = ei.Ellipsoid([[1, 0], [0, 1]])


ONE = ei.methods.polynomial([1])


# ------------------------------------------------------------------ soundness

@given(integer_matrices())
@settings(max_examples=60, deadline=None)
def test_berkowitz_equals_the_hessenberg_characteristic_polynomial_and_sympy(M):
    p = integer_characteristic_polynomial(M)
    assert [Fraction(c) for c in p] == characteristic_polynomial([[Fraction(x) for x in r] for r in M])
    x = sp.Symbol("x")
    expected = sp.Matrix(M).charpoly(x).all_coeffs()[::-1] if M else [1]
    assert p == [int(c) for c in expected]


@given(integer_matrices())
@settings(max_examples=60, deadline=None)
def test_bareiss_determinant_equals_sympy(M):
    assert integer_determinant(M) == (int(sp.Matrix(M).det()) if M else 1)


@given(symmetric_rational())
@settings(max_examples=80, deadline=None)
def test_fraction_free_psd_agrees_with_sympy(M):
    S = sp.Matrix([[sp.Rational(x.numerator, x.denominator) for x in r] for r in M])
    assert psd(M) == (bool(S.is_positive_semidefinite), bool(S.is_positive_definite))


def test_describe_bounds_every_number_in_a_message():
    assert describe(Fraction(-3, 4)) == "-3/4"
    assert describe(10 ** 6000) == "a 6001-digit integer"
    assert describe(Fraction(-1, 10 ** 100)) == "a 101-digit negative rational"
    assert describe("oo") == "oo"


def test_the_degree_127_isolation_is_now_afforded_and_the_false_claim_rejected():
    """The red team's H3: a degree-64 method with 100-digit coefficients, c_1 of degree 127 with ~670-bit
    coefficients (127^4 670^2 ~ 1.2e14).  The Descartes gate on degree^4 bits^2 refused it; priced by its nodes
    (issue 22, harden-budget) it is isolated within the certificate's budget (a few seconds), and the claim -- an
    empty valid set, though 0 is always valid -- is rejected for what it is."""
    report = check(_ellipsoid_cert([["-1"]], [["1"]], [{"type": "ellipsoid_valid_steplengths", "intervals": []}],
                                   (["1", "1"] + [str((-1) ** k * (10 ** 100 + 7 * k)) for k in range(63)], ["1"])))
    assert not report.ok
    assert "the valid set has 1 intervals, the claim 0" in str(report) or "over the" in str(report), str(report)[:500]


def test_an_ellipsoid_problem_above_the_degree_bound_is_rejected():
    report = check(_ellipsoid_cert(_identity(201), _identity(201),
                                   [{"type": "ellipsoid_continuous_invariance", "holds": True}]))
    assert not report.ok and "dimension at most 200" in str(report), str(report)


def test_the_constant_method_has_every_step_valid_in_the_engine():
    valid, tau = ei.valid_steplengths(ROT, DISC, ONE), ei.largest_threshold(ROT, DISC, ONE)
    assert str(valid).startswith("EllipsoidValidSteplengths([0, oo)")
    assert str(tau.value) == "oo" and tau.attained
    for h in (Fraction(1, 3), Fraction(10**6)):  # A_d = r(hA) = I: Q - I Q I = 0 >= 0
        assert ei.discrete_invariance(ROT, DISC, ONE, h).holds


def test_the_constant_method_certificate_verifies_and_forgeries_fail():
    cert = json.loads(json.dumps(certificate(ROT, DISC, ONE, [ei.valid_steplengths(ROT, DISC, ONE),
                                                               ei.largest_threshold(ROT, DISC, ONE)])))
    assert check(copy.deepcopy(cert)).ok, check(cert)
    forged = copy.deepcopy(cert)
    forged["claims"][0]["intervals"][0]["hi"] = "1"
    forged["claims"][0]["intervals"][0]["hi_closed"] = True
    forged["claims"][1]["value"], forged["claims"][1]["attained"] = "1", True
    report = check(forged)
    assert not report.ok and str(report).count("[REJECTED]") == 2, str(report)


def test_the_kernel_builds_no_condition_for_r_one():
    D, conditions = condition_polynomials([[Fraction(-1)]], [[Fraction(1)]], [Fraction(1)], [Fraction(1)])
    assert D == [1] and conditions == [[]]


# ------------------------------------------------------------------ resource

@pytest.mark.parametrize("cert, what", [
    # a dense 200 x 200 Q: its elimination is priced before it runs
    (_ellipsoid_cert(_identity(200), [[str(10 * 200 if i == j else (i * j) % 19 - 9) for j in range(200)]
                                      for i in range(200)], [{"type": "ellipsoid_continuous_invariance", "holds": True}]),
     "exact elimination of a 200 x 200 matrix"),
    # forward Euler at n = 60: 61 characteristic polynomials of 60 x 60 matrices
    (_ellipsoid_cert(_dense(60, 4, -180), _identity(60), [{"type": "ellipsoid_forward_euler_threshold", "value": "1"}]),
     "characteristic polynomial of a 60 x 60 matrix at 61 points"),
])
def test_work_over_a_budget_is_a_clean_rejection_naming_it(cert, what):
    report = check(cert)
    assert not report.ok
    text = str(report)
    assert "over the kernel's work budget" in text and what in text, text


def test_invariance_of_large_problems_is_priced_before_the_products():
    # Q = I, A dense 200 x 200: A^T Q + Q A costs 8 10^6 products, its elimination is over the budget
    report = check(_ellipsoid_cert(_dense(200, 1, -600), _identity(200),
                                   [{"type": "ellipsoid_continuous_invariance", "holds": True}]))
    assert not report.ok and "over the kernel's work budget" in str(report), str(report)
    # r(dt A) in Fractions for a dense 80 x 80 A is priced before it is computed
    report = check(_ellipsoid_cert(_dense(80, 3, -240), _identity(80), [
        {"type": "ellipsoid_discrete_invariance", "holds": True, "dt": "1/560"}], (["1", "1", "1/2"], ["1"])))
    assert not report.ok and "r(dt A) for a 80 x 80 matrix" in str(report), str(report)


def test_invariance_of_a_mid_size_problem_is_decided_exactly():
    # A = S - I with S skew (n = 30): A^T + A = -2I, so E = unit ball is invariant for x' = Ax;
    # A = S + e_1 e_1^T: v = e_1 gives v^T (A^T + A) v = 2 > 0
    n = 30
    S = [[(i - j) % 5 - 2 if i < j else -((j - i) % 5 - 2) if i > j else 0 for j in range(n)] for i in range(n)]
    assert all(S[i][j] == -S[j][i] for i in range(n) for j in range(n))
    minus = [[str(S[i][j] - (i == j)) for j in range(n)] for i in range(n)]
    plus = [[str(S[i][j] + (i == j == 0)) for j in range(n)] for i in range(n)]
    holds = {"type": "ellipsoid_continuous_invariance", "holds": True}
    assert check(_ellipsoid_cert(minus, _identity(n), [holds])).ok
    assert not check(_ellipsoid_cert(plus, _identity(n), [holds])).ok
    witness = {"type": "ellipsoid_continuous_invariance", "holds": False, "witness": {"v": ["1"] + ["0"] * (n - 1),
                                                                                          "value": "2"}}
    assert check(_ellipsoid_cert(plus, _identity(n), [witness])).ok
    # the discrete step of the contraction: A_d = I + A/4 with A = -I + S: |A_d|_2 may exceed 1,
    # decided against sympy
    method, dt = (["1", "1"], ["1"]), Fraction(1, 4)
    Ad = sp.eye(n) + sp.Rational(1, 4) * sp.Matrix([[S[i][j] - (i == j) for j in range(n)] for i in range(n)])
    truth = bool((sp.eye(n) - Ad.T * Ad).is_positive_semidefinite)
    claim = {"type": "ellipsoid_discrete_invariance", "holds": True, "dt": str(dt)}
    assert check(_ellipsoid_cert(minus, _identity(n), [claim], method)).ok == truth


def test_a_long_true_witness_is_reported_by_its_size():
    # A = [[1]], Q = [[1]]: v^T (A^T Q + Q A) v = 2 v^2 > 0 for v = 10^3000
    report = check(_ellipsoid_cert([["1"]], [["1"]], [{"type": "ellipsoid_continuous_invariance", "holds": False,
                                                      "witness": {"v": ["1" + "0" * 3000]}}]))
    assert report.ok and "a 6001-digit integer" in str(report), str(report)
