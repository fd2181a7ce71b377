"""A mutation fuzzer of version 3 certificates (red team rt-sparse, round 2): genuine engine certificates
on random polygons, one field of one sparse H / H~ mutated at a time, every accepted mutant checked true
by an independent dense Fraction check of what the sparse matrix certifies.

Used by tests/kernel/test_claims_invariance.py (a small seeded run) and runnable alone:
``python tests/sparse_fuzz.py SECONDS SEED``.
"""

from __future__ import annotations

import copy
import random
import sys
from fractions import Fraction as F

import exactinv as ei
from exactinv import methods as M
from exactinv.certificates import certificate
from exactinv_check import check

METHODS = [lambda: M.taylor(1), lambda: M.taylor(2), lambda: M.taylor(4), M.trapezoid, M.backward_euler]


def random_polygon(rng):
    """A polygon with 3..8 vertices on integer points of a circle-like convex curve (convex position)."""
    k = rng.randint(3, 8)
    pts = set()
    while len(pts) < k:
        t = rng.randrange(360)
        r = rng.choice([3, 4, 5])
        import math
        pts.add((round(r * math.cos(math.radians(t)) * 4), round(r * math.sin(math.radians(t)) * 4)))
    return ei.Polyhedron.from_vertices(sorted(pts))


def random_system(rng):
    while True:
        A = [[rng.randint(-4, 2), rng.randint(-3, 3)], [rng.randint(-3, 3), rng.randint(-4, 2)]]
        if A[0][0] + A[1][1] < 0:
            return ei.LinearSystem(A)


def genuine(rng):
    """One engine certificate with a sparse H or H~ (or None when this draw has none)."""
    S, P = random_system(rng), random_polygon(rng)
    kind = rng.randrange(4)
    try:
        if kind == 0:
            cert = ei.steplength_threshold(S, P, rng.choice(METHODS)()).certificate
        elif kind == 1:
            cert = certificate(S, P, None, [ei.continuous_invariance(S, P)])
        elif kind == 2:
            method = rng.choice(METHODS[:3])()
            cert = certificate(S, P, method, [ei.discrete_invariance(S, P, method, F(1, rng.randint(2, 20)))])
        else:
            cert = ei.robust_threshold([S, random_system(rng)], P, rng.choice(METHODS)()).certificate
    except ei.ExactinvError:
        return None
    return cert if _sparse_fields(cert) else None


def _sparse_fields(cert):
    """(claim index, path to the matrix object, which) of every sparse matrix in the claims."""
    out = []
    for i, claim in enumerate(cert["claims"]):
        if isinstance(claim.get("H"), dict):
            out.append((i, ("H",)))
        for j, record in enumerate(claim.get("vertices") or []):
            if isinstance(record, dict) and isinstance(record.get("H"), dict):
                out.append((i, ("vertices", j, "H")))
    return out


def _get(claim, path):
    for key in path:
        claim = claim[key]
    return claim


VALUES = ["1", "-1", "1/2", "-1/3", "0", "-0", 0, 1, -1, True, 0.5, "1e3", "10" * 60, "3/1", "2.50"]
INDICES = [-1, 0, 1, 2, 7, 10**9, True, False, "0", 0.0, 1.0, None]


def mutate(rng, rows, m):
    """One random change to the list of sparse rows (in place); returns its name."""
    nonempty = [r for r in rows if r]
    op = rng.randrange(12)
    if op == 0 and nonempty:
        pair = rng.choice(rng.choice(nonempty))
        pair[1] = rng.choice(VALUES) if rng.random() < 0.5 else str(F(pair[1]) + F(rng.randint(-3, 3), rng.randint(1, 9)))
        return "value"
    if op == 1 and nonempty:
        pair = rng.choice(rng.choice(nonempty))
        pair[0] = rng.choice(INDICES + [m - 1, m, m + 1, pair[0] + 1, pair[0] - 1])
        return "index"
    if op == 2 and nonempty:
        row = rng.choice(nonempty)
        row.pop(rng.randrange(len(row)))
        return "remove entry"
    if op == 3:
        row = rng.choice(rows)
        k = rng.randrange(m)
        row.insert(rng.randrange(len(row) + 1), [k, rng.choice(VALUES[:4] + [str(F(rng.randint(-5, 5), rng.randint(1, 5)))])])
        return "insert entry"
    if op == 4 and nonempty:
        row = rng.choice(nonempty)
        row.append(list(rng.choice(row)))
        return "duplicate entry"
    if op == 5:
        i, j = rng.randrange(m), rng.randrange(m)
        rows[i], rows[j] = rows[j], rows[i]
        return "swap rows"
    if op == 6:
        rows.append(copy.deepcopy(rng.choice(rows)) if rng.random() < 0.5 else [])
        return "extra row"
    if op == 7:
        rows.pop(rng.randrange(m))
        return "missing row"
    if op == 8:
        rows[rng.randrange(m)] = []
        return "empty row"
    if op == 9 and nonempty:
        row = rng.choice(nonempty)
        row.reverse()
        return "reverse row"
    if op == 10 and nonempty:  # scale a row by a positive factor (HG = GA breaks unless it is 1)
        row = rng.choice(nonempty)
        c = F(rng.randint(1, 3), rng.randint(1, 3))
        for pair in row:
            pair[1] = str(F(pair[1]) * c)
        return "scale row"
    if op == 11:  # move mass along the left null space is hard in general: shift one entry to another column
        if nonempty:
            row = rng.choice(nonempty)
            pair = rng.choice(row)
            pair[0] = rng.randrange(m)
            row.sort(key=lambda p: p[0] if type(p[0]) is int else -1)
        return "move entry"
    return "none"


