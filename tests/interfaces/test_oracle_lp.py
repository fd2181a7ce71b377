"""exactinv.oracle.judge_lp: a user's solved cvxpy LP judged exactly."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

import exactinv as ei
from exactinv.interfaces.oracle import judge_lp

cp = pytest.importorskip("cvxpy")


def _certificate_holds(v) -> bool:
    """Re-check the verdict's certificate with Fractions: x feasible, y >= 0 on
    inequality rows, A^T y = -c, and c.x = -b.y (so x is optimal)."""
    data = v.data
    A, b, c, eq = data["A"], data["b"], data["c"], data["equality"]
    x, y = v.lp.x, v.y
    for row, rhs, e in zip(A, b, eq):
        lhs = sum(a * x[i] for i, a in row.items())
        assert lhs == rhs if e else lhs <= rhs
    assert all(yr >= 0 for yr, e in zip(y, eq) if not e)
    ATy = [Fraction(0)] * len(c)
    for row, yr in zip(A, y):
        for i, a in row.items():
            ATy[i] += a * yr
    assert ATy == [-ci for ci in c]
    assert sum(ci * xi for ci, xi in zip(c, x)) == -sum(bi * yi for bi, yi in zip(b, y))
    return True


def _seven_thirds():
    x = cp.Variable(2, name="x")
    problem = cp.Problem(cp.Maximize(x[0] + x[1]), [x[0] + 2 * x[1] <= 3, 2 * x[0] + x[1] <= 4, x >= 0])
    problem.solve(solver=cp.HIGHS)
    return problem, x


def test_a_small_lp_with_optimum_seven_thirds():
    problem, _ = _seven_thirds()
    v = ei.oracle.judge_lp(problem)
    assert v.status == "tight" and v.exact == Fraction(7, 3)
    assert v.x == {"x": (Fraction(5, 3), Fraction(2, 3))}
    assert _certificate_holds(v)
    assert v.lp.path in ("float-rounded", "float-basis", "float-basis+pivots", "exact-ppl")


def test_minimize_with_offset_attributes_and_matrix_variables():
    X = cp.Variable((2, 2), name="X")
    z = cp.Variable(name="z", nonneg=True)
    problem = cp.Problem(cp.Minimize(cp.sum(X) + 3 * z + 1),
                         [X >= 1, X[0, 1] >= 2, z >= X[1, 0] - 3, cp.trace(X) == 5])
    problem.solve(solver=cp.CLARABEL)
    v = judge_lp(problem)
    # X = [[a, >=2], [1, d]] with a + d = 5, a, d >= 1: sum = 5 + 2 + 1 = 8, z = 0, +1
    assert v.exact == 9 and v.status == "tight"
    assert v.x["z"] == (0,) and sum(v.x["X"]) == 8
    assert _certificate_holds(v)


@pytest.mark.parametrize("delta", [1e-7, -1e-7])
def test_a_perturbed_float_answer_is_refuted_with_an_exact_counterexample(delta):
    problem, _ = _seven_thirds()
    claimed = problem.value + delta
    v = judge_lp(problem, claimed)
    assert v.status == "invalid" and not v
    cex = v.counterexample
    if delta > 0:  # a maximum above 7/3: the dual bound proves it unattainable
        assert cex["kind"] == "dual_bound" and cex["bound"] == Fraction(7, 3) < Fraction(claimed)
        assert -sum(bi * yi for bi, yi in zip(v.data["b"], cex["y"])) == -Fraction(7, 3)
    else:  # below 7/3: an exact feasible point beats it
        assert cex["kind"] == "better_point" and cex["value"] > Fraction(claimed)
        x0, x1 = cex["x"]["x"]
        assert x0 + 2 * x1 <= 3 and 2 * x0 + x1 <= 4 and x0 >= 0 and x1 >= 0 and x0 + x1 == cex["value"]
    assert _certificate_holds(v)


def test_a_bound_claim_is_valid_on_the_feasible_side():
    problem, _ = _seven_thirds()
    assert judge_lp(problem, 2.3, claim="bound").status == "valid"
    assert judge_lp(problem, 2.4, claim="bound").status == "invalid"
    assert judge_lp(problem, 7 / 3, claim="bound").status == "tight"


def _gamma_lp(S, P):
    """gamma* = min{gamma : H + gamma I >= 0, HG = GA, Hb <= 0}, as a float user writes it."""
    G = np.array([[float(v) for v in r] for r in P.G])
    A = np.array([[float(v) for v in r] for r in S.A])
    b = np.array([float(v) for v in P.b])
    m = P.m
    H = cp.Variable((m, m), name="H")
    gamma = cp.Variable(name="gamma")
    problem = cp.Problem(cp.Minimize(gamma), [H + gamma * np.eye(m) >= 0, H @ G == G @ A, H @ b <= 0])
    problem.solve(solver=cp.HIGHS)
    return problem


@pytest.mark.parametrize("A", [
    [[-1, 1], [-1, -1]],
    [[-3, 1, 0.5], [0, -2, 1], [1, -0.25, -4]],
])
def test_the_gamma_lp_of_a_box_written_in_cvxpy(A):
    S = ei.LinearSystem(A, allow_float=True) if any(isinstance(v, float) for r in A for v in r) else ei.LinearSystem(A)
    P = ei.Polyhedron.box([-1] * len(A), [1] * len(A))
    problem = _gamma_lp(S, P)
    v = judge_lp(problem)
    assert v.exact == ei.optimal_gamma(S, P).value
    assert v.status == "tight" and _certificate_holds(v)


def test_a_gamma_row_lp_of_a_box_in_cvxpy():
    """Row j of gamma*:  max h_j  s.t.  h^T G = g_j^T A, h^T b <= 0, h_k >= 0 (k != j)."""
    S = ei.LinearSystem([[-2, 1], [Fraction(1, 2), -1]])
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    G = np.array([[float(v) for v in r] for r in P.G])
    A = np.array([[float(v) for v in r] for r in S.A])
    b = np.array([float(v) for v in P.b])
    j = 0
    h = cp.Variable(P.m, name="h")
    problem = cp.Problem(cp.Maximize(h[j]), [G.T @ h == A.T @ G[j], b @ h <= 0] + [h[k] >= 0 for k in range(P.m) if k != j])
    problem.solve(solver=cp.CLARABEL)
    v = judge_lp(problem, tolerance="1e-7")
    assert v.exact == -ei.optimal_gamma(S, P).rows[j].gamma
    assert v.status == "tight"


def test_a_forward_euler_vertex_lp_in_cvxpy():
    """The largest forward-Euler step by the vertex ratio test, as one LP in dt:
    max dt  s.t.  dt * g_j.(A v) <= b_j - g_j.v  for every vertex v and facet j."""
    S = ei.LinearSystem([[-1, Fraction(1, 2)], [Fraction(-1, 3), -2]])
    P = ei.Polyhedron([[1, 0], [0, 1], [-1, 0], [0, -1], [1, 1], [-1, -1]], [1, 1, 1, 1, Fraction(3, 2), Fraction(3, 2)])
    dt = cp.Variable(name="dt")
    constraints = [dt >= 0]
    for vtx in P.vertices:
        Av = [sum(S.A[r][k] * vtx[k] for k in range(2)) for r in range(2)]
        for g, bj in zip(P.G, P.b):
            rate = float(sum(gi * a for gi, a in zip(g, Av)))
            slack = float(bj - sum(gi * xi for gi, xi in zip(g, vtx)))
            if rate > 0:
                constraints.append(dt * rate <= slack)
    problem = cp.Problem(cp.Maximize(dt), constraints)
    problem.solve(solver=cp.HIGHS)
    exact = ei.forward_euler_threshold(S, P).value
    v = judge_lp(problem)
    # the float data are the float images of the exact rates: the exact LP of those
    # floats has an optimum within a few ulps of the true threshold
    assert abs(v.exact - exact) <= Fraction(1, 10**12) * exact
    assert v.status == "tight"
    v = judge_lp(problem, limit_denominator=1000)  # the stated rounding recovers the exact rates
    assert v.exact == exact


def test_float_data_are_taken_exactly_unless_a_rounding_is_stated():
    x = cp.Variable(name="x")
    problem = cp.Problem(cp.Minimize(x), [x == 0.1, 10 * x == 1])
    problem.solve(solver=cp.HIGHS)
    assert problem.status == cp.OPTIMAL  # within the float solver's tolerances
    v = judge_lp(problem)
    assert v.status == "invalid" and v.exact is None and v.counterexample["kind"] == "infeasible"
    assert judge_lp(problem, limit_denominator=10).exact == Fraction(1, 10)


def test_an_unbounded_exact_lp_gets_a_point_beating_the_claim():
    x = cp.Variable(2, name="x")
    problem = cp.Problem(cp.Maximize(x[0] + x[1]), [x[0] - x[1] <= 1, x[1] >= 0])
    v = judge_lp(problem, 1000.0)
    assert v.status == "invalid" and v.exact == ei.INF
    p = v.counterexample["x"]["x"]
    assert p[0] - p[1] <= 1 and p[1] >= 0 and p[0] + p[1] > 1000


def test_the_reported_point_is_checked_exactly():
    problem, x = _seven_thirds()
    x.value = np.array([5 / 3, 2 / 3])
    assert judge_lp(problem).reported_point_feasible is False  # 5/3 + 2*(2/3) rounds above 3
    x.value = np.array([1.5, 0.5])
    assert judge_lp(problem, 7 / 3).reported_point_feasible is True


def test_unsupported_forms_are_refused():
    x = cp.Variable(2)
    with pytest.raises(ei.InvalidInput, match="not affine"):
        judge_lp(cp.Problem(cp.Minimize(cp.sum_squares(x)), [x >= 1]), 1.0)
    with pytest.raises(ei.InvalidInput, match="constraint 0"):
        judge_lp(cp.Problem(cp.Minimize(cp.sum(x)), [cp.norm(x) <= 1]), 1.0)
    n = cp.Variable(2, integer=True)
    with pytest.raises(ei.InvalidInput, match="attributes"):
        judge_lp(cp.Problem(cp.Minimize(cp.sum(n)), [n >= 1]), 2.0)
    with pytest.raises(ei.InvalidInput, match="not solved"):
        judge_lp(cp.Problem(cp.Minimize(cp.sum(x)), [x >= 1]))
    with pytest.raises(ei.InvalidInput, match="cvxpy.Problem"):
        judge_lp("min x")
    with pytest.raises(ei.InvalidInput, match="claim"):
        judge_lp(cp.Problem(cp.Minimize(cp.sum(x)), [x >= 1]), 2.0, claim="upper")


def test_the_verdict_is_frozen():
    problem, _ = _seven_thirds()
    v = judge_lp(problem)
    with pytest.raises(AttributeError):
        v.status = "valid"


def test_the_float_gamma_lp_of_a_tight_box_is_exactly_infeasible():
    """A = -3/10 on the diagonal, 1/10 off it: the box is invariant with gamma* = 3/10,
    but in the floats the user's LP holds, 3 * fl(0.1) > fl(0.3): the float system
    does not keep the box invariant, its gamma LP is infeasible -- HiGHS says
    optimal within its tolerances, the judge proves infeasibility (Farkas).  The
    stated rounding limit_denominator=100 recovers the rational LP."""
    A = [[Fraction(-3, 10) if i == j else Fraction(1, 10) for j in range(4)] for i in range(4)]
    S, P = ei.LinearSystem(A), ei.Polyhedron.box([-1] * 4, [1] * 4)
    problem = _gamma_lp(S, P)
    assert problem.status == cp.OPTIMAL
    v = judge_lp(problem)
    assert v.status == "invalid" and v.counterexample["kind"] == "infeasible"
    y, data = v.counterexample["farkas"], v.data
    assert sum(bi * yi for bi, yi in zip(data["b"], y)) < 0  # the Farkas certificate, re-checked
    assert all(yi >= 0 for yi, eq in zip(y, data["equality"]) if not eq)
    ATy = [Fraction(0)] * len(data["c"])
    for row, yr in zip(data["A"], y):
        for i, a in row.items():
            ATy[i] += a * yr
    assert all(v == 0 for v in ATy)  # every column is free
    w = judge_lp(problem, limit_denominator=100)
    assert w.status == "tight" and w.exact == ei.optimal_gamma(S, P).value == Fraction(3, 10)
