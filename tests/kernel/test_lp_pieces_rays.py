"""Attacks on the kernel's LP route on UNBOUNDED P (exactinv_check/routes/lp_pieces.py): ray pieces {"ray": d},
point pieces [t, t], ray pieces ending at a pole, the record's point, the coverage rule.

The truth is computed here, independently of the kernel: the vertex route (route="vertex", generators of P
by double description) for the whole valid set, and exact LPs over Q (pplpy's MIP_Problem: unbounded, or
the optimum) of max g_i A_d(h) x over P at rational steplengths h, A_d(h) = r(hA) exact.  The mutation
fuzzer takes genuine lp certificates of random small unbounded pointed P (n = 2..4: cones, orthant
sections, slabs) under Taylor 1..6 and rational methods, changes one field at a time (a ray, a piece's kind,
an end, a point piece, the point, the problem) and checks that every record the kernel accepts gives the
true valid set."""


import copy
import json
import random
from fractions import Fraction as F

import pytest
from lp_record_sets import kernel_set, same

import exactinv as ei
import exactinv_check
from exactinv_check import poly_arithmetic, polys
from exactinv_check.conditions import method_matrices, method_matrix_at
from exactinv_check.failure import CheckFailure
from exactinv_check.reals import Real
from exactinv_check.routes import lp_pieces
from exactinv_check.validset import Interval, require_intervals

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


M = ei.methods


ppl = pytest.importorskip("ppl")


TALLY = {}  # (tried | accepted, mutation kind) -> count, for the fuzzer's report


METHODS = [M.taylor(k) for k in range(1, 7)] + [M.pade(1, 1), M.backward_euler(), M.pade(0, 2), M.pade(1, 2)]


def _lcm_scale(values):
    d = 1
    for v in values:
        d = d * v.denominator // __import__("math").gcd(d, v.denominator)
    return d


def lp_valid_at(A, G, b, method, h):
    """A_d(h) P subset of P, decided by exact LPs over Q (pplpy): for every facet i, max g_i A_d(h) x over P
    is bounded and at most b_i.  None where h_r(hA) is singular (a pole: not a steplength); True when P is
    empty."""
    Ad = method_matrix_at([[F(x) for x in r] for r in A], [F(c) for c in method.numerator],
                          [F(c) for c in method.denominator], F(h))
    if Ad is None:
        return None
    n = len(A)
    xs = [ppl.Variable(j) for j in range(n)]
    cs = ppl.Constraint_System()
    for g, beta in zip(G, b):
        row = [F(v) for v in g] + [F(beta)]
        s = _lcm_scale(row)
        cs.insert(sum((int(v * s) * x for v, x in zip(row, xs)), ppl.Linear_Expression(0)) <= int(row[-1] * s))
    for g, beta in zip(G, b):
        c = [sum(F(g[k]) * Ad[k][j] for k in range(n)) for j in range(n)]
        s = _lcm_scale(c)
        obj = sum((int(v * s) * x for v, x in zip(c, xs)), ppl.Linear_Expression(0))
        mip = ppl.MIP_Problem(n, cs, obj, "maximization")
        status = mip.solve()["status"]
        if status == "unfeasible":
            return True
        if status == "unbounded":
            return False
        value = mip.optimal_value()
        if F(value.numerator, value.denominator) > F(beta) * s:
            return False
    return True


def vertex_truth(A, G, b, method):
    """The valid set's intervals by the vertex route (its own certificate verified by the kernel)."""
    result = ei.valid_steplengths(ei.LinearSystem([[F(x) for x in r] for r in A]),
                                  ei.Polyhedron([[F(x) for x in r] for r in G], [F(x) for x in b]),
                                  method, route="vertex")
    assert exactinv_check.check(result.certificate).ok
    return result.certificate["claims"][0]["intervals"]



