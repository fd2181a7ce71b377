"""A seeded mutation fuzzer of genuine lp records with dual pieces (tests/kernel/test_lp_duals_attacks.py):
random problems (bounded polytopes, unbounded P with rays, P with lines), every method family, certified by
the engine's LP route with dual pieces forced on; each record mutated one dual-piece field at a time (an
entry scaled, negated, made a tiny negative, added on another row or a line row, dropped, its row moved out
of range, negative or duplicated; a vector y_K appended; the piece's end moved outward or to oo; a basis or
ray piece replaced by a dual piece, a facet made one dual piece; b or A nudged).  Every record the kernel
accepts must give the vertex route's exact valid set of its problem."""

import copy
import itertools
import json
import random
from fractions import Fraction as F

from lp_record_sets import kernel_set, same

import exactinv as ei
from exactinv.validset import lp_route as engine_lp

M = ei.methods
METHODS = [M.taylor(1), M.taylor(2), M.taylor(3), M.taylor(4), M.backward_euler(), M.pade(1, 1), M.pade(1, 2)]


def random_problem(rng, dims, shape):
    """(A, G, b, method) of one shape: "bounded" (random rows and a box), "rays" (random rows g with
    g . 1 < 0, so 1 is a ray), "lines" (the last coordinate free: a line e_n)."""
    n = rng.choice(dims)
    k = n - 1 if shape == "lines" else n
    rows = []
    while len(rows) < rng.randint(k + 1, 2 * k + 2):
        g = [rng.randint(-4, 4) for _ in range(k)]
        if shape == "rays":
            s = sum(g)
            if s == 0:
                continue
            g = g if s < 0 else [-v for v in g]
        if any(g):
            rows.append(g)
    if shape == "bounded":
        rows += [[int(i == j) * s for j in range(k)] for i in range(k) for s in (1, -1)]
    if shape == "lines":
        rows += [[int(i == j) * s for j in range(k)] for i in range(k) for s in (1, -1)]
        rows = [g + [0] for g in rows]
    b = [rng.randint(1, 3) for _ in rows]
    A = [[F(-rng.randint(1, 2) if i == j else 0) + F(rng.randint(-3, 3), rng.choice([4, 8, 12])) for j in range(n)]
         for i in range(n)]
    if shape == "lines" and rng.random() < 0.7:
        for i in range(k):
            A[i][n - 1] = F(0)  # A e_n in the line: P may stay invariant
    return A, rows, b, rng.choice(METHODS)


def _duals(facets):
    return [(i, k) for i, f in enumerate(facets) for k, p in enumerate(f["bases"]) if isinstance(p, dict)
            and "dual" in p]


def mutate(rng, problem, record):
    """(problem, record) with one field changed, or None when the chosen kind does not apply."""
    pr, rec = copy.deepcopy(problem), copy.deepcopy(record)
    facets = rec["facets"]
    rows = len(pr["G"]) + len(rec.get("lines", []))
    where = _duals(facets)
    if not where:
        return None
    i, k = rng.choice(where)
    f = facets[i]
    y = f["bases"][k]["dual"]
    nonempty = [j for j, v in enumerate(y) if v]
    kind = rng.randrange(14)
    if kind <= 4 and not nonempty:
        return None
    if kind <= 4:
        j = rng.choice(nonempty)
        e = rng.randrange(len(y[j]))
        r, v = y[j][e]
        if kind == 0:  # scaled
            y[j][e][1] = str(F(v) * (1 + F(rng.choice([1, -1]), 10 ** rng.randint(1, 30))))
        elif kind == 1:  # negated or a tiny negative
            y[j][e][1] = rng.choice(["-" + v, f"-1/{10 ** rng.randint(1, 60)}"])
        elif kind == 2:  # dropped
            del y[j][e]
        elif kind == 3:  # its row moved: out of range, negative, duplicated, or another row (a line row too)
            y[j][e][0] = rng.choice([rows, rows + 1, -1, -rows, r + 1, r - 1, rng.randrange(rows)])
        else:  # a duplicate of the entry (the same row twice), or split in two entries of one row
            half = str(F(v) / 2)
            y[j][e:e + 1] = rng.choice([[[r, v], [r, v]], [[r, half], [r, half]]])
    elif kind == 5:  # an entry added on a row (a line row, when P has lines)
        j = rng.randrange(len(y))
        r = rng.randrange(len(pr["G"]), rows) if rows > len(pr["G"]) and rng.random() < 0.5 else rng.randrange(rows)
        y[j] = sorted([e for e in y[j] if e[0] != r] + [[r, str(F(1, 10 ** rng.randint(0, 20)))]])
    elif kind == 6:  # an extra vector y_K: a copy, empty, or a small entry
        y.append(rng.choice([copy.deepcopy(y[-1]), [], [[rng.randrange(rows), "1/1000"]]]))
    elif kind == 7:  # the piece's end moved outward (or to oo)
        e = f["ends"][k]
        if e == "oo":
            return None
        if isinstance(e, dict):
            f["ends"][k] = str(F(e["interval"][1]) * (1 + F(1, 10 ** rng.randint(1, 8))))
        else:
            f["ends"][k] = rng.choice(["oo", str(F(e) * (1 + F(1, 10 ** rng.randint(1, 12)))), str(F(e) * 2)])
        if f["ends"][k] != "oo" and k + 1 < len(f["ends"]) and f["ends"][k + 1] != "oo" \
                and not isinstance(f["ends"][k + 1], dict) and F(f["ends"][k + 1]) <= F(f["ends"][k]):
            return None
    elif kind == 8 and k + 1 < len(f["ends"]):  # the dual piece absorbs the next piece
        del f["ends"][k]
        del f["bases"][k + 1]
    elif kind == 9:  # another piece (basis or ray) of some facet replaced by this dual piece
        j = rng.randrange(len(facets))
        t = rng.randrange(len(facets[j]["bases"]))
        facets[j]["bases"][t] = {"dual": copy.deepcopy(y)}
    elif kind == 10:  # the whole facet one dual piece [0, oo), or every facet
        for g in (facets if rng.random() < 0.3 else [f]):
            g["ends"], g["bases"] = ["oo"], [{"dual": copy.deepcopy(y)}]
    elif kind == 11:  # the dual piece starts earlier or later: the previous end moved (anchor != true start)
        if k == 0 or isinstance(f["ends"][k - 1], dict):
            return None
        t = F(f["ends"][k - 1])
        f["ends"][k - 1] = str(t * (1 + F(rng.choice([1, -1]), 10 ** rng.randint(1, 6))))
    elif kind == 12:  # b nudged, the record kept
        j = rng.randrange(len(pr["b"]))
        pr["b"][j] = str(F(pr["b"][j]) - F(1, rng.choice([2, 10, 1000])))
    elif kind == 13:  # A nudged, the record kept
        r, s = rng.randrange(len(pr["A"])), rng.randrange(len(pr["A"]))
        pr["A"][r][s] = str(F(pr["A"][r][s]) + F(rng.choice([1, -1]), rng.choice([2, 10, 1000])))
    else:
        return None
    return pr, rec


