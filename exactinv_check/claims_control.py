"""Claims about control (issue 25; docs/design.md, "Control").

* optimal_gain: the LP  max -gamma  over (H, F, gamma, Lambda) with
  HG = G(A + BF), Hb <= 0, H off-diagonal >= 0, H_ii + gamma >= 0, and (with
  inputs U = {u : Eu <= e}) Lambda >= 0, Lambda G = EF, Lambda b <= e.  The
  primal (H, F, Lambda) proves gamma*(A + BF) <= gamma for this F; the dual
  (Y, mu, nu, Z, w) proves gamma*(A + BF') >= gamma for EVERY gain F' (LP weak
  duality, the dual's constraints written out below).  holds = false: a Farkas
  vector (the dual with nu = 0 and a negative objective) proves that no gain
  makes P invariant.  Both carry a point x of P: on an empty P every gain keeps
  P invariant and "Fx in U on P" is vacuous, so neither LP statement would mean
  what the claim says.
* robust_threshold: a point x of P (P nonempty: 1/gamma is the largest robust
  forward-Euler step only then); each vertex A_i of the hull gets a full gamma_star check
  (H_i and the dual of its binding row); gamma = max_i gamma_i; the method's
  radius rho comes from a verified absolute_monotonicity_radius claim; the
  threshold is recomputed: rho/gamma (polynomial), min(rho/gamma, z_p/beta)
  (rational, P without lines, beta = max_i max_r (H_i v)_r / v_r recomputed).
"""

from __future__ import annotations

from fractions import Fraction
from typing import TYPE_CHECKING, Any, Sequence

from . import claims_invariance
from .budget import GAIN_WORK_BUDGET, charge, fraction_products_cost, within_budget
from .claims_thresholds import INF, ZERO, smallest_positive_root
from .failure import Record, require
from .rationals import describe, dot, matrix, matvec, rational, vector
from .reals import Real, quotient
from .sparse import diagonal, row_dot

if TYPE_CHECKING:
    from .kernel import Problem



def _bits(*arrays: Any) -> int:
    """The largest numerator plus denominator bits over the entries (matrices or vectors)."""
    out = 1
    for M in arrays:
        for row in M:
            for x in (row if isinstance(row, list) else [row]):
                out = max(out, x.numerator.bit_length() + x.denominator.bit_length())
    return out


def _price_gain(problem: Problem, count: int, *arrays: Any) -> None:
    """The gain LP's rows are ``count`` Fraction products and sums of the problem's and the record's numbers:
    priced (by their sizes) and charged before any of them is formed, so a large record is rejected, not run."""
    within_budget(fraction_products_cost(count, _bits(problem.A, problem.B, problem.G, [problem.b], problem.E,
                                                      [problem.e], *arrays)),
                  "the gain LP's rows (dense Fraction products)", GAIN_WORK_BUDGET)


def _matmul(X: Any, Y: Any) -> Any:
    """X Y, one row at a time; each row is a charge of nothing (a tick of the account's clock)."""
    cols = list(zip(*Y))
    out = []
    for row in X:
        charge(0, "a product of the gain LP's matrices")
        out.append([sum(a * b for a, b in zip(row, col)) for col in cols])
    return out


def _dual(record: Any, m: Any, n: Any, q: Any, what: Any) -> Any:
    require(isinstance(record, dict) and set(record) == {"Y", "mu", "nu", "Z", "w"},
            f"{what} has the keys Y, mu, nu, Z, w")
    return (matrix(record["Y"], f"{what} Y", m, n), vector(record["mu"], f"{what} mu", m),
            vector(record["nu"], f"{what} nu", m), matrix(record["Z"], f"{what} Z", q, n), vector(record["w"], f"{what} w", q))