def _inside(W, h):
    q = Real.rational(h)
    for w in W:
        lo = w.lo.compare(q)
        hi = 1 if w.hi.inf else w.hi.compare(q)
        if (lo < 0 or (lo == 0 and w.lo_closed)) and (hi > 0 or (hi == 0 and w.hi_closed)):
            return True
    return False


def sample_points(W, extra=()):
    """Rationals just inside and outside every end of W (and of ``extra`` ends), and beyond the last."""
    ends = []
    for w in list(W):
        for e in (w.lo, w.hi):
            if not e.inf:
                ends.append(e)
    ends += list(extra)
    out = set()
    for e in ends:
        lo, hi = e.bounds()
        for eps in (F(1, 10**6), F(1, 1000)):
            for q in (lo - eps, hi + eps, lo, hi):
                if q >= 0:
                    out.add(q)
    out.add(F(0))
    top = max([e.bounds()[1] for e in ends] + [F(1)])
    out |= {top + 1, 2 * top + 3}
    return sorted(out)


def lp_disagreement(cert, W):
    """A rational h where the kernel's set W and the exact LPs disagree, or None."""
    p = cert["problem"]
    method = _method_of(p)
    ends = [Real.parse(e) for f in cert["claims"][0]["lp"]["facets"] for e in f["ends"] if e != "oo"]
    for h in sample_points(W, ends):
        truth = lp_valid_at(p["A"], p["G"], p["b"], method, h)
        if truth is None:
            continue
        if truth != _inside(W, h):
            return h
    return None


def _method_of(problem):
    return ei.Method("m", [F(c) for c in problem["method"]["numerator"]],
                     [F(c) for c in problem["method"]["denominator"]])


def random_problem(rng, dims=(2, 3, 4)):
    """A small unbounded pointed P (a cone, an orthant section or a slab) and A, method at random."""
    n = rng.choice(dims)
    kind = rng.randrange(4)
    if kind == 3:  # the bare orthant with integer A: ray pieces meeting, point pieces (tests/test_lp_pieces.py)
        G = [[-int(i == j) for j in range(n)] for i in range(n)]
        A = [[F(rng.randint(-10, 10)) for _ in range(n)] for _ in range(n)]
        return A, G, [0] * n, rng.choice(METHODS)
    G, b = [], []
    if kind == 0:  # a cone (b = 0) or a shifted one: every row g with g . 1 < 0, so (1, .., 1) is a ray
        while len(G) < n + rng.randint(0, 2):
            row = [rng.randint(-3, 3) for _ in range(n)]
            s = sum(row)
            if s == 0:
                continue
            G.append(row if s < 0 else [-v for v in row])
            b.append(rng.choice([0, 0, 1, 2]))
    elif kind == 1:  # an orthant section: x >= 0 and a few rows a x <= beta with a not all positive
        G = [[-int(i == j) for j in range(n)] for i in range(n)]
        b = [0] * n
        for _ in range(rng.randint(1, 3)):
            row = [rng.randint(-3, 3) for _ in range(n)]
            if any(row):
                G.append(row)
                b.append(rng.randint(1, 3))
    else:  # a slab in x_1 over x >= 0 in the other coordinates, with a cutting row or two
        G = [[int(j == 0) for j in range(n)], [-int(j == 0) for j in range(n)]]
        b = [1, 1]
        G += [[-int(i == j) for j in range(n)] for i in range(1, n)]
        b += [0] * (n - 1)
        for _ in range(rng.randint(0, 2)):
            row = [rng.randint(-3, 3)] + [rng.randint(-3, 0) for _ in range(n - 1)]
            if any(row):
                G.append(row)
                b.append(rng.randint(1, 3))
    A = [[F(-rng.randint(0, 2) if i == j else 0) + F(rng.randint(-4, 4), rng.choice([1, 2, 4, 12])) for j in range(n)]
         for i in range(n)]
    return A, G, b, rng.choice(METHODS)


def _ray_pieces(cert):
    return [(i, k) for i, f in enumerate(cert["claims"][0]["lp"]["facets"])
            for k, basis in enumerate(f["bases"]) if isinstance(basis, dict) and "ray" in basis]