def truth(problem, method):
    """The vertex route's exact valid set of a problem (certificate intervals)."""
    A = [[F(x) for x in r] for r in problem["A"]]
    G = [[F(x) for x in r] for r in problem["G"]]
    b = [F(x) for x in problem["b"]]
    V = ei.valid_steplengths(ei.LinearSystem(A), ei.Polyhedron(G, b), method, route="vertex")
    return V.certificate["claims"][0]["intervals"]


def genuine(rng, dims, shapes, policy=None, wanted=None, tries=None):
    """One genuine certificate with at least one dual piece (or, with ``wanted(facets)``, one where that is
    true): (problem, record, method); None after ``tries`` problems (None: until one is found).  The engine
    runs under ``policy`` (default: a dual piece as early as possible)."""
    old = engine_lp.DUAL_POLICY
    engine_lp.DUAL_POLICY = policy or engine_lp.DualPolicy(F(0), 0, 1)
    wanted = wanted or _duals
    try:
        for _ in itertools.count() if tries is None else range(tries):
            A, G, b, method = random_problem(rng, dims, rng.choice(shapes))
            try:
                P = ei.Polyhedron(G, b)
                V = ei.valid_steplengths(ei.LinearSystem(A), P, method, route="lp")
            except (ei.ExactinvError, engine_lp.LPRouteDeclined):
                continue
            claim = V.certificate["claims"][0]
            if "lp" in claim and wanted(claim["lp"]["facets"]):
                return V.certificate["problem"], claim["lp"], method
    finally:
        engine_lp.DUAL_POLICY = old
    return None


def fuzz(seed, problems, mutations, dims=(2, 3), shapes=("bounded", "rays", "lines"), genuine_record=None,
         mutate_record=None):
    """(tried, accepted, false accepts): mutants of genuine dual-piece records; a false accept is an accepted
    mutant whose valid set is not the vertex route's.  ``genuine_record(rng, dims, shapes)`` and
    ``mutate_record(rng, problem, record)`` (default :func:`genuine` and :func:`mutate`) make the records
    and their mutants (tests/kernel/lp_chain_fuzz.py: chained dual pieces)."""
    genuine_record, mutate_record = genuine_record or genuine, mutate_record or mutate
    rng = random.Random(seed)
    tried = accepted = 0
    bad = []
    for _ in range(problems):
        problem, record, method = genuine_record(rng, dims, shapes)
        W = kernel_set(problem, record)
        assert W is not None and same(W, truth(problem, method)), json.dumps(record)
        truths = {}
        for _ in range(mutations):
            out = mutate_record(rng, problem, record)
            if out is None:
                continue
            pr, rec = out
            tried += 1
            W = kernel_set(pr, rec)
            if W is None:
                continue
            accepted += 1
            key = json.dumps(pr)
            if key not in truths:
                try:
                    truths[key] = truth(pr, method)
                except ei.ExactinvError:
                    truths[key] = None  # e.g. P made empty by a nudged b: the kernel must not accept it
            if truths[key] is None or not same(W, truths[key]):
                bad.append((pr, rec))
    return tried, accepted, bad
