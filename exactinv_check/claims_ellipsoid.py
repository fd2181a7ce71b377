"""Claims about an ellipsoid E = {x : x^T Q x <= 1} (the problem's Q, proved
symmetric positive definite when the problem is read).

* ellipsoid_continuous_invariance: E is invariant for x' = Ax iff
  -(A^T Q + Q A) >= 0 (recomputed by elimination); otherwise a rational v with
  v^T (A^T Q + Q A) v > 0: the boundary point v / ||v||_Q leaves E.
* ellipsoid_discrete_invariance: A_d E in E iff Q - A_d^T Q A_d >= 0;
  otherwise v with v^T (A_d^T Q A_d - Q) v > 0.
* ellipsoid_valid_steplengths / ellipsoid_largest_threshold /
  ellipsoid_forward_euler_threshold: the conditions c_k >= 0 and det h(hA)
  (:mod:`exactinv_check.ellipsoids`) are rebuilt and the valid set or its first
  interval recomputed by the same rules as for a polyhedron
  (:mod:`exactinv_check.validset`); the claim must equal it, end by end and flag by flag.
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING, Any

from . import poly_arithmetic
from .budget import FRACTION_WEIGHT, within_budget
from .claims_invariance import discrete_matrix
from .ellipsoids import condition_polynomials, psd
from .failure import require
from .rationals import boolean, describe, dot, integer, integer_matrix, matmul, matvec, rational, transpose, vector
from .reals import Real
from .validset import first_end, require_intervals, valid_set

if TYPE_CHECKING:
    from .kernel import Problem


def _witness(problem: Any, claim: Any, form: Any, what: Any) -> Any:
    """form(v) = v^T X v for the claim's rational v, compared with the recorded value, > 0."""
    w = claim.get("witness")
    require(isinstance(w, dict) and set(w) <= {"v", "value"} and "v" in w, "a witness has the keys v (and value)")
    v = vector(w["v"], "witness v", problem.n)
    value = form(v)
    if "value" in w:
        require(rational(w["value"], "witness value") == value, "the witness's recorded value is wrong")
    require(value > 0, f"the witness does not show {what}")
    return value