def _dual_rows(problem: Any, Y: Any, mu: Any, nu: Any, Z: Any, w: Any) -> Any:
    """The dual's constraints, one per primal variable; returns the dual objective <GA, Y> + e.w."""
    G, b, m, n, q = problem.G, problem.b, problem.m, problem.n, len(problem.E)
    require(all(x >= 0 for x in mu) and all(x >= 0 for x in nu) and all(x >= 0 for x in w), "mu, nu, w must be >= 0")
    YGt = []
    for i in range(m):
        charge(0, "the dual's rows")  # a tick of the account's clock (the work is priced by the caller)
        YGt.append([dot(Y[i], G[j]) for j in range(m)])
    for i in range(m):
        for j in range(m):
            s = YGt[i][j] + mu[i] * b[j]
            require(s == nu[i] if i == j else s >= 0, f"dual constraint of H[{i}][{j}] fails")
    GB = _matmul(G, problem.B)
    for k in range(problem.p):
        for c in range(n):
            s = sum(GB[i][k] * Y[i][c] for i in range(m)) + sum(problem.E[j][k] * Z[j][c] for j in range(q))
            require(s == 0, f"dual constraint of F[{k}][{c}] fails ((GB)^T Y + E^T Z != 0)")
    for j in range(q):
        for k in range(m):
            require(dot(Z[j], G[k]) + w[j] * b[k] >= 0, f"dual constraint of Lambda[{j}][{k}] fails")
    GA = _matmul(G, problem.A)
    return sum(dot(GA[i], Y[i]) for i in range(m)) + dot(problem.e, w)


def optimal_gain(problem: Any, claim: Any, context: Any) -> str:
    require(problem.B is not None, "an optimal_gain claim needs B in the problem")
    A, B, G, b, m, n, p = problem.A, problem.B, problem.G, problem.b, problem.m, problem.n, problem.p
    E, e, q = problem.E, problem.e, len(problem.E)
    within_budget((m + q) * (m + p) * n + n * n * p, f"the gain LP's rows ({m} x {m} H, {p} x {n} F, {q} x {m} Lambda)")
    # the dual's rows: <Y, G> (m^2 n), GB (m n p), the F rows ((m + q) p n), Z G (q m n), GA (m n^2); the primal's:
    # HG (m^2 n), G(A + BF) (m n^2 + n^2 p), Lambda G (q m n)
    count = 2 * (m + q) * m * n + 2 * m * n * n + 2 * (m + q) * p * n + 2 * n * n * p
    value = Real.parse(claim["value"], "gamma")
    keys = set(claim) - {"type", "holds", "value", "x"}
    # P must be nonempty, proved by a point x: on an empty P every gain keeps P invariant and "Fx in U on P" holds
    # vacuously, yet the gain LP can be infeasible (a Farkas vector) or its Lambda rows can exclude gains (a false
    # optimum): both were accepted (tests/kernel/test_claims_control.py).  With P nonempty, Lambda >= 0,
    # Lambda G = EF, Lambda b <= e is exactly "Fx in U for every x in P" (affine Farkas lemma).
    require("x" in claim, "an optimal_gain claim carries x, a point of P (P nonempty)")
    x = vector(claim["x"], "x (a point of P)", n)
    within_budget(fraction_products_cost(m * n, _bits(G, [b], [x])), "Gx <= b")
    require(all(v <= beta for v, beta in zip(matvec(G, x), b)), "x is not in P (P must be nonempty)")
    if not claim["holds"]:
        require(keys == {"farkas"} and value.inf == 1, "holds = false carries value oo and a farkas certificate only")
        Y, mu, nu, Z, w = _dual(claim["farkas"], m, n, q, "farkas")
        _price_gain(problem, count, Y, [mu], [nu], Z, [w])
        require(all(x == 0 for x in nu), "a Farkas certificate has nu = 0 (the cost of gamma is 0)")
        objective = _dual_rows(problem, Y, mu, nu, Z, w)
        require(objective < 0, "the Farkas certificate's objective <GA, Y> + e.w is not negative")
        return ("no linear gain u = Fx makes P invariant" + (" with u in U" if q else "")
                + ": a Farkas certificate of the gain LP (every constraint recomputed)")
    require(keys == {"F", "H", "Lambda", "dual"}, "holds = true carries F, H, Lambda, dual")
    require(value.inf == 0 and value.poly is None, "the optimal gamma is rational")
    gamma = value.q
    F = matrix(claim["F"], "F", p, n)
    H = matrix(claim["H"], "H", m, m)
    Lam = matrix(claim["Lambda"], "Lambda", q, m)
    Y, mu, nu, Z, w = _dual(claim["dual"], m, n, q, "dual")
    _price_gain(problem, count, F, H, Lam, Y, [mu], [nu], Z, [w])
    closed = [[A[i][c] + sum(B[i][k] * F[k][c] for k in range(p)) for c in range(n)] for i in range(n)]
    require(_matmul(H, G) == _matmul(G, closed), "HG != G(A + BF)")
    require(all(v <= 0 for v in matvec(H, b)), "Hb <= 0 fails")
    require(all(H[i][j] >= 0 for i in range(m) for j in range(m) if i != j), "an off-diagonal entry of H is negative")
    require(all(H[i][i] + gamma >= 0 for i in range(m)), "H + gamma I >= 0 fails")
    require(all(v >= 0 for r in Lam for v in r), "Lambda has a negative entry")
    require(all(dot(Lam[j], [G[k][c] for k in range(m)]) == sum(E[j][k] * F[k][c] for k in range(p))
                for j in range(q) for c in range(n)), "Lambda G != EF")
    require(all(dot(Lam[j], b) <= e[j] for j in range(q)), "Lambda b <= e fails")
    require(sum(nu) == 1, "the dual's nu must sum to 1 (the cost of gamma)")
    objective = _dual_rows(problem, Y, mu, nu, Z, w)
    require(-objective == gamma, f"the dual objective gives gamma >= {describe(-objective)}, not {describe(gamma)}")
    context["gain"] = (F, gamma)
    return (f"gain F: gamma*(A + BF) <= {describe(gamma)} (H" + (", Lambda: u in U" if q else "")
            + f"), and the LP dual proves gamma*(A + BF') >= {describe(gamma)} for every gain F'"
            + (" with u in U" if q else ""))


