"""The kernel's box route (exactinv_check/routes/boxes.py): genuine box certificates verify, and a
forged or unprovable one -- wrong intervals, a box claimed for a non-box, a missing bound,
tampered numbers, an input too large to rebuild -- is rejected with a reason."""


import random
from fractions import Fraction
from math import factorial

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.certificates import certificate
from exactinv_check import check
from exactinv_check.conditions import method_matrices, method_matrix_at
from exactinv_check.failure import CheckFailure
from exactinv_check.linalg import integer_solve
from exactinv_check.rationals import determinant, solve
from exactinv_check.routes.boxes import prove_box, vertex_of

M = ei.methods


F = Fraction


def _cert(S, P, m):
    return certificate(S, P, m, [ei.largest_threshold(S, P, m), ei.valid_steplengths(S, P, m)])


def _rejected(cert, reason=""):
    report = check(cert)
    assert not report.ok, f"accepted:\n{report}"
    assert reason.lower() in str(report).lower(), str(report)


SHEAR = ei.LinearSystem([[-1, 1], [0, -1]])


SQUARE = ei.Polyhedron.box([-1, -1], [1, 1])


SPIN = ei.LinearSystem([[-1, "1/2", 0], ["-1/2", -1, "1/4"], [0, "-1/3", -2]])


OFFSET = ei.Polyhedron([[2, 0, 0], [0, 1, 0], [0, 0, 1], [-1, 0, 0], [0, -1, 0], [0, 0, -3], [1, 0, 0]],
                       [4, 1, 3, 1, "1/2", 3, 9])  # [-1, 2] x [-1/2, 1] x [-1, 3], the last row implied


def _genuine():
    cert = _cert(SPIN, OFFSET, M.taylor(4))
    assert check(cert).ok
    return cert


def _matrix_polynomial(coeffs, t, A):
    """sum_k coeffs[k] (tA)^k by Horner, in Fractions (3 x 3)."""
    out = [[F(0)] * 3 for _ in range(3)]
    for c in reversed(coeffs):
        out = [[sum(out[i][k] * t * A[k][j] for k in range(3)) + (c if i == j else 0) for j in range(3)] for i in range(3)]
    return out


# ------------------------------------------------------------------ soundness

def test_the_hand_example_verifies_and_names_the_box():
    cert = _cert(ei.LinearSystem([[-1]]), ei.Polyhedron.box([0], [2]), M.taylor(2))
    assert [c["box"] for c in cert["claims"]] == [{"lo": ["0"], "hi": ["2"]}] * 2
    report = check(cert)
    assert report.ok and "box P proved from G and b" in str(report)


@pytest.mark.parametrize("m", [M.taylor(1), M.taylor(4), M.taylor(8), M.backward_euler(), M.pade(2, 2),
                               M.theta("1/3"), M.trapezoid()], ids=lambda m: m.name)
@pytest.mark.parametrize("S, P", [(SHEAR, SQUARE), (SPIN, OFFSET)], ids=["shear", "offset"])
def test_genuine_box_certificates_verify(S, P, m):
    cert = _cert(S, P, m)
    assert "box" in cert["claims"][0] and "vertices" not in cert["claims"][1]
    assert check(cert).ok


@settings(max_examples=25, deadline=None)
@given(st.integers(1, 3), st.randoms(use_true_random=False), st.sampled_from([M.taylor(3), M.pade(1, 1)]))
def test_random_box_certificates_verify_and_equal_the_listed_route(n, rng, m):
    A = [[F(rng.randint(-4, 4), rng.randint(1, 3)) for _ in range(n)] for _ in range(n)]
    lo = [F(rng.randint(-3, 1), rng.randint(1, 2)) for _ in range(n)]
    S, P = ei.LinearSystem(A), ei.Polyhedron.box(lo, [x + F(rng.randint(1, 5), rng.randint(1, 2)) for x in lo])
    cert = _cert(S, P, m)
    assert check(cert).ok
    listed = certificate(S, P, m, [ei.valid_steplengths(S, P, m, box=False)])
    assert listed["claims"][0]["intervals"] == cert["claims"][1]["intervals"] and check(listed).ok


def test_prove_box_reads_the_tightest_bounds_and_the_vertex_order():
    G = [[F(x) for x in r] for r in ([2, 0], [0, 1], [-1, 0], [0, -3], [1, 0])]
    lo, hi, facets = prove_box(G, [F(4), F(1), F(1), F(3), F(5)])
    assert (lo, hi) == ([-1, -1], [2, 1]) and facets == [((0, 2), (2, 1)), ((1, 1), (3, 3))]
    P = ei.Polyhedron.box([0, -2, 1], [1, 3, 2])
    assert [tuple(vertex_of(i, [0, -2, 1], [1, 3, 2])) for i in range(8)] == list(P.vertices)


