"""exactinv_check.claims_control, attacked: the control claims (issue 25): optimal_gain and robust_threshold.

Findings (each a test that failed before its fix):

* an optimal_gain claim with ``holds: false`` on an EMPTY P was accepted: the gain LP of an empty P can be
  infeasible (HG = G(A + BF) has no solution when a row of G(A + BF) leaves the row space of G), so a
  genuine Farkas vector exists, yet every gain leaves an empty P invariant -- the kernel's verdict "no
  linear gain makes P invariant" was false.  Likewise ``holds: true``: on an empty P the Lambda rows
  restrict F although "Fx in U on P" is vacuous, so an LP optimum 0 was accepted where a gain reaches
  gamma* = -5.  Now the claim carries a point x of P.
* a robust_threshold claim on an EMPTY P was accepted with ``forward_euler`` = 1/gamma finite, stated as the
  largest robust forward-Euler step, though an empty P keeps every step (its gamma* LP can be finite).  Now
  the claim carries a point x of P.
* the robust problem's rank test (P without lines, for rational methods) ran a Fraction Gauss-Jordan
  elimination of G uncharged, so neither the work budget nor the clock could stop it: a 640 KB certificate
  (G 400 x 200, digits -9..9) ran for minutes of CPU before the first claim.  Now a fraction-free
  elimination charged per row operation (exactinv_check.cones.integer_rank).

Then a mutation fuzzer: genuine certificates of the engine (random gain problems with and without inputs,
feasible and infeasible; random hulls with polynomial and rational methods), one field changed at a time;
every mutant the kernel accepts must still be TRUE by an independent check written here: for a gain, the
primal (H, F, Lambda) and the dual checked by this file's own code, P nonempty, and the value equal to the
genuine optimum when the problem is unchanged; for a hull, sampling -- random lambda in the simplex, random
h <= tau, A_d(h) = r(hA) computed here with flint, D(hA) nonsingular, A_d(h) mapping every generator of P
(from ppl) into P exactly; the forward-Euler step checked at 1/gamma and just above it.
"""


import copy
import random
from fractions import Fraction

import flint
import pytest

import exactinv as ei
import exactinv_check
from exactinv_check import budget
from exactinv_check.cones import integer_rank
from exactinv_check.failure import CheckFailure
from exactinv_check.kernel import Problem
from exactinv_check.rationals import rank_and_nullspace

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


_EMPTY_P = {"A": [["0", "1"], ["0", "0"]], "B": [["0"], ["1"]], "G": [["1", "0"], ["-1", "0"]], "b": ["-1", "-1"]}


# P = {x1 <= -1, -x1 <= -1} is empty (x1 <= -1 and x1 >= 1), so every gain leaves it invariant.  The Farkas
# vector is genuine: the first row of G(A + BF) is (0, 1) for every F (B's first row is 0), outside the row
# space {(t, 0)} of G, so HG = G(A + BF) has no solution; Y = [[0, -1], [0, 0]] gives <GA, Y> = -1 < 0 with
# YG^T = 0 and (GB)^T Y = 0.
_EMPTY_FARKAS = {"Y": [["0", "-1"], ["0", "0"]], "mu": ["0", "0"], "nu": ["0", "0"], "Z": [], "w": []}


def _gain_cert(problem, claim):
    return {"format": "exactinv-certificate", "version": 2, "problem": problem, "claims": [claim]}


# P = {x1 <= -1, -x1 <= -1, x2 <= 1} is empty; U = {u : -u <= 1}.  Lambda G = EF needs EF = (-f1, -f2) in the
# cone of G's rows {(s, t) : t >= 0}, so the LP admits only f2 <= 0, and its optimum is gamma = 0 (F = 0).  But
# on an empty P "Fx in U for every x in P" holds for EVERY F, and F' = (0, 5) has gamma*(A + BF') = -5.
_EMPTY_P3 = {"A": [["0", "0"], ["0", "0"]], "B": [["0"], ["1"]], "G": [["1", "0"], ["-1", "0"], ["0", "1"]],
             "b": ["-1", "-1", "1"], "inputs": {"E": [["-1"]], "e": ["1"]}}