def _all_rays(cert):
    return [b["ray"] for f in cert["claims"][0]["lp"]["facets"] for b in f["bases"] if isinstance(b, dict) and "ray" in b]


def _all_bases(cert):
    return [b for f in cert["claims"][0]["lp"]["facets"] for b in f["bases"] if isinstance(b, list)]


def _fix_point(c):
    """Keep the record's shape rule: a point exactly when a ray piece is left."""
    lp = c["claims"][0]["lp"]
    if _ray_pieces(c) and "point" not in lp:
        lp["point"] = ["0"] * len(c["problem"]["A"])
    if not _ray_pieces(c) and "point" in lp:
        del lp["point"]


def _rational_end(e):
    return isinstance(e, str) and e != "oo"


def _roots_for(c, i, rng, pole):
    """Positive roots (as certificate numbers: rationals or {"poly", "interval"}) of D (pole) or of
    (g_i N(h) d) D for a ray d of the record and facet i."""
    p = c["problem"]
    A = [[F(x) for x in r] for r in p["A"]]
    D, N = method_matrices(A, [F(x) for x in p["method"]["numerator"]], [F(x) for x in p["method"]["denominator"]])
    if pole:
        q = D
    else:
        rays = _all_rays(c)
        if not rays:
            return []
        d = [F(x) for x in rng.choice(rays)]
        g = [F(x) for x in p["G"][i]]
        e = [sum(g[a] * Nk[a][b] * d[b] for a in range(len(d)) for b in range(len(d))) for Nk in N]
        q = poly_arithmetic.mul(poly_arithmetic.trim(e), D)
    out = []
    if len(poly_arithmetic.trim(q)) < 2:
        return out
    for lo, hi in polys.positive_roots(q):
        if lo == hi:
            out.append(str(lo))
        else:
            sq = poly_arithmetic.integer_coefficients(polys.squarefree(poly_arithmetic.strip_zero_roots(q)))
            out.append({"poly": [str(x) for x in sq], "interval": [str(lo), str(hi)]})
    return out


