"""Attacks on the kernel's box route (exactinv_check/routes/boxes.py) and the integer
method matrices (conditions.method_matrices, linalg.integer_solve).

The two resource holes it found (rational method matrices rebuilt unpriced, by a discrete-invariance
claim with dt and by the listed route) are fixed: their tests assert a quick rejection.  What held is
kept as ordinary regression tests."""


import itertools
import random
from fractions import Fraction as F

import pytest
from kernel_deadline import check_within

import exactinv as ei
from exactinv.certificates import certificate
from exactinv_check import check
from exactinv_check.conditions import condition_polynomials
from exactinv_check.kernel import Method
from exactinv_check.polyhedra import prove_generators
from exactinv_check.routes import boxes
from exactinv_check.validset import first_end, valid_set

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


M = ei.methods


def _degree_64_method():
    den = ["1"] + ["1" if k % 2 else f"1/{k + 1}" for k in range(1, 65)]
    num = ["1"] + [f"1/{k + 2}" for k in range(1, 65)]
    return {"numerator": num, "denominator": den}


def _cube_problem(n):
    A = [[str(-1 if i == j else (1 if j == i + 1 else 0)) for j in range(n)] for i in range(n)]
    G, b = [], []
    for l in range(n):
        for sgn in (1, -1):
            row = ["0"] * n
            row[l] = str(sgn)
            G.append(row)
            b.append("1")
    return {"A": A, "G": G, "b": b, "method": _degree_64_method()}


def _kernel_routes(A, G, b, lo, hi, m):
    km = Method({"numerator": [str(x) for x in m.numerator], "denominator": [str(x) for x in m.denominator]})
    D, ineq, _ = boxes.box_conditions(A, G, b, km.numerator, km.denominator,
                                      {"lo": [str(x) for x in lo], "hi": [str(x) for x in hi]})
    n = len(lo)
    gens = prove_generators(G, b, [boxes.vertex_of(i, lo, hi) for i in range(2 ** n)], [], [])
    D2, ineq2, eq2 = condition_polynomials(A, G, b, km.numerator, km.denominator, gens)
    first = sorted(ineq, key=lambda p: F(abs(p[0]), max(map(abs, p))))[:n]
    return (valid_set(D, list(ineq), [], first), first_end(D, ineq, {}, first),
            valid_set(D2, list(ineq2), list(eq2)), first_end(D2, ineq2, eq2), set(ineq) <= set(ineq2))


def _same(a, b):
    return len(a) == len(b) and all(x.lo.compare(y.lo) == 0 and x.hi.compare(y.hi) == 0
                                    and (x.lo_closed, x.hi_closed) == (y.lo_closed, y.hi_closed) for x, y in zip(a, b))


# ------------------------------------------------------------------ soundness

@pytest.mark.parametrize("seed", range(12))
def test_box_conditions_equal_the_vertex_route(seed):
    """Shuffled, rescaled, duplicated and redundant rows; rational methods with sign-changing D."""
    rng = random.Random(seed)
    n = rng.randint(1, 2)
    A = [[F(rng.randint(-4, 4), rng.randint(1, 3)) for _ in range(n)] for _ in range(n)]
    lo = [F(rng.randint(-3, 2), rng.randint(1, 3)) for _ in range(n)]
    hi = [x + F(rng.randint(1, 4), rng.randint(1, 3)) for x in lo]
    G, b = [], []
    for l in range(n):
        for up in (True, False):
            for slack in (0, 0, rng.randint(0, 2)):  # a duplicate and an implied row
                a = F(rng.randint(1, 3), rng.randint(1, 2))
                row = [F(0)] * n
                row[l] = a if up else -a
                G.append(row)
                b.append(a * (hi[l] + slack) if up else -a * (lo[l] - slack))
    order = list(range(len(G)))
    rng.shuffle(order)
    G, b = [G[i] for i in order], [b[i] for i in order]
    m = [M.backward_euler(), M.pade(1, 1), M.pade(0, 2), M.theta(F(1, 3)), M.taylor(3), M.pade(1, 2)][seed % 6]
    box_set, box_end, truth, truth_end, subset = _kernel_routes(A, G, b, lo, hi, m)
    assert subset and _same(box_set, truth)
    assert box_end[0].compare(truth_end[0]) == 0 and box_end[1] == truth_end[1]


def test_forged_box_interval_is_rejected_and_listed_truth_accepted():
    S, P, m = ei.LinearSystem([[1, -2], ["1/2", -1]]), ei.Polyhedron.box([-1, -2], [1, 2]), M.backward_euler()
    cert = certificate(S, P, m, [ei.valid_steplengths(S, P, m)])
    assert "box" in cert["claims"][0] and check(cert).ok
    listed = certificate(S, P, m, [ei.valid_steplengths(S, P, m, box=False)])
    assert listed["claims"][0]["intervals"] == cert["claims"][0]["intervals"]
    for iv in cert["claims"][0]["intervals"]:
        iv["hi_closed"] = not iv["hi_closed"] if iv["hi"] != "oo" else iv["hi_closed"]
        iv["lo_closed"] = not iv["lo_closed"]
    assert not check(cert).ok


# ------------------------------------------------------------------ resource

def test_discrete_invariance_dt_prices_the_rational_method_matrices():
    n = 12
    cert = {"format": "exactinv-certificate", "version": 2, "problem": _cube_problem(n),
            "claims": [{"type": "discrete_invariance", "holds": True, "dt": "1", "H": [["0"] * (2 * n)] * (2 * n)}]}
    assert not check_within(cert, 2).ok


def test_listed_route_prices_the_rational_method_matrices():
    n = 6
    claim = {"type": "valid_steplengths", "intervals": [], "rays": [], "lines": [],
             "vertices": [[str(x) for x in v] for v in itertools.product([-1, 1], repeat=n)]}
    cert = {"format": "exactinv-certificate", "version": 2, "problem": _cube_problem(n), "claims": [claim]}
    assert not check_within(cert, 2).ok


def test_box_route_prices_the_same_input_first():
    """What held: the box route prices the rebuild before method_matrices."""
    n = 6
    claim = {"type": "valid_steplengths", "intervals": [], "box": {"lo": ["-1"] * n, "hi": ["1"] * n}}
    cert = {"format": "exactinv-certificate", "version": 2, "problem": _cube_problem(n), "claims": [claim]}
    report = check_within(cert, 2)
    assert not report.ok and "work budget" in str(report)