class _Vertex:
    """The problem seen from one vertex A_i of the hull (for the gamma_star check)."""

    def __init__(self, problem: Problem, A: Sequence[list[Fraction]]) -> None:
        self.A, self.G, self.b, self.m, self.n, self.method = A, problem.G, problem.b, problem.m, problem.n, problem.method
        self.version = problem.version


def robust_threshold(problem: Any, claim: Any, context: Any) -> str | None:
    method = problem.method
    require(method is not None, "a robust_threshold claim needs the problem's method")
    rho = context.get("rho")
    require(rho is not None, "a verified absolute_monotonicity_radius claim must precede this one")
    require(Real.parse(claim["rho"], "rho").compare(rho) == 0, "rho differs from the verified radius")
    # forward_euler = 1/gamma is the LARGEST robust step only on a nonempty P (an empty P keeps every step, yet its
    # gamma* LP can be finite: tests/kernel/test_claims_control.py); a point of P proves it nonempty
    x = vector(claim["x"], "x (a point of P)", problem.n)
    within_budget(fraction_products_cost(problem.m * problem.n, _bits(problem.G, [problem.b], [x])), "Gx <= b")
    require(all(v <= beta for v, beta in zip(matvec(problem.G, x), problem.b)), "x is not in P (P must be nonempty)")
    records = claim["vertices"]
    require(isinstance(records, list) and len(records) == len(problem.hull), "one gamma* record per vertex of the hull")
    gammas, Hs = [], []
    for i, (A, record) in enumerate(zip(problem.hull, records)):
        require(isinstance(record, dict) and "type" not in record, f"vertex {i}: a gamma* record without type")
        allowed = {"value", "H", "binding_row", "dual", "rows"}
        require(set(record) <= allowed and "value" in record, f"vertex {i}: keys {sorted(allowed)}")
        ctx: dict[str, Any] = {}
        claims_invariance.gamma_star(_Vertex(problem, A), Record(record, type="gamma_star"), ctx)
        require(ctx["gamma"].inf != 1, f"vertex {i}: P is not invariant, no robust threshold exists")
        gammas.append(ctx["gamma"])
        Hs.append(ctx.get("H"))
    gamma = gammas[0]
    for g in gammas[1:]:
        if g.compare(gamma) > 0:
            gamma = g
    require(Real.parse(claim["gamma"], "gamma").compare(gamma) == 0, f"gamma is not max_i gamma_i = {gamma}")
    positive = gamma.inf == 0 and gamma.q > 0
    fe = Real.rational(1 / gamma.q) if positive else INF
    require(Real.parse(claim["forward_euler"], "forward_euler").compare(fe) == 0,
            f"the largest robust forward-Euler step is 1/gamma = {fe}")
    value = Real.parse(claim["value"], "tau")
    attained = claim["attained"]
    has_beta = "beta" in claim or "v" in claim
    if method.is_polynomial:
        require(not has_beta, "beta and v belong to rational methods only")
        if positive and rho.inf:
            expected, at = INF, True
        elif positive:
            expected, at = quotient(rho, gamma), context["rho_attained"]
        else:
            expected, at = (INF if all(s >= 0 for s in method.numerator) else ZERO), True
        require(value.compare(expected) == 0 and attained == at, f"tau is rho/gamma = {expected} (attained {at})")
        return (f"tau = {expected}: every A in the hull has H = sum lambda_i H_i with H + gamma I >= 0, "
                f"gamma = max of the {len(gammas)} verified gamma_i (docs/design.md)")
    require(not problem.lines_possible, "a rational method needs P without lines (checked: G has full column rank)")
    if rho.is_zero():
        require(value.is_zero() and attained, "rho = 0 gives tau = 0 (attained)")
        return "tau = 0 (rho = 0)"
    candidates = []
    if positive and not rho.inf:
        candidates.append((quotient(rho, gamma), context["rho_attained"]))
    pole = smallest_positive_root(method.denominator)
    if pole is not None and problem.m:
        require(all(H is not None for H in Hs), "every vertex needs its H for the hull-wide abscissa bound")
        # beta bounds Re lambda only; r(hA) exists (and the series at -kappa converges) because the spectral
        # radius of hH + kappa I >= 0 is h alpha(H) + kappa < z_p + kappa, which needs H + gamma I >= 0 for the
        # SAME H = sum lambda_i H_i (kappa = h max(gamma, 0) <= rho).  A gamma* = -oo record's H is not tied to
        # gamma: without this test an H with Re lambda <= 0 but a complex eigenvalue on a pole's ray passed
        # (tests/kernel/test_lp_pieces.py, r(hA) singular at h = 1 under a claimed tau = oo).
        floor = gamma.q if positive else 0
        require(all(h + floor >= 0 for H in Hs for h in diagonal(H)),
                f"a vertex's H has H + {describe(floor)} I >= 0 failing: its abscissa bound beta does not "
                "bound the spectral radius the rational method's series needs")
        v = vector(claim["v"], "v", problem.m)
        require(all(x > 0 for x in v), "v must be positive")
        beta = max(row_dot(row, v) / vr for H in Hs for row, vr in zip(H, v))  # type: ignore[arg-type]
        require(rational(claim["beta"], "beta") == beta, f"beta is max_i max_r (H_i v)_r / v_r = {describe(beta)}")
        if beta > 0:
            candidates.append((quotient(pole, Real.rational(beta)), False))
    else:
        require(not has_beta, "no pole: beta and v do not belong here")
    expected, expected_at = INF, True
    for bound, at in candidates:
        c = bound.compare(expected)
        if c < 0:
            expected, expected_at = bound, at
        elif c == 0:
            expected_at = expected_at and at
    require(value.compare(expected) == 0, f"tau is not min(rho/gamma, z_p/beta) = {expected}")
    require(attained == expected_at, "the attained flag is wrong")
    return (f"tau = {expected} = min(rho/gamma, z_p/beta) over the whole hull (beta bounds the spectral abscissa of "
            "every sum lambda_i H_i; P has no lines, so r(hA) exists; docs/design.md)")