def mutate(rng, cert):
    """One field changed (module docstring); None when the chosen mutation does not apply."""
    c = copy.deepcopy(cert)
    lp = c["claims"][0]["lp"]
    facets = lp["facets"]
    n, m = len(c["problem"]["A"]), len(c["problem"]["G"])
    rays = _ray_pieces(c)
    i = rng.randrange(len(facets))
    f = facets[i]
    K = len(f["ends"])
    k = rng.randrange(K)
    kind = rng.randrange(22)
    TALLY["tried", kind] = TALLY.get(("tried", kind), 0) + 1
    if kind in (0, 1, 2) and rays:  # a ray's entry changed, the ray replaced, scaled or negated
        i, k = rng.choice(rays)
        d = facets[i]["bases"][k]["ray"]
        if kind == 0:
            j = rng.randrange(n)
            d[j] = str(F(d[j]) + rng.choice([-1, 1, F(1, 2), F(-1, 3), F(1, 10**6)]))
        elif kind == 1:
            choice = rng.randrange(5)
            if choice == 0:
                facets[i]["bases"][k]["ray"] = list(rng.choice(_all_rays(c)))
            elif choice == 1:
                facets[i]["bases"][k]["ray"] = [str(int(j == rng.randrange(n)) * rng.choice([1, -1])) for j in range(n)]
            elif choice == 2:
                facets[i]["bases"][k]["ray"] = [str(rng.randint(-2, 2)) for _ in range(n)]
            elif choice == 3:
                e = rng.choice(_all_rays(c))
                facets[i]["bases"][k]["ray"] = [str(F(x) + F(y)) for x, y in zip(d, e)]
            else:
                facets[i]["bases"][k]["ray"] = ["0"] * n
        else:
            s = rng.choice([-1, 2, F(1, 3), 10**rng.randint(50, 3000), F(1, 10**rng.randint(50, 3000))])
            facets[i]["bases"][k]["ray"] = [str(F(x) * s) for x in d]
    elif kind == 3 and rays:  # a ray piece claimed a basis piece (the LP called bounded)
        i, k = rng.choice(rays)
        facets[i]["bases"][k] = list(rng.choice(_all_bases(c))) if _all_bases(c) else \
            [rng.randrange(m) for _ in range(n)]
    elif kind == 4 and isinstance(f["bases"][k], list) and rays:  # a basis piece claimed a ray piece
        f["bases"][k] = {"ray": list(rng.choice(_all_rays(c)))}
    elif kind == 5 and _rational_end(f["ends"][k]):  # a point piece inserted at an existing end
        basis = list(rng.choice(_all_bases(c))) if _all_bases(c) and rng.random() < 0.8 else \
            rng.sample(range(m), n)
        f["ends"].insert(k, f["ends"][k])
        f["bases"].insert(k + 1, basis)
    elif kind == 6:  # a point piece inserted inside a piece, at a rational
        lo = F(0) if k == 0 else (F(f["ends"][k - 1]) if _rational_end(f["ends"][k - 1]) else None)
        end = f["ends"][k]
        hi = F(end) if _rational_end(end) else (None if end != "oo" else lo + 2 if lo is not None else None)
        if lo is None or hi is None:
            return None
        t = lo + (hi - lo) * F(rng.randint(1, 99), 100)
        basis = list(rng.choice(_all_bases(c))) if _all_bases(c) else rng.sample(range(m), n)
        piece = f["bases"][k]
        f["ends"][k:k] = [str(t), str(t)]
        f["bases"][k:k + 1] = [copy.deepcopy(piece), basis, copy.deepcopy(piece)]
    elif kind == 7:  # a point piece deleted (its ends merged)
        points = [j for j in range(1, K) if f["ends"][j] == f["ends"][j - 1] and isinstance(f["bases"][j], list)]
        if not points:
            return None
        j = rng.choice(points)
        del f["ends"][j], f["bases"][j]
    elif kind == 8 and rays:  # a ray piece's end moved
        i, k = rng.choice(rays)
        f = facets[i]
        if not _rational_end(f["ends"][k]):
            return None
        e = F(f["ends"][k])
        f["ends"][k] = str(e * (1 + F(rng.choice([1, -1]), 10 ** rng.randint(1, 9))))
    elif kind == 9 and rays:  # a ray piece's start moved (the end before it)
        i, k = rng.choice(rays)
        f = facets[i]
        if k == 0 or not _rational_end(f["ends"][k - 1]):
            return None
        e = F(f["ends"][k - 1])
        f["ends"][k - 1] = str(e * (1 + F(rng.choice([1, -1]), 10 ** rng.randint(1, 9))))
    elif kind == 10:  # the point of P replaced
        if "point" not in lp:
            return None
        choice = rng.randrange(3)
        if choice == 0:
            lp["point"] = [str(rng.randint(-3, 3)) for _ in range(n)]
        elif choice == 1:
            j = rng.randrange(n)
            lp["point"][j] = str(F(lp["point"][j]) + rng.choice([-1, 1, F(1, 7)]))
        else:
            lp["point"] = [str(F(x) * 10**rng.randint(100, 3000)) for x in lp["point"]]
    elif kind == 11 and K >= 2:  # two pieces merged (an end deleted, one of their data kept)
        j = rng.randrange(K - 1)
        del f["ends"][j]
        del f["bases"][j + rng.randint(0, 1)]
    elif kind == 12 and K >= 2:  # two adjacent pieces' data swapped
        j = rng.randrange(K - 1)
        f["bases"][j], f["bases"][j + 1] = f["bases"][j + 1], f["bases"][j]
    elif kind == 13:  # the last piece run to oo, or cut
        if rng.random() < 0.5:
            f["ends"][-1] = "oo"
        elif K >= 2:
            del f["ends"][-1], f["bases"][-1]
        else:
            return None
    elif kind == 14 and rays:  # a ray piece split at a rational, the second half with another ray
        i, k = rng.choice(rays)
        f = facets[i]
        lo = F(0) if k == 0 else (F(f["ends"][k - 1]) if _rational_end(f["ends"][k - 1]) else None)
        hi = F(f["ends"][k]) if _rational_end(f["ends"][k]) else (lo + 3 if lo is not None and f["ends"][k] == "oo" else None)
        if lo is None or hi is None:
            return None
        t = lo + (hi - lo) * F(rng.randint(1, 99), 100)
        f["ends"].insert(k, str(t))
        f["bases"].insert(k + 1, {"ray": list(rng.choice(_all_rays(c)))})
    elif kind == 15:  # an end made a random rational, or a duplicate of another end
        f["ends"][k] = rng.choice([str(F(rng.randint(1, 400), rng.randint(1, 200))), rng.choice(f["ends"])])
    elif kind == 16:  # the problem's b nudged (the record kept)
        j = rng.randrange(m)
        c["problem"]["b"][j] = str(F(c["problem"]["b"][j]) + F(rng.choice([1, -1]), rng.choice([2, 10, 1000])))
    elif kind == 17:  # the problem's A nudged
        r, s = rng.randrange(n), rng.randrange(n)
        c["problem"]["A"][r][s] = str(F(c["problem"]["A"][r][s]) + F(rng.choice([1, -1]), rng.choice([2, 10, 1000])))
    elif kind == 18:  # facets swapped
        j = rng.randrange(len(facets))
        facets[i], facets[j] = facets[j], facets[i]
    elif kind == 19 and isinstance(f["bases"][k], list):  # a basis row changed
        f["bases"][k][rng.randrange(n)] = rng.randrange(m)
    elif kind in (20, 21):  # a piece split, or an end moved, at a pole (a root of D) or at a root of a ray's r
        roots = _roots_for(c, i, rng, pole=kind == 20)
        if not roots:
            return None
        t = rng.choice(roots)
        tr = Real.parse(t)
        for k, e in enumerate(f["ends"]):  # noqa: B007 (k, the piece holding t, is used after the loop)
            if Real.parse(e).compare(tr) >= 0:
                break
        if Real.parse(f["ends"][k]).compare(tr) == 0:
            return None
        choice = rng.randrange(4)
        if choice == 0:  # the end of piece k (before t) moved to t
            if k == 0:
                return None
            f["ends"][k - 1] = t
        elif choice == 1:  # split at t, the same data both sides
            f["ends"].insert(k, t)
            f["bases"].insert(k, copy.deepcopy(f["bases"][k]))
        elif choice == 2:  # split at t, a ray on the right
            if not _all_rays(c):
                return None
            f["ends"].insert(k, t)
            f["bases"].insert(k + 1, {"ray": list(rng.choice(_all_rays(c)))})
        else:  # a point piece [t, t] inside piece k
            bases = _all_bases(c)
            basis = list(rng.choice(bases)) if bases else rng.sample(range(m), n)
            f["ends"][k:k] = [t, t]
            f["bases"][k:k + 1] = [copy.deepcopy(f["bases"][k]), basis, copy.deepcopy(f["bases"][k])]
    else:
        return None
    _fix_point(c)
    c["claims"][0]["kind"] = kind  # for the tally only (kernel_set reads the lp record)
    return c