def _integer_product(X: Any, Y: Any, what: str) -> Any:
    """(x, y, X_i Y_i) with X = X_i/x, Y = Y_i/y, X_i and Y_i integral, priced first."""
    (x, Xi), (y, Yi) = integer_matrix(X), integer_matrix(Y)
    n = len(X)
    bits = max((abs(c).bit_length() for M in (Xi, Yi) for row in M for c in row), default=0)
    within_budget(n ** 3 * (1 + (2 * bits + n.bit_length()) // 64), f"{what} of {n} x {n} matrices")
    return x, y, matmul(Xi, Yi)


def continuous_invariance(problem: Any, claim: Any, context: Any) -> str | None:
    """-(A^T Q + Q A) >= 0, decided on beta alpha (A^T Q + Q A) = (Q_i A_i)^T + Q_i A_i (a
    positive multiple, integral); or a v with v^T (A^T Q + Q A) v = 2 v^T Q A v > 0."""
    A, Q = problem.A, problem.Q
    if boolean(claim["holds"], "holds"):
        require("witness" not in claim, "a claim that holds carries no witness")
        _, _, QA = _integer_product(Q, A, "the product Q A")
        n = problem.n
        require(psd([[-(QA[i][j] + QA[j][i]) for j in range(n)] for i in range(n)])[0],
                "A^T Q + Q A is not negative semidefinite")
        return "E is invariant for x' = Ax: -(A^T Q + Q A) >= 0 (exact elimination)"
    value = _witness(problem, claim, lambda v: 2 * dot(v, matvec(Q, matvec(A, v))), "v^T (A^T Q + Q A) v > 0")
    return f"E is NOT invariant: v^T (A^T Q + Q A) v = {describe(value)} > 0, so v/||v||_Q leaves E"


def _price_step(problem: Problem, claim: dict[str, list[list[Any]] | bool | str]) -> None:
    """Reject before recomputing r(dt A) in Fractions when that is over the work budget."""
    if "dt" in claim and problem.method is not None:
        n, g, h = problem.n, problem.method.numerator, problem.method.denominator
        steps = len(g) if len(h) == 1 else (n * (len(h) - 1) + 1) * (len(g) + len(h) + 2)
        within_budget(FRACTION_WEIGHT * n ** 3 * steps, f"r(dt A) for a {n} x {n} matrix A")


def discrete_invariance(problem: Any, claim: Any, context: Any) -> str | None:
    """Q - A_d^T Q A_d >= 0, decided on beta delta^2 (Q - A_d^T Q A_d) = delta^2 Q_i - N^T Q_i N
    (A_d = N/delta, Q = Q_i/beta integral); or v with (A_d v)^T Q (A_d v) - v^T Q v > 0."""
    _price_step(problem, claim)
    Ad, what = discrete_matrix(problem, claim)
    Q = problem.Q
    if boolean(claim["holds"], "holds"):
        require("witness" not in claim, "a claim that holds carries no witness")
        beta, delta, QN = _integer_product(Q, Ad, "the product Q A_d")
        _, N = integer_matrix(Ad)
        _, _, NtQN = _integer_product(transpose(N), QN, "the product A_d^T Q A_d")
        Qi = integer_matrix(Q)[1]
        M = [[delta * delta * q - x for q, x in zip(r, s)] for r, s in zip(Qi, NtQN)]
        require(psd(M)[0], "Q - A_d^T Q A_d is not positive semidefinite")
        return f"A_d E is a subset of E for {what} (Q - A_d^T Q A_d >= 0)"

    def form(v: Any) -> Any:
        w = matvec(Ad, v)
        return dot(w, matvec(Q, w)) - dot(v, matvec(Q, v))
    value = _witness(problem, claim, form, "v^T (A_d^T Q A_d - Q) v > 0")
    return f"A_d E is NOT a subset of E for {what}: v^T (A_d^T Q A_d - Q) v = {describe(value)} > 0"


def _conditions(problem: Any, claim: Any, context: Any, numerator: Any = None, denominator: Any = None) -> Any:
    """(D, conditions), rebuilt once per certificate and method (kept in the context)."""
    if numerator is None:
        require(problem.method is not None, "a method is needed")
        numerator, denominator = problem.method.numerator, problem.method.denominator
    key = ("ellipsoid conditions", tuple(numerator), tuple(denominator))
    if key not in context:
        context[key] = condition_polynomials(problem.A, problem.Q, numerator, denominator)
    D, full = context[key]
    conditions = [c for c in full if c]
    if claim.get("determinant") is not None:
        claimed = poly_arithmetic.trim(vector(claim["determinant"], "determinant"))
        require(poly_arithmetic.primitive(claimed) == poly_arithmetic.primitive(D), "det h(dt A) does not match")
    return D, conditions, full


def valid_steplengths(problem: Any, claim: Any, context: Any) -> str | None:
    D, conditions, _ = _conditions(problem, claim, context)
    truth = valid_set(D, conditions, [], conditions[:1])  # c_1 (the trace) first: exact pruning
    require_intervals(claim["intervals"], truth)
    return (f"the valid set {truth} on E recomputed from {len(conditions)} coefficient conditions of "
            f"H^T Q H - G^T Q G and det h(hA)")


def largest_threshold(problem: Any, claim: Any, context: Any) -> str | None:
    D, conditions, full = _conditions(problem, claim, context)
    tau, attained = first_end(D, conditions, [], conditions[:1])
    value = Real.parse(claim["value"], "tau")
    require(value.compare(tau) == 0, f"the largest threshold on E is {tau}, not {value}")
    require(boolean(claim["attained"], "attained") == attained, "the attained flag is wrong")
    binding = claim.get("binding")
    if binding is not None:
        k = integer(binding, "binding", 1, problem.n + 1)
        require(full[k - 1], f"condition {k} vanishes identically")
        end, _ = first_end([Fraction(1)], [full[k - 1]], [])
        require(end.compare(tau) == 0, f"condition {k} does not end the first interval")
    return f"largest threshold on E {value} ({'attained' if attained else 'not attained'}), recomputed"


def forward_euler_threshold(problem: Any, claim: Any, context: Any) -> str | None:
    D, conditions, _ = _conditions(problem, {}, context, [Fraction(1), Fraction(1)], [Fraction(1)])
    tau, _ = first_end(D, conditions, [])
    value = Real.parse(claim["value"], "tau")
    require(value.compare(tau) == 0, f"the largest forward-Euler step on E is {tau}, not {value}")
    return f"largest forward-Euler step on E {value}, recomputed (r(z) = 1 + z)"
