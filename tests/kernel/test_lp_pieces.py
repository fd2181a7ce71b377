"""exactinv_check.routes.lp_pieces, attacked: the LP route's lp record (exactinv_check/routes/lp_pieces.py) and the control claims
(exactinv_check/claims_control.py): resource attacks that ran for minutes before the fix, and forgeries
that the kernel must keep rejecting."""


import copy
import json
import random
import time
from fractions import Fraction as F

import pytest

import exactinv as ei
import exactinv_check
from exactinv_check.kernel import Problem
from exactinv_check.reals import Real
from exactinv_check.routes import lp_pieces
from exactinv_check.validset import valid_set

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


M = ei.methods


def _zeros(r, c):
    return [[0] * c for _ in range(r)]


def _timed_check(cert):
    text = json.dumps(cert, separators=(",", ":"))
    assert len(text) < 1_000_000
    start = time.process_time()
    report = exactinv_check.check(text)
    return report, time.process_time() - start


def _problem(seed, method, bounded=True):
    rng = random.Random(seed)
    n = 2
    G = [[rng.randint(-4, 4) for _ in range(n)] for _ in range(4)]
    G += [[int(i == j) * s for j in range(n)] for i in range(n) for s in ((1, -1) if bounded else (1,))]
    G = [g for g in G if any(g)]
    S = ei.LinearSystem([[F(rng.randint(-4, 4), rng.choice([1, 2, 4])) for _ in range(n)] for _ in range(n)])
    return S, ei.Polyhedron(G, [1] * len(G)), method


def _truth(cert, record):
    """The kernel's own set from an lp record (CheckFailure when the record is rejected)."""
    problem = Problem(cert["problem"])
    gens, D, inequalities, equalities, horizon = lp_pieces.lp_conditions(problem, record)
    lp_pieces.require_horizon(D, inequalities, equalities, horizon, {}, "key")
    return [(str(i.lo), str(i.hi), i.lo_closed, i.hi_closed) for i in valid_set(D, list(inequalities), [])]


# ------------------------------------------------------------------ soundness

def test_an_algebraic_end_with_a_wrong_interval_is_rejected():
    S, P, meth = _problem(0, M.pade(1, 1))
    cert = ei.valid_steplengths(S, P, meth, route="lp").certificate
    for f in cert["claims"][0]["lp"]["facets"]:
        for e in f["ends"]:
            if isinstance(e, dict):
                lo, hi = (F(x) for x in e["interval"])
                e["interval"] = [str(hi), str(hi + (hi - lo))]  # next to the root, not around it
                report = exactinv_check.check(cert)
                assert not report.ok
                return
    pytest.skip("no algebraic end")


def test_a_robust_tau_past_a_complex_pole_is_rejected():
    """Found (fixed): robust_threshold for a rational method took beta = max_r (H_i v)_r / v_r from a
    gamma* = -oo vertex's H without tying that H to gamma (H + max(gamma, 0) I >= 0).  beta bounds only
    Re lambda: with P = {0} (G = [I; -I], b = 0, so gamma* = -oo), A = [[-1, -1], [1, -1]] (eigenvalues
    -1 +- i), r = (1 + z/2) / ((1 - z)(1 + z + z^2/2)) (poles 1 and -1 +- i, rho = 0.247...) and the H
    -I + (a 4-cycle) (rows summing to 0, so beta = 0 with v = 1), the kernel VERIFIED tau = oo -- yet
    h_r(1 A) is singular (h A has the eigenvalues -1 +- i, poles of r): h = 1 is no valid steplength."""
    m = ei.methods.rational([1, F(1, 2)], [1, 0, F(-1, 2), F(-1, 2)])
    P = ei.Polyhedron([[1, 0], [0, 1], [-1, 0], [0, -1]], [0, 0, 0, 0])
    A = [[-1, -1], [1, -1]]
    cert = ei.robust_threshold([A], P, m).certificate
    assert exactinv_check.check(cert).ok  # the engine's own H is nonnegative: genuine, and still verified
    claim = cert["claims"][1]
    assert claim["gamma"] == "-oo"
    claim["vertices"][0]["H"] = {"sparse": [[[0, "-1"], [3, "1"]], [[0, "1"], [1, "-1"]], [[1, "1"], [2, "-1"]],
                                            [[2, "1"], [3, "-1"]]]}  # version 3: by rows
    claim["v"], claim["beta"] = ["1"] * 4, "0"
    claim["value"], claim["attained"] = "oo", True
    report = exactinv_check.check(cert)
    assert not report.ok and "H + 0 I >= 0 failing" in str(report), report
    # the claim is false: h_r(hA) = I - (hA)^2/2 - (hA)^3/2 is singular at h = 1
    A2 = [[sum(A[i][k] * A[k][j] for k in range(2)) for j in range(2)] for i in range(2)]
    A3 = [[sum(A2[i][k] * A[k][j] for k in range(2)) for j in range(2)] for i in range(2)]
    Hr = [[int(i == j) - F(A2[i][j], 2) - F(A3[i][j], 2) for j in range(2)] for i in range(2)]
    assert Hr[0][0] * Hr[1][1] - Hr[0][1] * Hr[1][0] == 0


# ------------------------------------------------------------------ resource