def fuzz(seed, problems, mutations, dims=(2, 3, 4), use_lp=True, log=None, lp_rate=0.2):
    """Genuine lp certificates (with at least one ray piece) of random unbounded P, mutated one field at a
    time; every record the kernel accepts must give the vertex route's valid set, and the exact LPs at rational
    points around its ends must agree.  Returns (accepted, rejected, false accepts)."""
    rng = random.Random(seed)
    accepted = rejected = 0
    bad = []
    done = 0
    while done < problems:
        A, G, b, method = random_problem(rng, dims)
        try:
            result = ei.valid_steplengths(ei.LinearSystem(A), ei.Polyhedron(G, b), method, route="lp")
        except ei.ExactinvError:
            continue
        cert = result.certificate
        if not _ray_pieces(cert):
            continue
        done += 1
        truths = {}
        if use_lp:  # the genuine record itself against the exact LPs
            W = kernel_set(cert["problem"], cert["claims"][0]["lp"])
            if W is None or lp_disagreement(cert, W) is not None:
                bad.append(cert)
                if log is not None:
                    log(json.dumps(cert))
        for _ in range(mutations):
            c = mutate(rng, cert)
            if c is None:
                continue
            W = kernel_set(c["problem"], c["claims"][0]["lp"])
            if W is None:
                rejected += 1
                continue
            accepted += 1
            TALLY["accepted", c["claims"][0]["kind"]] = TALLY.get(("accepted", c["claims"][0]["kind"]), 0) + 1
            p = c["problem"]
            key = json.dumps(p)
            if key not in truths:
                truths[key] = vertex_truth(p["A"], p["G"], p["b"], method)
            wrong = not same(W, truths[key])
            h = lp_disagreement(c, W) if use_lp and not wrong and rng.random() < lp_rate else None
            if wrong or h is not None:
                bad.append(c)
                if log is not None:
                    log(json.dumps(c))
    return accepted, rejected, bad