_EMPTY_P3_CLAIM = {"type": "optimal_gain", "holds": True, "value": "0", "F": [["0", "0"]], "H": [["0"] * 3] * 3,
                   "Lambda": [["0", "0", "0"]],
                   "dual": {"Y": [["0", "0"], ["0", "0"], ["0", "1"]], "mu": ["0", "0", "0"], "nu": ["0", "0", "1"],
                            "Z": [["0", "1"]], "w": ["0"]}}


_FE_RADIUS = {"type": "absolute_monotonicity_radius", "value": "1", "reason": "coefficient", "attained": True,
              "binding": 0, "d": [["1", "-1"], ["1"]]}


def _empty_robust(x=None):
    """P = {x1 <= -1, -x1 <= -1, x2 <= 5} is empty (rows 0 and 1), so every step keeps it: the largest robust
    forward-Euler step is oo.  Yet gamma* of A = diag(0, -1) is 1 by a genuine H and dual: rows 0 and 1 of H
    are free to grow (1, 1, 0), row 2 is h_3 = (a, a, -1) with h_33 = -1 fixed by h_3 G = g_3 A = (0, -1); the
    dual of row 2 is y = (0, 1), lambda = 0 (g_k y + lambda b_k = 0, 0, 1), and (A^T g_3) . y = -1."""
    claim = {"type": "robust_threshold", "value": "1", "attained": True, "gamma": "1", "rho": "1",
             "forward_euler": "1",
             "vertices": [{"value": "1", "H": [["1", "1", "0"], ["1", "1", "0"], ["0", "0", "-1"]], "binding_row": 2,
                           "dual": {"y": ["0", "1"], "lambda": "0"}}]}
    if x is not None:
        claim["x"] = x
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"hull": [[["0", "0"], ["0", "-1"]]], "G": [["1", "0"], ["-1", "0"], ["0", "1"]],
                        "b": ["-1", "-1", "5"], "method": {"name": "forward_euler", "numerator": ["1", "1"],
                                                          "denominator": ["1"]}},
            "claims": [_FE_RADIUS, claim]}


def _hull_record(G):
    n = len(G[0])
    return {"hull": [[["0"] * n for _ in range(n)]], "G": [[str(v) for v in r] for r in G], "b": ["1"] * len(G),
            "method": {"name": "backward_euler", "numerator": ["1"], "denominator": ["1", "-1"]}}


def _q(x):
    return Fraction(x)


def _mat(M):
    return [[_q(v) for v in r] for r in M]


def _mm(X, Y):
    return [[sum(a * b for a, b in zip(r, c)) for c in zip(*Y)] for r in X] if Y else [[] for _ in X]


def _points_rays_lines(G, b):
    """P's generators from ppl (the engine's polyhedron), or None if P is empty."""
    P = ei.Polyhedron(G, b)
    if P.is_empty:
        return None
    return P.vertices, P.rays, P.lines