def test_a_dense_farkas_record_is_priced_not_run():
    """Found: a 350 KB optimal_gain certificate (n = m = 240, every matrix 0, holds = false) ran the dual's
    m^2 n Fraction products unpriced (the check counted entries, not Fraction operations, and never ticked
    the clock): 105 s of CPU before a rejection.  Now priced by fraction_products_cost and rejected at once."""
    n = m = 240
    cert = {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": _zeros(n, n), "B": [[0] for _ in range(n)],
                        "G": [[int(i == j) for j in range(n)] for i in range(m)], "b": [1] * m},
            "claims": [{"type": "optimal_gain", "holds": False, "value": "oo",
                        "farkas": {"Y": _zeros(m, n), "mu": [0] * m, "nu": [0] * m, "Z": [], "w": []},
                        "x": [0] * n}]}
    report, seconds = _timed_check(cert)
    assert not report.ok
    assert "work budget" in str(report), report
    assert seconds < 10


def test_a_dense_primal_gain_record_is_priced_not_run():
    n = m = 200
    cert = {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": _zeros(n, n), "B": [[0] for _ in range(n)],
                        "G": [[int(i == j) for j in range(n)] for i in range(m)], "b": [1] * m},
            "claims": [{"type": "optimal_gain", "holds": True, "value": "0", "F": [[0] * n], "H": _zeros(m, m),
                        "Lambda": [], "dual": {"Y": _zeros(m, n), "mu": [0] * m, "nu": [1] + [0] * (m - 1),
                                               "Z": [], "w": []}, "x": [0] * n}]}
    report, seconds = _timed_check(cert)
    assert not report.ok
    assert "work budget" in str(report), report
    assert seconds < 10


def test_a_dense_robust_hull_is_priced_not_run():
    """Found: a 770 KB robust_threshold certificate (8 vertices A_i = 0 in R^150, G = I) ran gamma*'s
    G A_i (m n^2 Fraction products each) unpriced: about 2 minutes.  check_H now prices it."""
    n = m = 150
    k = 8
    vertex = {"value": "0", "H": _zeros(m, m), "binding_row": 0, "dual": {"y": [1] + [0] * (n - 1), "lambda": 0}}
    cert = {"format": "exactinv-certificate", "version": 2,
            "problem": {"hull": [_zeros(n, n)] * k, "G": [[int(i == j) for j in range(n)] for i in range(m)],
                        "b": [1] * m, "method": {"name": "taylor(1)", "numerator": ["1", "1"], "denominator": ["1"]}},
            "claims": [{"type": "absolute_monotonicity_radius", "value": "1", "reason": "coefficient",
                        "attained": True, "binding": 0, "d": [["1", "-1"], ["1"]]},
                       {"type": "robust_threshold", "value": "1", "attained": True, "gamma": "0", "rho": "1",
                        "forward_euler": "oo", "vertices": [vertex] * k, "x": [0] * n}]}
    report, seconds = _timed_check(cert)
    assert not report.ok
    assert "work budget" in str(report), report
    assert seconds < 10


def test_a_dense_gamma_star_is_priced_not_run():
    """The same G A product in a plain gamma_star claim (n = 300: about 100 s before the fix)."""
    n = m = 300
    cert = {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": _zeros(n, n), "G": [[int(i == j) for j in range(n)] for i in range(m)], "b": [1] * m},
            "claims": [{"type": "gamma_star", "value": "0", "H": _zeros(m, m), "binding_row": 0,
                        "dual": {"y": [1] + [0] * (n - 1), "lambda": "0"}}]}
    report, seconds = _timed_check(cert)
    assert not report.ok
    assert "work budget" in str(report), report
    assert seconds < 10


@pytest.mark.parametrize("method", [M.taylor(2), M.pade(1, 1), M.backward_euler(), M.pade(0, 2)])
def test_accepted_mutations_of_an_lp_record_never_change_the_set(method):
    """Random mutations (merged pieces, foreign bases, moved ends, truncation, swapped facets, split pieces
    with a random basis): whenever the kernel accepts the mutated record, its set is the genuine one."""
    for seed in range(3):
        S, P, meth = _problem(seed, method, bounded=seed != 2)
        cert = ei.valid_steplengths(S, P, meth, route="lp").certificate
        claim = cert["claims"][0]
        if "lp" not in claim:
            continue
        base = _truth(cert, claim["lp"])
        rng = random.Random(seed)
        m, n = len(cert["problem"]["G"]), len(cert["problem"]["A"])
        for _ in range(15):
            rec = copy.deepcopy(claim["lp"])
            f = rng.choice(rec["facets"])
            K = len(f["ends"])
            op = rng.randrange(4)
            if op == 0 and K >= 2:
                k = rng.randrange(K - 1)
                keep = f["bases"][rng.choice([k, k + 1])]
                del f["ends"][k], f["bases"][k]
                f["bases"][k] = keep
            elif op == 1:
                f["bases"][rng.randrange(K)] = rng.sample(range(m), n)
            elif op == 2:
                del f["ends"][1:], f["bases"][1:]
            else:
                k = rng.randrange(K)
                if f["ends"][k] != "oo":
                    lo, hi = Real.parse(f["ends"][k]).bounds()
                    f["ends"][k] = str(rng.choice([lo, hi, lo * F(99, 100), hi * F(101, 100)]))
            try:
                forged = _truth(cert, rec)
            except exactinv_check.kernel.CheckFailure:
                continue
            assert forged == base