def _pole_certificate():
    """Pade(1,1) on P = {-3x1 - x2 <= 1, x2 >= 0, -3 x2 <= 1}, A = [[-4, -3/4], [-3/4, 3]]: D = 1 + h/2 -
    201 h^2/64 has the pole t = 0.6494.. (root of 201h^2 - 32h - 64); facet 0 is a basis piece up to 0.402..,
    then the ray (1, 0) up to the pole and the ray (-1, 3) after it.  The valid set is {0}."""
    S = ei.LinearSystem([[-4, F(-3, 4)], [F(-3, 4), 3]])
    P = ei.Polyhedron([[-3, -1], [0, -2], [0, -3]], [1, 0, 1])
    cert = ei.valid_steplengths(S, P, M.pade(1, 1), route="lp").certificate
    f = cert["claims"][0]["lp"]["facets"][0]
    assert f["bases"][1:] == [{"ray": ["1", "0"]}, {"ray": ["-1", "3"]}]
    assert f["ends"][1]["poly"] == ["-64", "-32", "201"]
    assert exactinv_check.check(cert).ok
    return cert


# ------------------------------------------------------------------ soundness

def test_the_lp_truth_agrees_with_the_vertex_route_on_a_worked_orthant():
    """The orthant of R^2 with M = [[-4, -1], [10, 0]], Taylor(3): the valid set is {0} and {1}
    (tests/test_lp_pieces.py); the exact LPs say so at 1 and refuse 1 +- 10^-6 and 1/2."""
    A, G, b = [[-4, -1], [10, 0]], [[-1, 0], [0, -1]], [0, 0]
    assert lp_valid_at(A, G, b, M.taylor(3), F(1)) is True
    assert lp_valid_at(A, G, b, M.taylor(3), F(0)) is True
    for h in (F(1, 2), 1 + F(1, 10**6), 1 - F(1, 10**6), F(5)):
        assert lp_valid_at(A, G, b, M.taylor(3), h) is False
    intervals = vertex_truth(A, G, b, M.taylor(3))
    assert [(t["lo"], t["hi"]) for t in intervals] == [("0", "0"), ("1", "1")]


def test_the_fuzzer_can_fail_on_a_kernel_that_skips_the_ray_cone_check(monkeypatch):
    """With G d <= 0 not checked, a ray outside the recession cone (a mutated entry) is accepted and its
    condition, not necessary, cuts the valid set short -- which the fuzzer reports."""
    real = lp_pieces._require_in
    monkeypatch.setattr(lp_pieces, "_require_in", lambda rows, x, what, cone=False: None if cone else
                        real(rows, x, what))
    _, _, bad = fuzz(seed=7, problems=6, mutations=25, use_lp=False)
    assert bad