@pytest.mark.parametrize("G, b, reason", [
    ([[1, 1], [-1, 0], [0, -1]], [1, 0, 0], "nonzero entries"),
    ([[1, 0], [-1, 0], [0, 1]], [1, 1, 1], "bounded both ways"),
    ([[1], [-1]], [1, -1], "lo >= hi"),
])
def test_prove_box_rejects_what_is_not_a_box(G, b, reason):
    with pytest.raises(CheckFailure, match=reason):
        prove_box([[F(x) for x in r] for r in G], [F(x) for x in b])


def test_wrong_intervals_are_rejected():
    cert = _genuine()
    cert["claims"][1]["intervals"][0]["hi"] = "1/3"
    _rejected(cert, "ends at")
    cert = _genuine()
    cert["claims"][1]["intervals"][0]["hi_closed"] = False
    _rejected(cert, "hi_closed")


def test_a_tampered_box_record_is_rejected():
    cert = _genuine()
    cert["claims"][1]["box"]["hi"][0] = "3"
    _rejected(cert, "not the claimed one")
    cert = _genuine()
    cert["claims"][1]["box"]["lo"] = ["-1", "-1/2"]
    _rejected(cert, "expected 3 entries")
    cert = _genuine()
    cert["claims"][1]["box"]["center"] = ["0", "0", "0"]
    _rejected(cert, "keys lo, hi")


def test_box_and_generator_lists_do_not_mix():
    cert = _genuine()
    cert["claims"][1]["vertices"] = [["0", "0", "0"]]
    _rejected(cert, "either the box or the vertices")
    cert = _genuine()
    del cert["claims"][1]["box"]
    _rejected(cert, "either the box or the vertices")
    cert = _genuine()
    cert["claims"][1]["pruning"] = {"horizon": "1", "vertex": 0, "order": list(range(8))}
    _rejected(cert, "no pruning")


def test_a_box_claimed_for_a_non_box_is_rejected():
    cert = _genuine()
    cert["problem"]["G"][0] = ["2", "1", "0"]  # a slanted facet: P is no box
    _rejected(cert, "nonzero entries")


def test_a_box_with_a_missing_bound_is_rejected():
    cert = _genuine()
    del cert["problem"]["G"][4], cert["problem"]["b"][4]  # y >= -1/2 gone: y unbounded below
    _rejected(cert, "bounded both ways")


def test_a_box_whose_b_was_tampered_is_rejected():
    """x' = -x, forward Euler: on [0, 2] the valid set is [0, 1] (2 (1 - h) >= 0); on [-1, 2] it is [0, 3/2]."""
    cert = _cert(ei.LinearSystem([[-1]]), ei.Polyhedron.box([0], [2]), M.forward_euler())
    assert check(cert).ok and cert["claims"][1]["intervals"][0]["hi"] == "1"
    cert["problem"]["b"][1] = "1"  # -x <= 1: the box [-1, 2], not the claimed [0, 2]
    _rejected(cert, "not the claimed one")
    for claim in cert["claims"]:
        claim["box"]["lo"] = ["-1"]  # claim the new box: its valid set is [0, 3/2], not [0, 1]
    _rejected(cert, "3/2")  # the first claim (largest threshold) is 3/2, not 1: the kernel stops there


def test_a_determinant_of_another_method_is_rejected():
    cert = _cert(SHEAR, SQUARE, M.backward_euler())
    cert["claims"][1]["determinant"] = ["1", "-3", "1"]
    _rejected(cert, "det h(dt A)")


@pytest.mark.parametrize("m", [M.backward_euler(), M.pade(2, 2), M.theta("1/3"), M.rational([2, 1], [2, -3, 1])],
                         ids=lambda m: m.name)
def test_method_matrices_equal_a_direct_evaluation_off_the_interpolation_points(m):
    """D(t) = det h(tA) and N(t) = D(t) h(tA)^-1 g(tA) at t = 1/3 (no interpolation point), in Fractions."""
    A = [[F(-1), F(1, 2), F(0)], [F(1, 3), F(-2), F(1)], [F(0), F(-1, 4), F(-1)]]
    num, den = [F(x) for x in m.numerator], [F(x) for x in m.denominator]
    D, N = method_matrices(A, num, den)
    t = F(1, 3)
    H, Gm = _matrix_polynomial(den, t, A), _matrix_polynomial(num, t, A)
    d = determinant(H)
    assert sum(c * t**k for k, c in enumerate(D)) == d
    X = solve(H, Gm)
    assert [[sum(Nk[i][j] * t**k for k, Nk in enumerate(N)) for j in range(3)] for i in range(3)] == \
        [[d * x for x in r] for r in X]


@pytest.mark.parametrize("m", [M.backward_euler(), M.pade(2, 2), M.pade(1, 2), M.theta(F(1, 3)), M.taylor(3)],
                         ids=lambda m: m.name)
@pytest.mark.parametrize("t", [F(0), F(1, 3), F(7, 2), F(-5, 9)])
def test_method_matrix_at_is_r_of_dt_A_by_one_solve(m, t):
    """r(tA) = h(tA)^-1 g(tA) in Fractions (a direct Gauss solve) equals the kernel's one fraction-free solve."""
    A = [[F(-1), F(1, 2), F(0)], [F(1, 3), F(-2), F(1)], [F(0), F(-1, 4), F(-1)]]
    num, den = [F(x) for x in m.numerator], [F(x) for x in m.denominator]
    H = _matrix_polynomial(den, t, A)
    expected = solve(H, _matrix_polynomial(num, t, A)) if determinant(H) != 0 else None
    assert method_matrix_at(A, num, den, t) == expected


