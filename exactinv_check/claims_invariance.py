"""Claims about invariance and gamma* (paper, Section 2).

* continuous_invariance: P is invariant for x' = Ax iff some H with
  nonnegative off-diagonal entries has HG = GA and Hb <= 0; otherwise a point
  x on a facet j with g_j.Ax > 0 leaves P.
* discrete_invariance: A_d P is a subset of P iff some H~ >= 0 has
  H~G = GA_d and H~b <= b; otherwise x in P with g_j.A_d x > b_j.
* gamma_star = min{gamma : H + gamma I >= 0, HG = GA, Hb <= 0}: a feasible H
  bounds it from above, the LP dual of its binding row from below.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from .budget import fraction_products_cost, within_budget
from .conditions import method_matrix_at
from .failure import require
from .format import INFINITY, NEG_INFINITY
from .rationals import describe, dot, integer, matmul, matrix, matvec, rational, transpose, vector
from .reals import Real
from .sparse import diagonal, read_square, row_dot


def read_H(problem: Any, claim: Any, key: str, what: str) -> Any:
    """The m x m matrix ``claim[key]`` as sparse rows (:mod:`.sparse`): the certificate's version decides
    the encoding (version 3: only the nonzero entries, by row; versions 1 and 2: dense)."""
    return read_square(claim[key], what, problem.m, problem.version)


def check_H(problem: Any, rows: Any) -> None:
    """H (sparse rows, :mod:`.sparse`) is an invariance certificate: off-diagonal >= 0, HG = GA,
    Hb <= 0 -- over the nonzero entries of each row of H only (a row LP's basic solution has at
    most n + 1 of its m)."""
    A, G, b, n = problem.A, problem.G, problem.b, problem.n
    # priced before any product: GA (m n^2) and the nonzero entries of H times G (each a Fraction product of
    # the numbers' sizes) -- a dense n x n problem per claim (or per vertex of a robust hull) is not free
    bits = max([1] + [x.numerator.bit_length() + x.denominator.bit_length()
                      for M in (A, G, [b]) for r in M for x in r if x]
               + [x.numerator.bit_length() + x.denominator.bit_length() for row in rows for _, x in row])
    within_budget(fraction_products_cost(len(G) * n * n + sum(map(len, rows)) * (n + 1), bits),
                  f"HG = GA for a {len(G)} x {len(G)} H in dimension {n}")
    require([[sum(x * G[k][c] for k, x in row) for c in range(n)] for row in rows] == matmul(G, A), "HG != GA")
    require(all(sum(x * b[k] for k, x in row) <= 0 for row in rows), "Hb <= 0 fails")
    require(all(x >= 0 for i, row in enumerate(rows) for k, x in row if k != i), "an off-diagonal entry of H is negative")


def facet_witness(problem: Any, M: Any, w: Any, on_facet: Any) -> Any:
    """x in P, facet j and g_j.Mx; checks the recorded value and (optionally) that x is on facet j."""
    require(isinstance(w, dict) and set(w) <= {"x", "facet", "value"} and {"x", "facet"} <= set(w),
            "a witness has the keys x, facet (and value)")
    x = vector(w["x"], "witness x", problem.n)
    j = integer(w["facet"], "witness facet", 0, problem.m)
    require(all(v <= beta for v, beta in zip(matvec(problem.G, x), problem.b)), "witness x is not in P")
    if on_facet:
        require(dot(problem.G[j], x) == problem.b[j], "witness x is not on facet j")
    value = dot(problem.G[j], matvec(M, x))
    if "value" in w:
        require(rational(w["value"], "witness value") == value, "the witness's recorded value is wrong")
    return j, value


def continuous_invariance(problem: Any, claim: Any, context: Any) -> str:
    if claim["holds"]:
        check_H(problem, read_H(problem, claim, "H", "H"))
        return "P is invariant for x' = Ax (H: off-diagonal >= 0, HG = GA, Hb <= 0)"
    j, value = facet_witness(problem, problem.A, claim.get("witness"), on_facet=True)
    require(value > 0, f"the witness does not leave P through facet {j}")
    return f"P is NOT invariant: a point of facet {j} has g_j.Ax = {describe(value)} > 0"


def discrete_matrix(problem: Any, claim: Any) -> Any:
    """A_d: r(dt A) recomputed when the claim names dt, else the matrix the claim states."""
    if "dt" in claim:
        require(problem.method is not None, "a claim with dt needs the problem's method")
        dt = rational(claim["dt"], "dt")
        require(dt >= 0, "dt must be >= 0")
        Ad = method_matrix_at(problem.A, problem.method.numerator, problem.method.denominator, dt)
        require(Ad is not None, f"r(dt A) does not exist at dt = {describe(dt)}")
        if "Ad" in claim:
            require(matrix(claim["Ad"], "Ad", problem.n, problem.n) == Ad, "Ad is not r(dt A)")
        return Ad, f"A_d = r(dt A) with dt = {describe(dt)}"
    return matrix(claim["Ad"], "Ad", problem.n, problem.n), "the matrix A_d stated in the claim"


def discrete_invariance(problem: Any, claim: Any, context: Any) -> str | None:
    Ad, what = discrete_matrix(problem, claim)
    G, b = problem.G, problem.b
    if claim["holds"]:
        rows = read_H(problem, claim, "H", "H~")
        require(all(x > 0 for row in rows for _, x in row), "H~ has a negative entry")
        n = problem.n
        bits = max([1] + [x.numerator.bit_length() + x.denominator.bit_length()
                          for M in (Ad, G, [b]) for r in M for x in r if x]
                   + [x.numerator.bit_length() + x.denominator.bit_length() for row in rows for _, x in row])
        within_budget(fraction_products_cost(len(G) * n * n + sum(map(len, rows)) * (n + 1), bits),
                      f"H~G = GA_d for a {len(G)} x {len(G)} H~ in dimension {n}")
        require([[sum(x * G[k][c] for k, x in row) for c in range(n)] for row in rows] == matmul(G, Ad), "H~G != GA_d")
        require(all(row_dot(row, b) <= beta for row, beta in zip(rows, b)), "H~b <= b fails")
        return f"A_d P is a subset of P for {what} (H~ >= 0, H~G = GA_d, H~b <= b)"
    j, value = facet_witness(problem, Ad, claim.get("witness"), on_facet=False)
    require(value > b[j], f"the witness's image does not leave P through facet {j}")
    return f"A_d P is NOT a subset of P for {what}: a point of P is mapped beyond facet {j}"


def gamma_star(problem: Any, claim: Any, context: Any) -> str | None:
    A, G, b, m, n = problem.A, problem.G, problem.b, problem.m, problem.n
    # the cheap structural test first: gamma* is rational or infinite, so an algebraic value
    # ({"poly", "interval"}) is rejected before any root isolation could prove it well defined
    require(isinstance(claim["value"], (str, int)) and not isinstance(claim["value"], bool),
            "gamma* is rational or infinite: its value is a number string, oo or -oo")
    value = Real.parse(claim["value"], "gamma* value")
    allowed = {INFINITY: {"witness"}, NEG_INFINITY: {"rows", "H"}}.get(claim["value"], {"H", "binding_row", "dual"})
    extra = set(claim) - allowed - {"type", "value", "paths"}
    require(not extra, f"keys {sorted(extra)} do not belong to gamma* = {claim['value']}")
    require(isinstance(claim.get("paths", {}), dict), "paths is an object")
    if value.inf == 1:
        j, rate = facet_witness(problem, A, claim.get("witness"), on_facet=True)
        require(rate > 0, f"the witness does not leave P through facet {j}")
        context["gamma"] = value
        return "gamma* = oo: P is not invariant (a facet point leaves P)"
    require(value.poly is None, "gamma* is rational or infinite")
    if value.inf == -1:
        rows = claim["rows"]
        require(isinstance(rows, list) and len(rows) == m, "one unbounded-row certificate per row of G is needed")
        AtG = [matvec(transpose(A), G[j]) for j in range(m)] if m else []
        for j, row in enumerate(rows):
            require(isinstance(row, dict) and set(row) == {"h", "ray"}, f"row {j}: keys h, ray")
            h, d = vector(row["h"], f"row {j} h", m), vector(row["ray"], f"row {j} ray", m)
            for vec, rhs, name in ((h, AtG[j], "h"), (d, [Fraction(0)] * n, "ray")):
                require(matvec(transpose(G), vec) == rhs, f"row {j}: G^T {name} mismatch")
                require(all(vec[k] >= 0 for k in range(m) if k != j), f"row {j}: {name} has a negative off-diagonal entry")
            require(dot(b, h) <= 0 and dot(b, d) <= 0 and d[j] > 0, f"row {j}: not a ray of increase of h_jj")
        if claim.get("H") is not None:
            H = read_H(problem, claim, "H", "H")
            check_H(problem, H)
            context["H"] = H
        context["gamma"] = value
        return "gamma* = -oo: every row LP is unbounded (a feasible point and a ray per row)"
    gamma = value.q
    H = read_H(problem, claim, "H", "H")
    check_H(problem, H)
    require(all(h + gamma >= 0 for h in diagonal(H)), "H + gamma I >= 0 fails")
    j = integer(claim["binding_row"], "binding_row", 0, m)
    dual = claim["dual"]
    require(isinstance(dual, dict) and set(dual) == {"y", "lambda"}, "dual has the keys y, lambda")
    y, lam = vector(dual["y"], "dual y", n), rational(dual["lambda"], "dual lambda")
    require(lam >= 0, "dual lambda < 0")
    for k in range(m):
        s = dot(G[k], y) + lam * b[k]
        require(s == 1 if k == j else s >= 0, f"dual constraint {k} fails")
    require(dot(matvec(transpose(A), G[j]), y) == -gamma, "the dual objective differs from -gamma")
    context["gamma"], context["H"] = value, H
    return f"gamma* = {describe(gamma)}: H attains it, the dual of row {j} proves no smaller gamma is feasible"
