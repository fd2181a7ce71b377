"""Claims about the paper's steplength thresholds (Sections 3.1-3.3).

* polynomial_threshold (Theorem 3.4, errata E3, E5, E6): with gamma = gamma*
  > 0, tau = min_i tau_i, tau_i = sup{T : f_i >= 0 on [0, T]} for
  f_i(dt) = sum_{k>=i} (-1)^(k-i) sigma_k C(k, i) gamma^(k-i) dt^k.  With
  gamma* <= 0: oo when every sigma_k >= 0, else 0 (erratum E6).
* rational_threshold (Theorem 3.12 with errata E2 and E2'): tau = the least
  of rho/gamma, z_p/alpha(H) (when alpha(H) > 0) and the first h > 0 at
  which h_r(hA) is singular; every ingredient is recomputed here.
* forward_euler_threshold (Section 3.3, Lemma 3.14): the vertex ratio tests
  over a generator system proved complete, and 1/gamma*, must agree.
"""

from __future__ import annotations

from fractions import Fraction
from math import comb, gcd
from typing import Any

from . import budget, poly_arithmetic, polys
from .budget import fraction_products_cost, within_budget
from .claims_invariance import check_H, read_H
from .conditions import method_matrices
from .failure import require
from .linalg import characteristic_polynomial, largest_real_root, strongly_connected_blocks
from .polyhedra import prove_generators
from .rationals import integer, integer_matrix, integer_rows, matrix, rational, vector
from .reals import Real, quotient
from .sparse import diagonal, row_dot
from .validset import first_end

ZERO, INF = Real.rational(0), Real(inf=1)


def f_i(sigmas: Any, gamma: Any, i: Any) -> Any:
    return poly_arithmetic.trim([Fraction(0) if k < i else (-1) ** (k - i) * sigmas[k] * comb(k, i) * gamma ** (k - i)
                       for k in range(len(sigmas))])


def _verified(context: dict[str, list[list[Any]] | Real] | dict[str, bool | Real], key: str, claim_type: str) -> Any:
    require(key in context, f"a verified {claim_type} claim must precede this one")
    return context[key]


def polynomial_threshold(problem: Any, claim: Any, context: Any) -> str | None:
    method = problem.method
    require(method is not None and method.is_polynomial, "a polynomial method is needed")
    sigmas = method.numerator
    gamma = _verified(context, "gamma", "gamma_star")
    value = Real.parse(claim["value"], "tau")
    if gamma.inf == -1 or (not gamma.inf and gamma.q <= 0):
        expected = INF if all(s >= 0 for s in sigmas) else ZERO
        require(value.compare(expected) == 0, lambda: f"gamma* <= 0 gives tau = {expected}")
        require(claim.get("f") in (None, []), "no f_i table belongs to gamma* <= 0")
        return f"tau = {expected}: gamma* <= 0 and {'every sigma_k >= 0' if expected.inf else 'a sigma_k < 0 (erratum E6)'}"
    require(gamma.inf == 0, "gamma* = oo: P is not invariant, no threshold exists")
    rows = claim["f"]
    p = len(sigmas) - 1
    require(isinstance(rows, list) and len(rows) == p + 1, f"one f_i row per i = 0..{p} is needed")
    best = None
    for i, row in enumerate(rows):
        require(isinstance(row, dict) and set(row) == {"i", "coefficients", "tau"}, f"row {i}: keys i, coefficients, tau")
        require(integer(row["i"], "f row index") == i, f"the f rows must be i = 0..{p} in order")
        f = f_i(sigmas, gamma.q, i)
        require(poly_arithmetic.trim(vector(row["coefficients"], f"f_{i}")) == f, f"f_{i} does not match sigma and gamma*")
        tau_i, _ = first_end([Fraction(1)], [f] if f else [], [])
        require(Real.parse(row["tau"], f"tau_{i}").compare(tau_i) == 0,
                lambda i=i, tau_i=tau_i: f"tau_{i} is wrong (it is {tau_i})")
        if best is None or tau_i.compare(best) < 0:
            best = tau_i
    require(value.compare(best) == 0, lambda: f"tau is not min_i tau_i = {best}")
    if claim.get("binding") is not None:
        j = integer(claim["binding"], "binding", 0, p + 1)
        tau_j, _ = first_end([Fraction(1)], [f_i(sigmas, gamma.q, j)], [])
        require(tau_j.compare(best) == 0, "the binding index does not attain the minimum")
    return f"tau = min_i tau_i over the {p + 1} recomputed f_i (Theorem 3.4)"


def singular_point(problem: Any) -> Any:
    """The first h > 0 with h_r(hA) singular (a Real), or None."""
    D, _ = method_matrices(problem.A, [Fraction(1)], problem.method.denominator)
    roots = polys.positive_roots(D) if len(D) > 1 else []
    return Real.root_in(D, *roots[0]) if roots else None


