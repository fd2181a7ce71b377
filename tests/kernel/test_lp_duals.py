"""exactinv_check.routes.lp_duals: the dual pieces of an lp record (the paper's certificate y(h) >= 0 with
G'^T y(h) = D N^T g_i and q = D^2 b_i - y^T b >= 0 along a piece), proved by the kernel; genuine pieces
accepted, forged ones (a negative entry, an identity off by one coefficient, a piece past q's root, an
algebraic start, a facet claimed valid where it is not) rejected."""

import copy
import json
import sys
import time
from fractions import Fraction as F
from pathlib import Path

import pytest

import exactinv as ei
import exactinv_check
from exactinv.validset import lp_route as engine_lp
from exactinv_check.failure import CheckFailure
from exactinv_check.kernel import Problem
from exactinv_check.routes import lp_pieces
from exactinv_check.validset import valid_set

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from lp_route import family  # noqa: E402  (the benchmark's random family: P = {Gx <= 1}, A = -I + N/(10 n))

M = ei.methods

# x' = -x on [-1, 1], forward Euler: D = 1, N(h) = 1 - h, V = [0, 2].  Facet 0 (x <= 1) from a = 1/2:
# D N^T g_0 = 1 - h = 1/2 - (h - 1/2): y_0 = 1/2 on row 0 (G^T y_0 = 1/2), y_1 = 1 on row 1 (G^T y_1 = -1);
# y(h)^T b = 1/2 + (h - 1/2) = h, q(h) = 1 - h >= 0 on [1/2, 1]: facet 0 valid there (phi_0 = 1 - h <= 1).
PROBLEM = {"A": [["-1"]], "G": [["1"], ["-1"]], "b": ["1", "1"],
           "method": {"numerator": ["1", "1"], "denominator": ["1"]}}
DUAL = {"dual": [[[0, "1/2"]], [[1, "1"]]]}
RECORD = {"facets": [{"ends": ["1/2", "1", "oo"], "bases": [[0], DUAL, [1]]},
                     {"ends": ["1", "2"], "bases": [[1], [0]]}]}


def _set(record, problem=PROBLEM):
    """The kernel's valid set from an lp record (CheckFailure when the record is rejected)."""
    p = Problem(problem)
    gens, D, inequalities, equalities, horizon = lp_pieces.lp_conditions(p, record)
    lp_pieces.require_horizon(D, inequalities, equalities, horizon, {}, "key")
    return [(str(i.lo), str(i.hi), i.lo_closed, i.hi_closed) for i in valid_set(D, list(inequalities), list(equalities))]


def _forged(change):
    record = copy.deepcopy(RECORD)
    change(record["facets"][0])
    return record


def _dual_certificates(seeds, n=4, m=12, method=None):
    """Genuine certificates of the random family with dual pieces forced on (every basis piece's end tried)."""
    old = engine_lp.DUAL_POLICY
    engine_lp.DUAL_POLICY = engine_lp.DualPolicy(F(0), 0, 1, 10**9)
    try:
        out = []
        for seed in seeds:
            S, P = family(n, m, seed)
            V = ei.valid_steplengths(S, P, method or M.taylor(4), route="lp")
            if V.lp.duals:
                out.append(V.certificate)
        return out
    finally:
        engine_lp.DUAL_POLICY = old


# ------------------------------------------------------------------ soundness

def test_a_dual_piece_by_hand_is_accepted_and_adds_no_condition():
    assert _set(RECORD) == [("0", "2", True, True)]
    p = Problem(PROBLEM)
    gens, _, inequalities, _, _ = lp_pieces.lp_conditions(p, RECORD)
    assert len(gens.vertices) == 5  # one generator slot per piece, the dual one without a condition
    without = {"facets": [{"ends": ["1", "oo"], "bases": [[0], [1]]}, RECORD["facets"][1]]}
    assert len(inequalities) <= len(lp_pieces.lp_conditions(p, without)[2])


def test_a_point_dual_piece_and_a_dual_piece_touching_q_at_its_end():
    """[1/2, 1/2] (q(1/2) = 1/2 >= 0) and [1/2, 1] where q = 1 - h touches 0 at the end: both accepted."""
    point = _forged(lambda f: f.update(ends=["1/2", "1/2", "1", "oo"], bases=[[0], DUAL, DUAL, [1]]))
    assert _set(point) == [("0", "2", True, True)]
    assert _set(RECORD) == [("0", "2", True, True)]


def test_a_point_dual_piece_with_q_negative_is_rejected_and_q_touching_0_at_the_start_accepted():
    """y_0 = (3/2, 1): G^T y_0 = 1/2 (the identity holds) but b^T y_0 = 5/2 > 1, so q(1/2) = -3/2: rejected
    as a point piece [1/2, 1/2] (found: the general check bisected the point itself, a kernel fault); with
    y_0 = (3/4, 1/4), q(h) = 1/2 - h is 0 at the point 1/2 (accepted: the facet is exactly valid there) and
    negative right of it."""
    bad = {"dual": [[[0, "3/2"], [1, "1"]], [[1, "1"]]]}
    with pytest.raises(CheckFailure, match="negative at its point"):
        _set(_forged(lambda f: f.update(ends=["1/2", "1/2", "1", "oo"], bases=[[0], bad, DUAL, [1]])))
    touch = {"dual": [[[0, "3/4"], [1, "1/4"]], [[1, "1"]]]}
    assert _set(_forged(lambda f: f.update(ends=["1/2", "1/2", "1", "oo"], bases=[[0], touch, DUAL, [1]]))) == \
        [("0", "2", True, True)]
    with pytest.raises(CheckFailure, match="negative inside"):
        _set(_forged(lambda f: f.update(ends=["1/2", "1", "oo"], bases=[[0], touch, [1]])))