def test_every_accepted_mutation_of_a_genuine_ray_record_gives_the_true_valid_set():
    accepted, rejected, bad = fuzz(seed=11, problems=6, mutations=25)
    assert not bad, json.dumps(bad[0])
    assert accepted > 10 and rejected > 30


@pytest.mark.parametrize("end", ["3/5", "649/1000", "13/20"])
def test_a_ray_piece_cannot_cross_a_pole(end):
    """r = (g_i N(h) d) D(h) has the factor D, so it vanishes at the pole: moving the pole end of the two
    ray pieces (to 3/5 or 0.649 below it, 0.65 above it) makes one of them cross the pole -- rejected, whichever
    ray would claim the pole's other side.  (The truth: the exact LPs say h = 3/5, 0.649, 0.65 are all invalid,
    so a wrong verdict could only have been an acceptance of a wrong set; there is none.)"""
    cert = _pole_certificate()
    cert["claims"][0]["lp"]["facets"][0]["ends"][1] = end
    report = exactinv_check.check(cert)
    assert not report.ok and "vanishes inside its piece" in str(report), report
    p = cert["problem"]
    assert lp_valid_at(p["A"], p["G"], p["b"], M.pade(1, 1), F(end)) is False


def test_the_lp_truth_catches_a_forged_basis_piece_in_a_kernel_that_skips_z_b(monkeypatch):
    """The half-strip {x1 >= 0, |x2| <= 1}, x' = -x, forward Euler: V = [0, 1] (facet 0 is a basis piece on
    [0, 1] and the ray (1, 0) after it).  The ray piece forged into a basis piece of the vertex (0, 1) is
    rejected by the kernel (z_B < 0 past 1); a kernel that skips z_B >= 0 derives [0, oo) from it (the
    other facets' pieces run to oo as well), and the
    exact LPs at the rationals around its ends say where that is false."""
    S = ei.LinearSystem([[-1, 0], [0, -1]])
    P = ei.Polyhedron([[-1, 0], [0, 1], [0, -1]], [0, 1, 1])
    cert = ei.valid_steplengths(S, P, M.forward_euler(), route="lp").certificate
    f = cert["claims"][0]["lp"]["facets"][0]
    assert f["ends"] == ["1", "oo"] and f["bases"][1] == {"ray": ["1", "0"]}
    f["bases"][1] = [0, 1]
    del cert["claims"][0]["lp"]["point"]
    for g in cert["claims"][0]["lp"]["facets"][1:]:
        g["ends"][-1] = "oo"  # the other facets' vertices kept to oo
    assert kernel_set(cert["problem"], cert["claims"][0]["lp"]) is None
    monkeypatch.setattr(lp_pieces, "_batch_positive", lambda Y, D_int, a, b: [True] * len(Y))
    monkeypatch.setattr(lp_pieces, "_require_nonnegative", lambda *args, **kw: None)
    W = kernel_set(cert["problem"], cert["claims"][0]["lp"])
    assert W is not None and len(W) == 1 and W[0].hi.inf  # the forged record's conditions allow every h
    h = lp_disagreement(cert, W)
    assert h is not None and h > 1