def rational_threshold(problem: Any, claim: Any, context: Any) -> str | None:
    method = problem.method
    require(method is not None and not method.is_polynomial, "a rational method is needed")
    gamma = _verified(context, "gamma", "gamma_star")
    rho = _verified(context, "rho", "absolute_monotonicity_radius")
    require(Real.parse(claim["rho"], "rho").compare(rho) == 0, "rho differs from the verified radius")
    require(gamma.inf != 1, "gamma* = oo: P is not invariant, no threshold exists")
    value = Real.parse(claim["value"], "tau")
    attained = claim["attained"]
    H = context.get("H")
    require((claim.get("H") is None) == (claim.get("gamma_H") is None), "H and gamma_H come together")
    if claim.get("H") is not None:  # another certificate H with its own gamma_H >= gamma*
        H = read_H(problem, claim, "H", "H")
        check_H(problem, H)
        gamma_H = rational(claim["gamma_H"], "gamma_H")
        require(all(h + gamma_H >= 0 for h in diagonal(H)), "H + gamma_H I >= 0 fails")
        gamma = Real.rational(gamma_H)
    if rho.is_zero():
        require(value.is_zero() and attained, "rho = 0 gives tau = 0 (attained)")
        return "tau = 0 (rho = 0)"
    candidates = []  # (bound, attained there)
    if not rho.inf and gamma.inf == 0 and gamma.q > 0:
        candidates.append((quotient(rho, gamma), context["rho_attained"]))
    pole = smallest_positive_root(method.denominator)
    _same(claim.get("pole"), pole, "z_p (the smallest positive pole)")
    singular = singular_point(problem)
    if singular is not None:
        candidates.append((singular, False))  # E2': r(hA) does not exist there
    if pole is not None and problem.m:
        require(H is not None, "the gamma_star claim carries no H: the convergence bound of erratum E2 cannot be computed")
        alpha = None
        if claim.get("alpha") is not None or _e2_may_bind(H, problem.b, pole, candidates):
            alpha = _largest_real_eigenvalue(H)
            if alpha is not None and alpha.compare(ZERO) > 0:
                candidates.append((quotient(pole, alpha), False))  # E2: the series at -rho stops converging
        _same(claim.get("alpha"), alpha, "alpha(H)")
    expected, expected_attained = INF, True
    for bound, at in candidates:
        c = bound.compare(expected)
        if c < 0:
            expected, expected_attained = bound, at
        elif c == 0:
            expected_attained = expected_attained and at
    require(value.compare(expected) == 0, lambda: f"tau is not min(rho/gamma*, z_p/alpha(H), first singular point) = {expected}")
    require(attained == expected_attained, "the attained flag is wrong")
    return ("tau = min(rho/gamma*, z_p/alpha(H), first singular h) recomputed "
            "(Theorem 3.12 with the corrections of errata E2 and E2')")


def _e2_may_bind(H: Any, b: Any, pole: Real, candidates: Any) -> bool:
    """False when a cheap exact bound shows z_p/alpha(H) cannot be the least bound.

    H is in sparse rows (exactinv_check.sparse).  Collatz-Wielandt for the nonnegative matrix H + cI: for any v > 0,
    alpha(H) <= U = max_i (Hv)_i / v_i.  With v = b when b > 0 (then Hb <= 0
    gives U <= 0: no E2 bound at all), else v = 1.  If U <= 0, or z_p/U exceeds
    another candidate, the characteristic polynomial of H is not needed."""
    v = b if all(x > 0 for x in b) else [Fraction(1)] * len(b)
    U = max(row_dot(row, v) / vi for row, vi in zip(H, v))
    if U <= 0:
        return False
    lower = quotient(pole, Real.rational(U))  # z_p/alpha(H) >= z_p/U
    return not any(lower.compare(bound) > 0 for bound, _ in candidates)


def _largest_real_eigenvalue(H: Any) -> Any:
    """alpha(H), the largest real eigenvalue of H (sparse rows, m x m), or None.

    H is block triangular after a symmetric permutation (its strongly connected components in
    topological order), so its eigenvalues are those of the diagonal blocks, and alpha(H) is the
    largest of the blocks' largest real eigenvalues: one characteristic polynomial per block.
    Each block's degree is bounded (a larger one is rejected by root isolation anyway) and its
    Hessenberg reduction priced -- about k^3 Fraction operations on H's numbers -- before its
    dense k x k copy is built.  Version 3 makes a large m with few entries cheap to write (a
    100 KB certificate with m = 2000), so no m^2 copy or m^3 reduction may run unpriced."""
    bits = max([1] + [x.numerator.bit_length() + x.denominator.bit_length() for row in H for _, x in row])
    blocks = strongly_connected_blocks(H)
    largest = max(len(block) for block in blocks)
    require(largest <= budget.MAX_DEGREE, f"H has a strongly connected block of size {largest}: its characteristic "
            f"polynomial has degree {largest}, above the kernel's bound {budget.MAX_DEGREE}: alpha(H) cannot be certified")
    within_budget(sum(fraction_products_cost(len(block) ** 3, bits) for block in blocks),
                  f"the characteristic polynomials of H's {len(blocks)} diagonal blocks (the largest {largest} x {largest})")
    alpha = None
    for block in blocks:
        where = {k: i for i, k in enumerate(block)}
        M = [[Fraction(0)] * len(block) for _ in block]
        for i, k in enumerate(block):
            for c, x in H[k]:
                if c in where:
                    M[i][where[c]] = x
        root = largest_real_root(characteristic_polynomial(M))
        if root is not None and (alpha is None or root.compare(alpha) > 0):
            alpha = root
    return alpha