def _gain_claim_is_true(problem, claim, genuine_value):
    """Independent: the primal proves gamma*(A + BF) <= gamma with Fx in U on P; the dual (weak duality,
    written out here) proves that no admissible gain does better; P nonempty (ppl); and on the unchanged
    problem the value is the genuine optimum."""
    try:
        A, B, G, b = _mat(problem["A"]), _mat(problem["B"]), _mat(problem["G"]), [_q(v) for v in problem["b"]]
        E = _mat(problem["inputs"]["E"]) if "inputs" in problem else []
        e = [_q(v) for v in problem["inputs"]["e"]] if "inputs" in problem else []
    except Exception:  # a problem the kernel accepted but that is no problem: a defect by itself
        return False
    m, n, p, q = len(G), len(A), len(B[0]), len(E)
    if _points_rays_lines(G, b) is None:
        return False
    if claim["value"] == "oo":
        d = claim["farkas"]
        Y, mu, nu, Z, w = _mat(d["Y"]), [_q(v) for v in d["mu"]], [_q(v) for v in d["nu"]], _mat(d["Z"]), [_q(v) for v in d["w"]]
        if any(nu) or min(mu + w, default=0) < 0:
            return False
        gamma = None
    else:
        gamma = _q(claim["value"])
        F, H, Lam = _mat(claim["F"]), _mat(claim["H"]), _mat(claim["Lambda"])
        closed = [[A[i][j] + sum(B[i][k] * F[k][j] for k in range(p)) for j in range(n)] for i in range(n)]
        if _mm(H, G) != _mm(G, closed) or any(sum(H[i][k] * b[k] for k in range(m)) > 0 for i in range(m)):
            return False
        if any(H[i][k] < 0 for i in range(m) for k in range(m) if i != k) or any(H[i][i] + gamma < 0 for i in range(m)):
            return False
        if any(v < 0 for r in Lam for v in r) or (q and _mm(Lam, G) != _mm(E, F)):
            return False
        if any(sum(Lam[j][k] * b[k] for k in range(m)) > e[j] for j in range(q)):
            return False
        d = claim["dual"]
        Y, mu, nu, Z, w = _mat(d["Y"]), [_q(v) for v in d["mu"]], [_q(v) for v in d["nu"]], _mat(d["Z"]), [_q(v) for v in d["w"]]
        if sum(nu) != 1 or min(mu + nu + w) < 0:
            return False
    YGt, ZGt, GB, GA = _mm(Y, list(zip(*G))), _mm(Z, list(zip(*G))) if q else [], _mm(G, B), _mm(G, A)
    for i in range(m):
        for j in range(m):
            s = YGt[i][j] + mu[i] * b[j]
            if (i == j and s != nu[i]) or (i != j and s < 0):
                return False
    for k in range(p):
        for c in range(n):
            if sum(GB[i][k] * Y[i][c] for i in range(m)) + sum(E[j][k] * Z[j][c] for j in range(q)) != 0:
                return False
    if any(ZGt[j][k] + w[j] * b[k] < 0 for j in range(q) for k in range(m)):
        return False
    objective = sum(GA[i][c] * Y[i][c] for i in range(m) for c in range(n)) + sum(x * y for x, y in zip(e, w))
    if gamma is None:
        return objective < 0 and genuine_value in (None, "oo")
    return -objective == gamma and (genuine_value is None or genuine_value != "oo" and _q(genuine_value) == gamma)


def _r_of(method, A, h):
    """r(hA) = h(hA)^-1 g(hA) with flint, or None if h(hA) is singular."""
    n = A.nrows()
    M = A * flint.fmpq(h.numerator, h.denominator)

    def poly(coeffs):
        out, power = flint.fmpq_mat(n, n), flint.fmpq_mat([[int(i == j) for j in range(n)] for i in range(n)])
        for c in coeffs:
            c = Fraction(c)
            out = out + power * flint.fmpq(c.numerator, c.denominator)
            power = power * M
        return out

    D = poly(method.denominator)
    if D.det() == 0:
        return None
    return D.solve(poly(method.numerator))


def _maps_P_into_P(Ad, G, b, gens):
    points, rays, lines = gens
    Gq = flint.fmpq_mat([[flint.fmpq(_q(v).numerator, _q(v).denominator) for v in r] for r in G])
    GAd = Gq * Ad
    for kind, vs in (("p", points), ("r", rays), ("l", lines)):
        for v in vs:
            y = GAd * flint.fmpq_mat([[flint.fmpq(Fraction(x).numerator, Fraction(x).denominator)] for x in v])
            for j in range(len(G)):
                yj = Fraction(int(y[j, 0].p), int(y[j, 0].q))
                if (kind == "p" and yj > _q(b[j])) or (kind == "r" and yj > 0) or (kind == "l" and yj != 0):
                    return False
    return True


def _method_from(record):
    num = [Fraction(c) for c in record["numerator"]]
    den = [Fraction(c) for c in record["denominator"]]
    return type("M", (), {"numerator": num, "denominator": den})


