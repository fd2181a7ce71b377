"""exactinv_check.claims_sets: the valid-set and largest-threshold claims (beyond the paper), called directly on a
parsed Problem.  The truths are worked out here: for forward Euler, tau* = min over vertices v and facets j with
g_j A v > 0 of (b_j - g_j v)/(g_j A v) and the valid set is [0, tau*]; for r(z) = 1 + c s z + c z^2 on
x' = -x, P = [-1, 1], r(-h) = 1 - c h (s - h) is <= 1 exactly on [0, s] and >= -1 there iff c s^2 <= 8 (else the
first interval ends at the smaller root of c h^2 - c s h + 2, in (0, s/2)).  The generator lists, the box
record and the forged claims are all exercised through largest_threshold and valid_steplengths themselves."""

import itertools
from fractions import Fraction as F

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from exactinv_check import claims_sets
from exactinv_check.budget import account
from exactinv_check.failure import CheckFailure, OverBudget
from exactinv_check.kernel import Problem

diagonal = st.fractions(min_value=1, max_value=3, max_denominator=4)
off_diagonal = st.fractions(min_value=F(-1, 3), max_value=F(1, 3), max_denominator=6)
EULER = {"name": "custom", "numerator": ["1", "1"], "denominator": ["1"]}


def _box_problem(A, lo, hi, method=EULER):
    n = len(lo)
    G = [[int(i == k) for k in range(n)] for i in range(n)] + [[-int(i == k) for k in range(n)] for i in range(n)]
    b = list(hi) + [-x for x in lo]
    return Problem({"A": [[str(x) for x in row] for row in A], "G": [[str(x) for x in g] for g in G],
                    "b": [str(x) for x in b], "method": method})


def _vertices(lo, hi):
    return [[str(x) for x in v] for v in itertools.product(*zip(lo, hi))]


def _euler_tau(A, lo, hi):
    n, best = len(A), None
    G = [[F(int(i == k)) for k in range(n)] for i in range(n)] + [[F(-int(i == k)) for k in range(n)] for i in range(n)]
    b = list(hi) + [-x for x in lo]
    for v in itertools.product(*zip(lo, hi)):
        Av = [sum(a * x for a, x in zip(row, v)) for row in A]
        for g, beta in zip(G, b):
            rate = sum(a * x for a, x in zip(g, Av))
            if rate > 0:
                tau = (beta - sum(a * x for a, x in zip(g, v))) / rate
                best = tau if best is None else min(best, tau)
    return best


def _threshold(value, attained=True, **where):
    return {"type": "largest_threshold", "value": value, "attained": attained, **where}


def _interval(hi, lo="0"):
    return {"type": "valid_steplengths", "intervals": [{"lo": lo, "hi": hi, "lo_closed": True, "hi_closed": True}]}


# ------------------------------------------------------------------ soundness
@settings(max_examples=10, deadline=None)
@given(diagonal, diagonal, off_diagonal, off_diagonal)
def test_forward_euler_threshold_and_valid_set_are_the_definitions_over_vertices_and_over_the_box(a, d, p, q):
    # a, d >= 1 and |p|, |q| <= 1/3: A points strictly into the box at every vertex, so 0 < tau* < oo
    A, lo, hi = [[-a, p], [q, -d]], [F(-1), F(-2)], [F(1), F(1)]
    tau = _euler_tau(A, lo, hi)
    assert tau is not None and tau > 0
    problem = _box_problem(A, lo, hi)
    lists = {"vertices": _vertices(lo, hi), "rays": [], "lines": []}
    box = {"box": {"lo": [str(x) for x in lo], "hi": [str(x) for x in hi]}}
    for where in (lists, box):
        assert "largest threshold" in claims_sets.largest_threshold(problem, _threshold(str(tau), **where), {})
        assert "the valid set" in claims_sets.valid_steplengths(problem, {**_interval(str(tau)), **where}, {})
        for forged in (tau * F(11, 10), tau * F(9, 10)):
            with pytest.raises(CheckFailure, match=f"the largest threshold is {tau}, not {forged}"):
                claims_sets.largest_threshold(problem, _threshold(str(forged), **where), {})
            with pytest.raises(CheckFailure, match=f"interval 0 ends at {tau}"):
                claims_sets.valid_steplengths(problem, {**_interval(str(forged)), **where}, {})
        with pytest.raises(CheckFailure, match="the attained flag is wrong"):  # [0, tau*] is closed
            claims_sets.largest_threshold(problem, _threshold(str(tau), False, **where), {})


@settings(max_examples=20, deadline=None)
@given(st.fractions(min_value=F(1, 4), max_value=4, max_denominator=4),
       st.fractions(min_value=F(1, 8), max_value=8, max_denominator=8))