@pytest.mark.parametrize("change, message", [
    (lambda f: f["bases"][1]["dual"].__setitem__(1, [[1, "-1"]]), "not positive"),
    (lambda f: f["bases"][1]["dual"].__setitem__(1, [[1, "0"]]), "not positive"),
    (lambda f: f["bases"][1]["dual"].__setitem__(1, [[1, "2"]]), "Taylor coefficient 1"),
    (lambda f: f["bases"][1]["dual"].__setitem__(0, [[0, "1/2"], [1, "1/4"]]), "Taylor coefficient 0"),
    (lambda f: f["bases"][1]["dual"].pop(), "Taylor coefficient 1"),
    (lambda f: f["bases"][1]["dual"].append([]), "Taylor coefficients"),
    (lambda f: f["ends"].__setitem__(1, "8/7"), "negative inside its piece"),
    (lambda f: f.update(ends=["1/2", "oo"], bases=[[0], DUAL]), "negative inside its piece"),
    (lambda f: f["ends"].__setitem__(0, {"poly": ["-1", "0", "2"], "interval": ["0", "1"]}), "starts at a rational"),
    (lambda f: f["bases"][1]["dual"].__setitem__(1, [[2, "1"]]), "out of range"),
    (lambda f: f["bases"][1]["dual"].__setitem__(0, [[0, "1/4"], [0, "1/4"]]), "strictly increasing"),
    (lambda f: f["bases"][1].update(ray=["1"]), "a dual piece is"),
    (lambda f: f["bases"].__setitem__(1, {"dual": []}), "at least one vector"),
])
def test_forged_dual_pieces_are_rejected(change, message):
    with pytest.raises(CheckFailure, match=message):
        _set(_forged(change))


def test_a_dual_piece_claiming_an_invalid_facet_valid_is_rejected():
    """Taylor-1 on x' = -x, facet 0 past h = 2 is invalid (phi_0 = h - 1 > 1): a dual piece there needs
    y(h)^T b <= 1 with G^T y(h) = 1 - h, impossible -- any y_k the forger picks breaks the identity or q."""
    record = {"facets": [{"ends": ["1", "3"], "bases": [[0], {"dual": [[[1, "0"]], [[1, "1"]]]}]},
                         {"ends": ["1", "3"], "bases": [[1], [0]]}]}
    with pytest.raises(CheckFailure):
        _set(record)
    record["facets"][0]["bases"][1] = {"dual": [[], [[1, "1"]]]}  # identity right from a = 1, q = 1 - (h - 1)
    with pytest.raises(CheckFailure, match="negative inside"):
        _set(record)


def test_genuine_engine_certificates_with_dual_pieces_are_accepted_and_their_forgeries_rejected():
    certs = _dual_certificates(range(3))
    assert certs, "the forced policy made no dual piece on the random family"
    for cert in certs:
        assert exactinv_check.check(cert).ok
        facets = cert["claims"][0]["lp"]["facets"]
        where = [(i, k) for i, f in enumerate(facets) for k, b in enumerate(f["bases"]) if isinstance(b, dict)
                 and "dual" in b]
        i, k = where[0]
        forged = copy.deepcopy(cert)
        y = forged["claims"][0]["lp"]["facets"][i]["bases"][k]["dual"]
        last = max(j for j, v in enumerate(y) if v)
        y[last][0][1] = str(2 * F(y[last][0][1]))  # the identity off in one coefficient
        assert not exactinv_check.check(forged).ok
        forged = copy.deepcopy(cert)
        y = forged["claims"][0]["lp"]["facets"][i]["bases"][k]["dual"]
        y[0][0][1] = "-" + y[0][0][1]
        assert not exactinv_check.check(forged).ok


def test_a_rational_method_with_dual_pieces_checks():
    certs = _dual_certificates(range(2), method=M.pade(1, 1))
    for cert in certs:
        assert exactinv_check.check(cert).ok


# ------------------------------------------------------------------ resources

def test_too_many_dual_entries_are_rejected_before_any_work():
    from exactinv_check.budget import MAX_LP_DUAL_ENTRIES
    big = {"dual": [[[0, "1"]] for _ in range(200)]}
    count = MAX_LP_DUAL_ENTRIES // 200 + 1
    record = {"facets": [{"ends": ["oo"] * count, "bases": [big] * count},
                         RECORD["facets"][1]]}
    start = time.process_time()
    with pytest.raises(CheckFailure, match="entries in all"):
        _set(record)
    assert time.process_time() - start < 30  # a bound on the test's own run, not a timing claim
    # counted before the numbers are parsed: one vector too many in one piece is refused by the count
    with pytest.raises(CheckFailure, match="entries in all"):
        _set(_forged(lambda f: f["bases"][1]["dual"].__setitem__(0, [[0, "1/2"]] * (MAX_LP_DUAL_ENTRIES + 1))))


def test_huge_numbers_in_a_dual_piece_are_charged():
    """A 4000-digit y entry: the identity fails (or the budget says no) without a long computation."""
    forged = _forged(lambda f: f["bases"][1]["dual"].__setitem__(1, [[1, "1" + "0" * 4000]]))
    cert = {"format": "exactinv-certificate", "version": 3, "problem": PROBLEM, "claims": []}
    assert json.dumps(cert)  # the record alone goes through lp_conditions
    with pytest.raises(CheckFailure):
        _set(forged)