def _robust_claim_is_true(problem, claim, rng, samples=6):
    """Sampling: lambda in the simplex, h <= tau (< tau when not attained), D(hA) nonsingular and A_d(h)
    mapping P into P exactly; every vertex keeps P for forward Euler at 1/gamma, some vertex fails just
    above it (the step is the largest); at most ``samples`` draws."""
    try:
        hull = [flint.fmpq_mat([[flint.fmpq(_q(v).numerator, _q(v).denominator) for v in r] for r in A])
                for A in problem["hull"]]
        G, b = problem["G"], problem["b"]
        gens = _points_rays_lines([[_q(v) for v in r] for r in G], [_q(v) for v in b])
        method = _method_from(problem["method"])
    except Exception:
        return False
    if gens is None:
        return False
    tau = claim["value"]
    if not isinstance(tau, str):  # an algebraic tau: sample below its isolating interval's lower end
        top = _q(tau["interval"][0])
        attained = False
    else:
        top = None if tau == "oo" else _q(tau)
        attained = claim["attained"]
    for _ in range(samples):
        w = [rng.randint(0, 5) for _ in hull]
        if not sum(w):
            w[0] = 1
        A = sum((Ai * flint.fmpq(wi, sum(w)) for Ai, wi in zip(hull[1:], w[1:])), hull[0] * flint.fmpq(w[0], sum(w)))
        if top is None:
            h = Fraction(rng.randint(0, 200), 4)
        else:
            h = top * Fraction(rng.randint(0, 16), 16)
            if h == top and not attained:
                h = top * Fraction(15, 16)
        Ad = _r_of(method, A, h)
        if Ad is None or not _maps_P_into_P(Ad, G, b, gens):
            return False
    fe = claim["forward_euler"]
    one = type("M", (), {"numerator": [1, 1], "denominator": [1]})
    steps = [Fraction(1000)] if fe == "oo" else [_q(fe)]
    if not all(_maps_P_into_P(_r_of(one, A, s), G, b, gens) for A in hull for s in steps):
        return False
    if fe != "oo":
        above = _q(fe) * Fraction(65, 64)
        if all(_maps_P_into_P(_r_of(one, A, above), G, b, gens) for A in hull):
            return False
    return True


def _leaves(obj, path=()):
    """Every (path, value) of a JSON value: numbers, booleans, lists, dicts."""
    yield path, obj
    if isinstance(obj, dict):
        for k, v in obj.items():
            yield from _leaves(v, path + (k,))
    elif isinstance(obj, list):
        for i, v in enumerate(obj):
            yield from _leaves(v, path + (i,))


def _set(obj, path, value):
    out = copy.deepcopy(obj)
    target = out
    for k in path[:-1]:
        target = target[k]
    if value is _DELETE:
        del target[path[-1]]
    else:
        target[path[-1]] = value
    return out


_DELETE = object()


def _mutations(value, rng):
    """A few plausible forgeries of one JSON value."""
    if isinstance(value, bool):
        return [not value]
    if isinstance(value, str):
        out = ["0", "1", "-1", "oo", "-oo", "1/3"]
        try:
            x = Fraction(value)
            out += [str(x + 1), str(x - 1), str(-x), str(x / 2), str(2 * x), str(x + Fraction(1, 1000)),
                    str(x - Fraction(1, 1000)), f"{x.numerator * 3}/{x.denominator * 3}", str(x) + ".0"]
        except (ValueError, ZeroDivisionError):
            pass
        return [s for s in out if s != value]
    if isinstance(value, list):
        out = [value[:-1]] if value else []
        if value:
            out.append(value + [value[-1]])
            out.append(value[::-1])
        return out
    if isinstance(value, int):
        return [value + 1, value - 1, 0]
    return []


def _mutants(cert, rng, limit):
    """(description, mutant): one leaf changed, or one optional key of the claim dropped."""
    items = []
    for path, value in _leaves(cert):
        if path and path[0] in ("format", "version"):
            continue
        if path and isinstance(path[-1], str) and len(path) >= 3:  # drop a key
            items.append((path, _DELETE))
        for v in _mutations(value, rng):
            items.append((path, v))
    rng.shuffle(items)
    for path, v in items[:limit]:
        yield path, _set(cert, path, v)