def null_shift(rng, rows, G):
    """Add t y to one row, y a left null vector of G on three of its rows (y G = 0): HG = GA is kept,
    only Hb <= 0, the signs and the diagonal decide -- so these mutants are often accepted."""
    m = len(G)
    r = rng.randrange(m)
    for _ in range(20):
        ks = sorted(rng.sample(range(m), 3))
        (a, b_), (c, d), (e, f) = (G[k] for k in ks)
        # y = cross product of the columns (a, c, e) and (b, d, f): y . col = 0
        y = [c * f - e * d, e * b_ - a * f, a * d - c * b_]
        if any(y):
            break
    else:
        return "none"
    t = F(rng.choice([-1, 1]), rng.randint(1, 50))
    entries = {k: F(x) for k, x in rows[r]}
    for k, yk in zip(ks, y):
        entries[k] = entries.get(k, F(0)) + t * yk
    rows[r] = [[k, str(x)] for k, x in sorted(entries.items()) if x]
    return "null shift"


def _dense(rows, m):
    H = [[F(0)] * m for _ in range(m)]
    for i, row in enumerate(rows):
        for k, x in row:
            H[i][k] = F(x)
    return H


def _truth(cert, i, path):
    """The mutated sparse matrix certifies what its claim says (independent dense Fraction check)."""
    problem = cert["problem"]
    G = [[F(x) for x in r] for r in problem["G"]]
    b = [F(x) for x in problem["b"]]
    m, n = len(G), len(G[0])
    claim = cert["claims"][i]
    H = _dense(_get(claim, path)["sparse"], m)
    HG = [[sum(H[r][k] * G[k][c] for k in range(m)) for c in range(n)] for r in range(m)]
    Hb = [sum(H[r][k] * b[k] for k in range(m)) for r in range(m)]
    if claim["type"] == "discrete_invariance":
        from exactinv_check.conditions import method_matrix_at  # the kernel's own r(dt A) (not H's check)
        A = [[F(x) for x in r] for r in problem["A"]]
        meth = problem["method"]
        num, den = [F(x) for x in meth["numerator"]], [F(x) for x in meth["denominator"]]
        Ad = method_matrix_at(A, num, den, F(claim["dt"])) if "dt" in claim else [[F(x) for x in r] for r in claim["Ad"]]
        GAd = [[sum(G[r][k] * Ad[k][c] for k in range(n)) for c in range(n)] for r in range(m)]
        return (HG == GAd and all(x >= 0 for row in H for x in row) and all(Hb[r] <= b[r] for r in range(m)))
    A = problem["A"] if "A" in problem else problem["hull"][path[1]]
    A = [[F(x) for x in r] for r in A]
    GA = [[sum(G[r][k] * A[k][c] for k in range(n)) for c in range(n)] for r in range(m)]
    ok = HG == GA and all(x <= 0 for x in Hb) and all(H[r][c] >= 0 for r in range(m) for c in range(m) if r != c)
    record = _get(claim, path[:-1]) if len(path) > 1 else claim
    if ok and record.get("value") not in (None, "oo", "-oo") and claim["type"] != "rational_threshold":
        gamma = F(record["value"])
        ok = all(H[r][r] + gamma >= 0 for r in range(m))
    if ok and claim["type"] == "rational_threshold" and claim.get("gamma_H") is not None:
        ok = all(H[r][r] + F(claim["gamma_H"]) >= 0 for r in range(m))
    if ok and claim["type"] == "robust_threshold" and claim.get("beta") is not None:
        g = F(claim["gamma"]) if claim["gamma"] not in ("oo", "-oo") else None
        floor = g if g is not None and g > 0 else 0
        ok = all(H[r][r] + floor >= 0 for r in range(m))
    return ok


def run(seconds=None, seed=0, mutants=None, log=None):
    """Fuzz until ``seconds`` pass or ``mutants`` mutants are checked; returns (mutants, accepted, false)."""
    import time
    rng = random.Random(seed)
    start, count, accepted, false = time.time(), 0, 0, []
    pool = []
    while (seconds is None or time.time() - start < seconds) and (mutants is None or count < mutants):
        if len(pool) < 6 or rng.random() < 0.1:
            cert = genuine(rng)
            if cert is None:
                continue
            assert check(copy.deepcopy(cert)).ok, "a genuine certificate was rejected"
            pool.append(cert)
        base = rng.choice(pool)
        cert = copy.deepcopy(base)
        i, path = rng.choice(_sparse_fields(cert))
        obj = _get(cert["claims"][i], path)
        m = len(cert["problem"]["G"])
        if rng.random() < 0.4:
            what = null_shift(rng, obj["sparse"], [[F(x) for x in g] for g in cert["problem"]["G"]])
        else:
            what = mutate(rng, obj["sparse"], m)
        if obj["sparse"] == _get(base["claims"][i], path)["sparse"]:
            continue  # the mutation changed nothing
        count += 1
        if check(copy.deepcopy(cert)).ok:
            accepted += 1
            if not _truth(cert, i, path):
                false.append((what, cert))
                if log:
                    log(f"FALSE ACCEPT: {what}")
    return count, accepted, false


if __name__ == "__main__":
    seconds, seed = float(sys.argv[1]), int(sys.argv[2])
    count, accepted, false = run(seconds=seconds, seed=seed, log=print)
    print(f"seed {seed}: {count} mutants, {accepted} accepted, {len(false)} accepted and false")
