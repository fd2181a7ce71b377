"""exactinv_check.claims_thresholds: the forward-Euler threshold claim, against its definition
tau* = sup{tau >= 0 : x + tau A x in P for every x in P}, worked out here over the vertices of a box
(the minimum of (b_j - g_j v)/(g_j A v) over vertices v and facets j with g_j A v > 0)."""

import copy
import itertools
from fractions import Fraction as F

from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.certificates import certificate
from exactinv_check import check

entry = st.fractions(min_value=-3, max_value=3, max_denominator=3)


def _tau_by_definition(A, lo, hi):
    n = len(A)
    G = [[F(int(i == k)) for k in range(n)] for i in range(n)] + [[F(-int(i == k)) for k in range(n)] for i in range(n)]
    b = list(hi) + [-x for x in lo]
    best = None
    for v in itertools.product(*zip(lo, hi)):
        Av = [sum(a * x for a, x in zip(row, v)) for row in A]
        for g, beta in zip(G, b):
            rate = sum(a * x for a, x in zip(g, Av))
            if rate > 0:
                tau = (beta - sum(a * x for a, x in zip(g, v))) / rate
                best = tau if best is None else min(best, tau)
    return best  # None: every x + tau A x stays in P for all tau >= 0


# ------------------------------------------------------------------ soundness
@settings(max_examples=8, deadline=None)
@given(st.lists(st.lists(entry, min_size=2, max_size=2), min_size=2, max_size=2))
def test_the_claimed_value_is_accepted_exactly_at_the_definition(A):
    lo, hi = [F(-1), F(-2)], [F(1), F(1)]
    S, box = ei.LinearSystem([[str(x) for x in row] for row in A]), ei.Polyhedron.box(lo, hi)
    cert = certificate(S, box, None, [ei.forward_euler_threshold(S, box)])
    truth = _tau_by_definition(A, lo, hi)
    k = next(i for i, c in enumerate(cert["claims"]) if c["type"] == "forward_euler_threshold")
    value = cert["claims"][k]["value"]
    assert (value == "oo") if truth is None else (F(value) == truth)
    assert check(cert).ok
    forgeries = [F(1)] if truth is None else [F(1, 100)] if truth == 0 else [truth * F(11, 10), truth * F(9, 10)]
    for forged in forgeries:
        bad = copy.deepcopy(cert)
        bad["claims"][k]["value"] = str(forged)
        assert not check(bad).ok, forged


# ------------------------------------------------------------------ resources
def test_a_claim_with_a_huge_value_is_rejected_not_computed_at_length():
    S, box = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    cert = certificate(S, box, None, [ei.forward_euler_threshold(S, box)])
    cert["claims"][-1]["value"] = "9" * 4001  # over the format's digit bound: refused before any arithmetic
    report = check(cert)
    assert not report.ok and report.kind in ("rejected", "bad-input")