def test_method_matrix_at_is_none_where_r_has_a_pole():
    """Backward Euler 1/(1 - z) on A = [[1]] at dt = 1: I - A is singular, r(A) does not exist."""
    assert method_matrix_at([[F(1)]], [F(1)], [F(1), F(-1)], F(1)) is None
    assert method_matrix_at([[F(1)]], [F(1)], [F(1), F(-1)], F(1, 2)) == [[F(2)]]


# ------------------------------------------------------------------ resource

def test_a_wrong_largest_threshold_or_binding_is_rejected():
    cert = _genuine()
    cert["claims"][0]["value"] = "1/3"
    _rejected(cert, "largest threshold is")
    cert = _genuine()
    binding = cert["claims"][0]["binding"]
    binding["generator"] = (binding["generator"] + 1) % 8
    _rejected(cert, "binding")
    cert = _genuine()
    cert["claims"][0]["binding"]["generator"] = 8  # 2^3 vertices: out of range
    _rejected(cert, "out of range")


def test_a_huge_box_problem_is_priced_and_rejected_before_any_work():
    n = 120
    A = [["-2" if i == j else "1/7" for j in range(n)] for i in range(n)]
    G = [[str(int(i == j)) for j in range(n)] for i in range(n)] + [[str(-int(i == j)) for j in range(n)] for i in range(n)]
    cert = {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": A, "G": G, "b": ["1"] * (2 * n),
                        "method": {"name": "taylor(12)", "numerator": [str(F(1, factorial(k)))
                                                                        for k in range(13)], "denominator": ["1"]}},
            "claims": [{"type": "valid_steplengths", "intervals": [], "box": {"lo": ["-1"] * n, "hi": ["1"] * n}}]}
    _rejected(cert, "work budget")


def test_huge_numbers_in_a_box_problem_are_priced():
    n = 20
    big = "1" + "0" * 600
    A = [[big if i == j else "1" for j in range(n)] for i in range(n)]
    G = [[str(int(i == j)) for j in range(n)] for i in range(n)] + [[str(-int(i == j)) for j in range(n)] for i in range(n)]
    cert = {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": A, "G": G, "b": ["1"] * (2 * n),
                        "method": {"name": "taylor(8)", "numerator": [str(F(1, factorial(k)))
                                                                       for k in range(9)], "denominator": ["1"]}},
            "claims": [{"type": "valid_steplengths", "intervals": [], "box": {"lo": ["-1"] * n, "hi": ["1"] * n}}]}
    _rejected(cert, "work budget")


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 5), st.randoms(use_true_random=False))
def test_integer_solve_is_the_adjugate_times_b(n, rng):
    """det M and adj(M) B = det M * M^-1 B, against Gauss-Jordan over Q (rationals.solve, determinant)."""
    M = [[rng.randint(-3, 3) * (rng.random() < 0.8) for _ in range(n)] for _ in range(n)]
    B = [[rng.randint(-4, 4) for _ in range(2)] for _ in range(n)]
    d, X = integer_solve(M, B)
    assert d == determinant([[F(x) for x in r] for r in M])
    if d:
        assert X == [[d * x for x in r] for r in solve([[F(x) for x in r] for r in M], [[F(x) for x in r] for r in B])]
    else:
        assert X is None


def test_the_entries_root_isolation_is_priced_before_any_sturm_sequence():
    """Pade(2,2) on a 10-dimensional box with 15-digit entries: D and N are cheap to rebuild, but the
    110 entry polynomials (degree 20, coefficients of about a thousand bits) would need minutes of Sturm work.
    With Descartes isolation (charged as it runs) the entries take seconds, and the box route's conditions
    (degree 38, ~1900-bit coefficients) were over the price of one isolation at the Sturm gate.  Since Descartes
    isolation has its own gate (budget.DESCARTES_BUDGET, line-balance) the kernel finishes the exact valid set,
    [0, 0], within the certificate's budget (about 5 s) and rejects the claim of none for what it is."""
    n, rng = 10, random.Random(7)
    A = [[str(rng.randint(-10**15, 10**15)) for _ in range(n)] for _ in range(n)]
    G = [[str(int(i == j)) for j in range(n)] for i in range(n)] + [[str(-int(i == j)) for j in range(n)] for i in range(n)]
    cert = {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": A, "G": G, "b": ["1"] * (2 * n),
                        "method": {"name": "pade(2,2)", "numerator": ["1", "1/2", "1/12"], "denominator": ["1", "-1/2", "1/12"]}},
            "claims": [{"type": "valid_steplengths", "intervals": [], "box": {"lo": ["-1"] * n, "hi": ["1"] * n}}]}
    _rejected(cert, "the valid set has 1 intervals, the claim 0")