def _gain_problems(rng, count):
    out = []
    while len(out) < count:
        n, p = rng.randint(1, 3), rng.randint(1, 2)
        A = [[rng.randint(-2, 2) for _ in range(n)] for _ in range(n)]
        B = [[rng.randint(-1, 1) for _ in range(p)] for _ in range(n)]
        T = [[rng.randint(-2, 2) for _ in range(n)] for _ in range(n)]
        if flint.fmpz_mat(T).det() == 0:
            continue
        P = ei.Polyhedron([list(r) for r in T] + [[-v for v in r] for r in T], [rng.randint(1, 3) for _ in range(2 * n)])
        U = rng.choice([None, ei.Polyhedron.box([-rng.randint(1, 3)] * p, [rng.randint(1, 3)] * p)])
        try:
            out.append(ei.optimal_gain(A, B, P, inputs=U).certificate)
        except ei.ExactinvError:  # unbounded below: no claim
            continue
    return out


def _robust_problems(rng, count):
    methods = [ei.methods.taylor(2), ei.methods.rk4(), ei.methods.backward_euler(), ei.methods.trapezoid(),
               ei.methods.pade(1, 2)]
    out = []
    while len(out) < count:
        n, k = rng.randint(1, 2), rng.randint(2, 3)
        T = [[rng.randint(-2, 2) for _ in range(n)] for _ in range(n)]
        Tq = flint.fmpq_mat(T)
        if Tq.det() == 0:
            continue
        systems = []
        for _ in range(k):
            M = [[Fraction(rng.randint(-3, 3), rng.randint(1, 2)) if i != j else Fraction(0) for j in range(n)]
                 for i in range(n)]
            for i in range(n):
                M[i][i] = -sum(abs(v) for v in M[i]) - Fraction(rng.randint(0, 4), 2)
            Mq = flint.fmpq_mat([[flint.fmpq(v.numerator, v.denominator) for v in r] for r in M])
            A = Tq.inv() * Mq * Tq
            systems.append(ei.LinearSystem([[Fraction(int(A[i, j].p), int(A[i, j].q)) for j in range(n)]
                                            for i in range(n)]))
        P = ei.Polyhedron([list(r) for r in T] + [[-v for v in r] for r in T], [1] * (2 * n))
        out.append(ei.robust_threshold(systems, P, rng.choice(methods)).certificate)
    return out


def fuzz(seed, problems=2, mutants_per_cert=60):
    """(mutants checked, accepted, accepted and verified true, the false ones); genuine certificates must verify."""
    rng = random.Random(seed)
    stats = {"mutants": 0, "accepted": 0, "true": 0, "false": []}
    for kind, certs in (("gain", _gain_problems(rng, problems)), ("robust", _robust_problems(rng, problems))):
        for cert in certs:
            assert exactinv_check.check(cert).ok, cert
            claim = cert["claims"][-1]
            genuine = claim["value"] if kind == "gain" else None
            for path, mutant in _mutants(cert, rng, mutants_per_cert):
                stats["mutants"] += 1
                if not exactinv_check.check(mutant).ok:
                    continue
                stats["accepted"] += 1
                same_problem = mutant["problem"] == cert["problem"]
                claims = [c for c in mutant["claims"] if c.get("type") in ("optimal_gain", "robust_threshold")]
                if not claims:  # the claims list cut short: what is left are genuine claims, unchanged
                    ok = same_problem and all(c in cert["claims"] for c in mutant["claims"])
                elif kind == "gain":
                    ok = _gain_claim_is_true(mutant["problem"], claims[-1], genuine if same_problem else None)
                else:
                    ok = _robust_claim_is_true(mutant["problem"], claims[-1], rng)
                if ok:
                    stats["true"] += 1
                else:
                    stats["false"].append((kind, path))
    return stats


# ------------------------------------------------------------------ soundness

def test_a_farkas_vector_on_an_empty_P_does_not_prove_that_no_gain_exists():
    claim = {"type": "optimal_gain", "holds": False, "value": "oo", "farkas": dict(_EMPTY_FARKAS)}
    assert not exactinv_check.check(_gain_cert(_EMPTY_P, claim)).ok  # was accepted
    for x in (["-1", "0"], ["1", "0"], ["0", "0"]):  # no point of the empty P can be offered
        report = exactinv_check.check(_gain_cert(_EMPTY_P, dict(claim, x=x)))
        assert not report.ok and "not in P" in str(report), report