def _same(recorded: Any, computed: Any, what: Any) -> None:
    """A value the claim records for information must still be the true one."""
    if recorded is not None:
        require(computed is not None and Real.parse(recorded, what).compare(computed) == 0,
                f"the recorded {what} is not {computed}")


def smallest_positive_root(p: Any) -> Any:
    roots = polys.positive_roots(p)
    return Real.root_in(p, *roots[0]) if roots else None


def _ratio_tests(problem: Any, gens: Any) -> Any:
    """min over the generator-facet pairs of eps: for a vertex x with g_j.Ax > 0,
    eps = (b_j - g_j.x)/(g_j.Ax); for a ray, -g_j.x/(g_j.Ax); for a line with g_j.Ax != 0, 0
    (None: no pair limits the step).  In integers: with A = Ai/L, x = xi/d and row j times
    its positive denominator (gi, bi), eps = (bi d - gi.xi) L / (gi.Ai xi) for a vertex, the
    same without bi d for a ray; the least is kept as a reduced fraction (num, den), den > 0,
    and compared by cross-multiplication; priced first (generators x facets, by the words of
    the numbers)."""
    L, Ai = integer_matrix(problem.A)
    rows = integer_rows(problem.G, problem.b)
    generators = [x for vectors in (gens.vertices, gens.rays, gens.lines) for x in vectors]
    words = 1 + (max([abs(x).bit_length() for row in Ai for x in row] + [1])
                 + max([sum(x.denominator.bit_length() for x in v) + max(abs(x.numerator).bit_length() for x in v)
                        for v in generators] + [1])
                 + max([abs(x).bit_length() for gi, bi in rows for x in gi + [bi]] + [1])) // 64
    n = len(problem.A)
    within_budget(len(generators) * len(rows) * (30 + (2 * n + 4) * words // 20),
                  f"the forward-Euler ratio tests of {len(generators)} generators and {len(rows)} facets")
    best = None  # (num, den), reduced: each comparison multiplies a long number by a short one
    for kind, vectors in (("vertex", gens.vertices), ("ray", gens.rays), ("line", gens.lines)):
        for x in vectors:
            d, xi = integer_matrix([x])
            xi = xi[0]
            Axi = [sum(map(int.__mul__, row, xi)) for row in Ai]
            for gi, bi in rows:
                rate = sum(map(int.__mul__, gi, Axi))
                if kind == "line":
                    if rate == 0:
                        continue
                    num, den = 0, 1
                elif rate <= 0:
                    continue
                else:
                    num, den = ((bi * d if kind == "vertex" else 0) - sum(map(int.__mul__, gi, xi))) * L, rate
                if best is None or num * best[1] < best[0] * den:
                    common = gcd(num, den)
                    best = (num // common, den // common)
    return None if best is None else Fraction(*best)


def forward_euler_threshold(problem: Any, claim: Any, context: Any) -> str | None:
    gens = prove_generators(problem.G, problem.b, *(matrix(claim[k], k, cols=problem.n) for k in ("vertices", "rays", "lines")))
    gamma = _verified(context, "gamma", "gamma_star")
    best = _ratio_tests(problem, gens)
    by_vertices = INF if best is None else Real.rational(best)
    if gamma.inf == 1:
        by_gamma = ZERO
    elif gamma.inf == -1 or gamma.q <= 0:
        by_gamma = INF
    else:
        by_gamma = Real.rational(1 / gamma.q)
    value = Real.parse(claim["value"], "tau")
    require(by_vertices.compare(by_gamma) == 0, lambda: f"the ratio tests give {by_vertices} but 1/gamma* is {by_gamma}")
    require(value.compare(by_gamma) == 0, lambda: f"the largest forward-Euler step is {by_gamma}, not {value}")
    if "attained" in claim:
        require(claim["attained"] is True, "the largest forward-Euler step is attained")
    return (f"largest forward-Euler step {value}: the ratio tests over the {len(gens.vertices)} proved vertices "
            "and 1/gamma* (Lemma 3.14) agree")