def test_a_passing_piece_formats_no_number(monkeypatch):
    """Found (resource): the point-piece check built its failure message eagerly -- ``f"... negative at
    {start}"`` -- for every component of every point piece, and the ray-piece coverage check for every ray
    piece, though the check passed: each a Real printed by ``text.algebraic_text`` (up to 400 exact
    bisections of the end and a Descartes test, the decimal arithmetic uncharged).  A 840 KB certificate of
    8000 point pieces at the algebraic end 0.402.. of the Pade(1,1) record below took 15.5 s of CPU for
    1.05e8 charged word operations (a fifth of the calibrated rate; ends near a power of ten need all 400
    bisections, so the clock, not the budget, would decide).  Now a message is built only when its check
    fails: checking the record formats no number at all."""
    cert = _pole_certificate()
    f = cert["claims"][0]["lp"]["facets"][0]
    assert isinstance(f["ends"][0], dict)
    f["ends"][:1] = [f["ends"][0]] * 6  # five point pieces [t, t] after the basis piece, t algebraic
    f["bases"][:1] = [f["bases"][0]] * 6
    calls = []
    real = exactinv_check.text.algebraic_text
    monkeypatch.setattr(exactinv_check.text, "algebraic_text", lambda *a: calls.append(a) or real(*a))
    W = kernel_set(cert["problem"], cert["claims"][0]["lp"])
    assert W is not None and len(W) == 1 and W[0].hi.compare(Real.rational(0)) == 0
    assert not calls, f"{len(calls)} numbers printed while every check passed"


def test_a_matching_valid_set_claim_formats_no_number(monkeypatch):
    """The same for the claim's intervals (validset.require_intervals): every interval's true ends were
    printed into the messages of checks that passed, and the whole true set once more."""
    calls = []
    real = exactinv_check.text.algebraic_text
    monkeypatch.setattr(exactinv_check.text, "algebraic_text", lambda *a: calls.append(a) or real(*a))
    s = Real.parse({"poly": ["-2", "0", "1"], "interval": ["1", "2"]})  # sqrt 2
    t = Real.parse({"poly": ["-3", "0", "1"], "interval": ["1", "2"]})  # sqrt 3
    truth = [Interval(Real.rational(0), s, True, True), Interval(t, Real.parse("oo"), True, False)]
    claim = [{"lo": "0", "hi": {"poly": ["-2", "0", "1"], "interval": ["1", "2"]}, "lo_closed": True,
              "hi_closed": True},
             {"lo": {"poly": ["-3", "0", "1"], "interval": ["1", "2"]}, "hi": "oo", "lo_closed": True,
              "hi_closed": False}]
    require_intervals(claim, truth)
    assert not calls
    claim[1]["lo"] = "2"
    with pytest.raises(CheckFailure, match="interval 1 starts at 1.73205"):
        require_intervals(claim, truth)


# ------------------------------------------------------------------ resource

def test_huge_rays_and_points_give_the_same_set_or_are_priced():
    """A ray scaled by 10^3000 is the same ray: the kernel accepts it and derives the same valid set (the
    condition is a positive multiple); a point with 3000-digit entries outside P is rejected by G x <= b."""
    cert = _pole_certificate()
    lp = cert["claims"][0]["lp"]
    lp["facets"][0]["bases"][1]["ray"] = [str(10**3000), "0"]
    assert exactinv_check.check(cert).ok
    lp["point"] = [str(-10**3000), "1"]
    report = exactinv_check.check(cert)
    assert not report.ok and "lp point violates" in str(report), report


def test_a_positive_ray_piece_with_long_ends_is_not_rejected_by_printing_its_sample():
    """Found (robustness): the fallback of the ray piece's positivity test printed its sample point q into
    the failure message before testing it; with ends of 3000 digits q has over 4300, and Python's int -> str
    limit raised ValueError -- a true ray piece rejected.  p = (h - 1)^2 + 10^-6 > 0 everywhere, its complex
    roots near 1 defeat Descartes' rule on (1/3, 2), so the fallback (root isolation, one sample) runs."""
    p = [F(1) + F(1, 10**6), F(-2), F(1)]
    start = Real.rational(F(10**3000 + 1, 3 * 10**3000))
    end = Real.rational(2 - F(1, 7 * 10**3000 + 1))
    assert lp_pieces._require_positive_open(p, start, end, "r")
    with pytest.raises(CheckFailure, match="not positive inside its piece"):
        lp_pieces._require_positive_open([-c for c in p], start, end, "r")