def test_the_same_farkas_vector_on_a_nonempty_P_with_its_point_is_accepted():
    """Route against route: P = {x1 <= 1, -x1 <= 1} is nonempty and the LP is infeasible for the same
    reason (the first row of G(A + BF) is (0, 1)); so no gain makes P invariant -- true: at x = (1, 1),
    on the facet x1 = 1, x1' = x2 = 1 > 0 whatever u is."""
    problem = dict(_EMPTY_P, b=["1", "1"])
    claim = {"type": "optimal_gain", "holds": False, "value": "oo", "farkas": dict(_EMPTY_FARKAS), "x": ["1", "1"]}
    assert exactinv_check.check(_gain_cert(problem, claim)).ok
    claim.pop("x")
    assert not exactinv_check.check(_gain_cert(problem, claim)).ok  # x is required
    P = ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])
    for a22 in (0, -7, 3):  # whatever the gain puts in the second row
        assert not ei.continuous_invariance(ei.LinearSystem([[0, 1], [0, a22]]), P).holds


def test_an_optimal_gain_on_an_empty_P_is_refused():
    """The LP's claim 'gamma*(A + BF') >= 0 for every gain F' with u in U' was accepted on the empty P above; the
    kernel itself proves it false: gamma*(A + BF') = -5 for F' = (0, 5) (a gamma_star certificate on the same P,
    H rows (5, 5, 0), (5, 5, 0), (3, 3, 5); the dual of row 2 is y = (0, 1), lambda = 0)."""
    assert not exactinv_check.check(_gain_cert(_EMPTY_P3, _EMPTY_P3_CLAIM)).ok  # was accepted
    report = exactinv_check.check(_gain_cert(_EMPTY_P3, dict(_EMPTY_P3_CLAIM, x=["1", "1"])))
    assert not report.ok and "not in P" in str(report), report
    closed = {"A": [["0", "0"], ["0", "5"]], "G": _EMPTY_P3["G"], "b": _EMPTY_P3["b"]}
    smaller = {"type": "gamma_star", "value": "-5", "H": [["5", "5", "0"], ["5", "5", "0"], ["3", "3", "5"]],
               "binding_row": 2, "dual": {"y": ["0", "1"], "lambda": "0"}}
    assert exactinv_check.check(_gain_cert(closed, smaller)).ok  # so the optimum 0 was false


def test_the_engine_writes_the_point_and_the_kernel_checks_it():
    P = ei.Polyhedron([[1, 0], [-1, 0], [1, 1], [-1, -1]], [1, 1, 1, 1])
    for e, holds in ((1, False), (2, True)):
        g = ei.optimal_gain([[0, 1], [0, 0]], [[0], [1]], P, inputs=ei.Polyhedron.box([-e], [e]))
        assert g.holds is holds
        cert = g.certificate
        assert [Fraction(v) for v in cert["claims"][0]["x"]] in P
        assert exactinv_check.check(cert).ok
        bad = copy.deepcopy(cert)
        bad["claims"][0]["x"] = ["5", "0"]
        assert not exactinv_check.check(bad).ok


def test_integer_rank_agrees_with_gauss_jordan():
    rng = random.Random(2)
    for _ in range(60):
        m, n = rng.randint(1, 6), rng.randint(1, 5)
        k = rng.randint(0, min(m, n))  # rank at most k: a product of m x k and k x n
        L = [[rng.randint(-3, 3) for _ in range(k)] for _ in range(m)]
        R = [[rng.randint(-3, 3) for _ in range(n)] for _ in range(k)]
        M = [[sum(L[i][t] * R[t][j] for t in range(k)) for j in range(n)] for i in range(m)]
        expected = rank_and_nullspace([[Fraction(v) for v in r] for r in M], n)[0]
        assert integer_rank(M, n) == expected <= k
        assert expected == flint.fmpz_mat(M).rank()


def test_a_hull_with_lines_is_still_refused_for_a_rational_method():
    """P = {|x1| <= 1} in R^2 has the line x1 = 0: the rational robust claim needs P without lines."""
    with budget.account(time_limit=None):
        assert Problem(_hull_record([[1, 0], [-1, 0]])).lines_possible
        assert not Problem(_hull_record([[1, 0], [-1, 0], [0, 1], [0, -1]])).lines_possible