def test_a_quadratic_method_on_the_interval_ends_at_s_or_at_the_smaller_root(s, c):
    method = {"name": "custom", "numerator": ["1", str(c * s), str(c)], "denominator": ["1"]}
    problem = _box_problem([[-1]], [F(-1)], [F(1)], method)
    where = {"vertices": [["-1"], ["1"]], "rays": [], "lines": []}
    root = {"poly": ["2", str(-c * s), str(c)], "interval": ["0", str(s / 2)]}  # c h^2 - c s h + 2 on (0, s/2)
    if c * s * s <= 8:
        claims_sets.largest_threshold(problem, _threshold(str(s), **where), {})
        claims_sets.valid_steplengths(problem, {**_interval(str(s)), **where}, {})
        wrong = [str(s + F(1, 100)), str(s - F(1, 100))]
        if c * s * s < 8:  # c h^2 - c s h + 2 has no real root: a claim naming one is refused as it is parsed
            with pytest.raises(CheckFailure, match="does not isolate exactly one root"):
                claims_sets.largest_threshold(problem, _threshold(root, **where), {})
    else:
        claims_sets.largest_threshold(problem, _threshold(root, **where), {})
        wrong = [str(s), str(s / 2)]
    for forged in wrong:
        with pytest.raises(CheckFailure, match="the largest threshold is"):
            claims_sets.largest_threshold(problem, _threshold(forged, **where), {})


def test_the_binding_record_names_the_recomputed_condition_or_is_rejected():
    # x' = -x, forward Euler, P = [-1, 1]: the vertex 1 and facet x <= 1? g A v = -1 < 0; facet -x <= 1 at v = 1:
    # 1 + (1 - h) >= 0 ends at h = 2 (vertex 0 = -1 and facet 0 likewise); the condition is 2 - h, primitive
    problem = _box_problem([[-1]], [F(-1)], [F(1)])
    where = {"vertices": [["-1"], ["1"]], "rays": [], "lines": []}
    binding = {"kind": "vertex", "generator": 1, "facet": 1, "poly": ["2", "-1"]}
    claims_sets.largest_threshold(problem, _threshold("2", binding=binding, **where), {})
    with pytest.raises(CheckFailure, match="binding polynomial is not the recomputed condition"):
        claims_sets.largest_threshold(problem, _threshold("2", binding={**binding, "poly": ["3", "-1"]}, **where), {})
    with pytest.raises(CheckFailure, match="binding polynomial is not the recomputed condition"):
        claims_sets.largest_threshold(problem, _threshold("2", binding={**binding, "facet": 0}, **where), {})
    with pytest.raises(CheckFailure, match="binding kind is vertex, ray or line"):
        claims_sets.largest_threshold(problem, _threshold("2", binding={**binding, "kind": "edge"}, **where), {})


def test_malformed_claims_are_rejected_for_their_reason():
    problem = _box_problem([[-1, 0], [0, -1]], [F(-1)] * 2, [F(1)] * 2)
    V = _vertices([-1, -1], [1, 1])
    box = {"lo": ["-1", "-1"], "hi": ["1", "1"]}
    cases = [
        ({"vertices": V, "rays": [], "lines": [], "box": box}, "either the box or the vertices"),
        ({"vertices": V, "rays": []}, "missing keys: vertices, rays and lines go together"),
        ({}, "either the box or the vertices"),
        ({"box": box, "pruning": {"horizon": "2", "vertex": 0, "order": [0, 1, 2, 3]}}, "box claim needs no pruning"),
        ({"box": {"lo": ["-1", "-1"], "hi": ["1", "2"]}}, "not the claimed one"),  # not the box of G and b
        ({"vertices": V[:3], "rays": [], "lines": []}, "incomplete generators"),  # a corner missing
        ({"vertices": V, "rays": [], "lines": [], "determinant": ["1", "3"]}, "det h\\(dt A\\) does not match"),
        ({"vertices": V, "rays": [], "lines": [], "pruning": {"variable": "h/(s+h)", "horizon": "2"}},
         "written for rational methods only"),
    ]
    for where, reason in cases:
        with pytest.raises(CheckFailure, match=reason):
            claims_sets.largest_threshold(problem, _threshold("1", **where), {})
    no_method = Problem({"A": [["-1"]], "G": [["1"], ["-1"]], "b": ["1", "1"]})
    with pytest.raises(CheckFailure, match="a method is needed"):
        claims_sets.largest_threshold(no_method, _threshold("2", vertices=[["-1"], ["1"]], rays=[], lines=[]), {})


# ------------------------------------------------------------------ resources
def test_the_generators_are_proved_once_per_context_and_the_work_is_charged():
    problem = _box_problem([[-1, 1, 0], [0, -1, 1], [0, 0, -1]], [F(-1)] * 3, [F(1)] * 3)
    where = {"vertices": _vertices([-1] * 3, [1] * 3), "rays": [], "lines": []}
    tau = _euler_tau([[F(-1), F(1), F(0)], [F(0), F(-1), F(1)], [F(0), F(0), F(-1)]], [F(-1)] * 3, [F(1)] * 3)
    context = {}
    with account() as first:
        claims_sets.largest_threshold(problem, _threshold(str(tau), **where), context)
    with account() as again:  # the same lists in the same certificate: proved and rebuilt once
        claims_sets.valid_steplengths(problem, {**_interval(str(tau)), **where}, context)
    assert first.spent > 0 and again.spent < first.spent
    with account(limit=first.spent // 10):
        with pytest.raises(OverBudget, match="over the certificate's work budget"):
            claims_sets.largest_threshold(problem, _threshold(str(tau), **where), {})