def test_the_independent_checks_accept_genuine_and_refuse_forged_claims():
    """The fuzzer's oracle is no rubber stamp: true on genuine certificates, false on known-false claims."""
    rng = random.Random(5)
    for cert in _gain_problems(rng, 3):
        assert _gain_claim_is_true(cert["problem"], cert["claims"][0], cert["claims"][0]["value"])
        if cert["claims"][0]["holds"]:
            bad = copy.deepcopy(cert["claims"][0])
            bad["value"] = str(Fraction(bad["value"]) - 1)
            assert not _gain_claim_is_true(cert["problem"], bad, None)
    for cert in _robust_problems(rng, 3):
        assert _robust_claim_is_true(cert["problem"], cert["claims"][-1], rng)
    # x' = -x and x' = -2x on [-1, 1] with Taylor(2): tau = 1 is true, tau = 2 is false (the vertex -2 leaves
    # P at h = 2: 1 - 4 + 8 = 5 > 1), and forward Euler's largest step is 1 (|1 - 2h| <= 1 iff h <= 1)
    problem = {"hull": [[["-1"]], [["-2"]]], "G": [["1"], ["-1"]], "b": ["1", "1"],
               "method": {"numerator": ["1", "1", "1/2"], "denominator": ["1"]}}
    claim = {"value": "1", "attained": True, "forward_euler": "1"}
    assert _robust_claim_is_true(problem, claim, random.Random(0), samples=30)
    assert not _robust_claim_is_true(problem, dict(claim, value="2"), random.Random(0), samples=30)
    assert not _robust_claim_is_true(problem, dict(claim, forward_euler="2"), random.Random(0))
    assert not _robust_claim_is_true(problem, dict(claim, forward_euler="1/2"), random.Random(0))  # not the largest


def test_fuzzer_every_accepted_mutant_is_true():
    """Seeded and small (the long runs: CHANGELOG.md, Security): each accepted mutant verified."""
    stats = fuzz(seed=2026, problems=2, mutants_per_cert=40)
    assert stats["mutants"] >= 100
    assert stats["false"] == [], stats["false"]
    assert stats["accepted"] == stats["true"]


# ------------------------------------------------------------------ resource

def test_the_largest_robust_forward_euler_step_needs_a_nonempty_P():
    assert not exactinv_check.check(_empty_robust()).ok  # was accepted: "forward_euler": "1" on an empty P
    for x in (["-1", "0"], ["1", "0"], ["0", "5"]):
        report = exactinv_check.check(_empty_robust(x))
        assert not report.ok and "not in P" in str(report), report
    # the same record on the nonempty P = {|x1| <= 1, x2 <= 5} (b = (1, 1, 5)) is true: at x = (0, 5) on the
    # facet x2 = 5, forward Euler gives x2 = 5 - 5h, and the facets |x1| <= 1 are fixed (x1' = 0); the step
    # 1/gamma = 1 is the largest, as the independent sampler of this file confirms.
    cert = _empty_robust(["0", "5"])
    cert["problem"]["b"] = ["1", "1", "5"]
    cert["claims"][1]["vertices"][0]["H"] = [["0", "0", "0"], ["0", "0", "0"], ["0", "0", "-1"]]
    cert["claims"][1]["vertices"][0]["dual"] = {"y": ["0", "1"], "lambda": "0"}
    assert exactinv_check.check(cert).ok
    assert _robust_claim_is_true(cert["problem"], cert["claims"][1], random.Random(3), samples=20)


def test_the_hull_problems_rank_is_charged():
    """Before: Problem() ran rank_and_nullspace (Fraction Gauss-Jordan) with no charge, so a 400 x 200 G
    (640 KB) ran minutes of CPU that neither the budget nor the clock saw.  Now each elimination step is
    charged: under a small account the same work (scaled down: 60 x 30) is rejected, not run."""
    rng = random.Random(1)
    G = [[rng.randint(-9, 9) for _ in range(30)] for _ in range(60)]
    with budget.account(limit=10**5, time_limit=None):
        with pytest.raises(CheckFailure, match="work budget"):
            Problem(_hull_record(G))
    with budget.account(time_limit=None) as acc:
        assert not Problem(_hull_record(G)).lines_possible
    assert acc.spent > 10**5
