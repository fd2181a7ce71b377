"""Red team of the LP route on P with lines (exactinv_check/routes/lp_pieces.py, the ``lines`` key; issue 22/23 rule).

The kernel decides an ``lp`` record on P' = P with the lines l_j appended as rows l_j^T x <= 0 and rebuilds the
line equalities g_i N(h) l_j = 0 itself (docs/design.md, "P with lines").  Attacks: seeded mutations of genuine
records (bases, ends, point pieces, pieces dropped, lines scaled, duplicated, combined, rays along a line), each
accepted mutant's valid set -- the kernel's own, from the mutated record -- compared with the genuine record's,
which equals the vertex route's; and forgeries crafted from scratch (a missing line hidden behind ray pieces,
dependent lines, a line not in ker G or the zero vector).  Nothing was found: every accepted mutant gives the
true set (4,357 mutants in the red team's longer run, 1,465 accepted, none with another set).
"""


import copy
import random
from fractions import Fraction as F

import pytest

import exactinv as ei
import exactinv_check
from exactinv_check import budget
from exactinv_check.failure import CheckFailure
from exactinv_check.kernel import Problem
from exactinv_check.routes import lp_pieces
from exactinv_check.validset import valid_set

M = ei.methods


def _kernel_set(problem, record):
    """The valid set the kernel derives from an lp record (every piece proved, the horizon checked), as text."""
    with budget.account(time_limit=60):
        _, D, inequalities, equalities, horizon = lp_pieces.lp_conditions(problem, record)
        lp_pieces.require_horizon(D, inequalities, equalities, horizon, {}, ("set",))
        return repr(valid_set(D, list(inequalities), list(equalities)))


def _genuine(A, G, b, method):
    S, P = ei.LinearSystem(A), ei.Polyhedron(G, b)
    V = ei.valid_steplengths(S, P, method, route="lp")
    W = ei.valid_steplengths(S, P, method, route="vertex")
    assert [(iv.lo, iv.hi, iv.lo_closed, iv.hi_closed) for iv in V] == \
        [(iv.lo, iv.hi, iv.lo_closed, iv.hi_closed) for iv in W]
    cert = V.certificate
    assert exactinv_check.check(cert).ok
    return cert, Problem(cert["problem"], cert["version"]), cert["claims"][0]["lp"]


def _mutate(rng, record, n, m):
    """One random mutation of an lp record (a deep copy)."""
    rec = copy.deepcopy(record)
    f = rng.choice(rec["facets"])
    rows = m + len(rec.get("lines", []))
    K = len(f["ends"])
    k = rng.randrange(K)
    t = str(F(rng.randint(0, 40), rng.randint(1, 8)))
    kind = rng.randrange(11)
    if kind == 0:  # another basis, possibly with line rows
        f["bases"][k] = rng.sample(range(rows), n)
    elif kind == 1:  # an end moved
        f["ends"][k] = t
    elif kind == 2 and K > 1:  # two pieces merged under one basis (a breakpoint skipped)
        del f["ends"][k]
        del f["bases"][rng.choice([k, min(k + 1, K - 1)])]
    elif kind == 3:  # a point piece at a random rational, with a random basis
        f["ends"][k:k] = [t, t]
        f["bases"][k:k] = [rng.sample(range(rows), n), f["bases"][k]]
    elif kind == 4 and "lines" in rec:  # a line scaled
        j = rng.randrange(len(rec["lines"]))
        c = rng.choice([-1, 2, F(1, 3)])
        rec["lines"][j] = [str(F(x) * c) for x in rec["lines"][j]]
    elif kind == 5 and "lines" in rec and len(rec["lines"]) < n - 1:  # a dependent line appended
        rec["lines"].append(list(rec["lines"][0]))
    elif kind == 6 and "lines" in rec and len(rec["lines"]) == 2:  # the second line replaced by l_1 + l_2
        rec["lines"][1] = [str(F(x) + F(y)) for x, y in zip(*rec["lines"])]
    elif kind == 7 and "lines" in rec:  # a ray piece along a line (l or -l): a direction of P
        f["bases"][k] = {"ray": [str(F(x) * rng.choice([1, -1])) for x in rng.choice(rec["lines"])]}
        rec.setdefault("point", ["0"] * n)
    elif kind == 8 and K > 1:  # the last piece dropped (a shorter horizon)
        f["ends"].pop()
        f["bases"].pop()
    elif kind == 9:  # the last end moved
        f["ends"][-1] = t
    elif kind == 10 and K > 1:  # adjacent bases swapped
        f["bases"][k], f["bases"][(k + 1) % K] = f["bases"][(k + 1) % K], f["bases"][k]
    return rec


PROBLEMS = [  # (A, G, b, method): a slab whose line feeds the facet, a strip x interval, a rotated slab, two lines
    ([[-1, 1], [0, -1]], [[1, 0], [-1, 0]], [1, 1], M.taylor(2)),
    ([[-1, 0, 0], [0, -2, 0], [1, 0, -1]], [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0]], [1, 1, 2, 2], M.taylor(3)),
    ([[F(-3, 2), F(1, 2)], [F(1, 2), F(-3, 2)]], [[1, 1], [-1, -1]], [1, 1], M.pade(1, 1)),
    ([[-1, 0, 0], [1, -1, 0], [0, 1, -1]], [[1, 1, -1], [-1, -1, 1]], [1, 2], M.taylor(2)),
]


# ------------------------------------------------------------------ soundness

@pytest.mark.parametrize("index", range(len(PROBLEMS)))
def test_accepted_mutants_of_genuine_lines_records_give_the_true_set(index):
    """Every mutant the kernel accepts yields the genuine (= vertex route's) valid set; some are rejected and
    some accepted (the mutations are not all no-ops, nor all caught by parsing)."""
    A, G, b, method = PROBLEMS[index]
    _, problem, record = _genuine(A, G, b, method)
    assert "lines" in record
    truth = _kernel_set(problem, record)
    rng = random.Random(2300 + index)
    accepted = rejected = 0
    for _ in range(80):
        mutant = _mutate(rng, record, len(A), len(G))
        if mutant == record:
            continue
        try:
            got = _kernel_set(problem, mutant)
        except CheckFailure:
            rejected += 1
            continue
        accepted += 1
        assert got == truth, (mutant, got, truth)
    assert rejected > 0 and accepted > 0


def test_a_missing_line_cannot_be_hidden_behind_ray_pieces():
    """The slab with A = [[-1, 1], [0, -1]], Taylor(2): V = {0, 1} (the line (0, 1) leaves the slab unless
    h r'(-h) = h (1 - h) = 0).  Without its line no basis of G is nonsingular, so a forger covers (0, oo) by ray
    pieces along the line: +l on (0, 1), -l on (1, oo).  The end 1 is a root of (g N l) D: neither ray covers it,
    so the record (which would claim V = {0}) is rejected; h = 1 is a genuine valid step."""
    cert, problem, record = _genuine([[-1, 1], [0, -1]], [[1, 0], [-1, 0]], [1, 1], M.taylor(2))
    forged = {"facets": [{"ends": ["1", "oo"], "bases": [{"ray": ["0", "1"]}, {"ray": ["0", "-1"]}]},
                         {"ends": ["1", "oo"], "bases": [{"ray": ["0", "-1"]}, {"ray": ["0", "1"]}]}],
              "point": ["0", "0"]}
    with pytest.raises(CheckFailure, match="covered by neither"):
        _kernel_set(problem, forged)
    bad = copy.deepcopy(cert)
    bad["claims"][0]["lp"] = forged
    assert [iv["lo"] for iv in bad["claims"][0]["intervals"]] == ["0", "1"]
    bad["claims"][0]["intervals"] = bad["claims"][0]["intervals"][:1]  # the forger's V = {0}
    report = exactinv_check.check(bad)
    assert not report.ok and "covered by neither" in str(report)


def test_dependent_or_partial_lines_leave_every_basis_singular():
    """ker G = span{e_2, e_3} (the slab |x_1| <= 1 in R^3): the lines e_2 and 2 e_2 are dependent, so a basis
    holding rows of both is singular, and one holding only one of them misses e_3 -- rejected either way."""
    A = [[-1, 0, 0], [0, -1, 0], [1, 1, -1]]
    cert, problem, record = _genuine(A, [[1, 0, 0], [-1, 0, 0]], [1, 1], M.taylor(1))
    assert len(record["lines"]) == 2
    forged = copy.deepcopy(record)
    forged["lines"] = [["0", "1", "0"], ["0", "2", "0"]]
    with pytest.raises(CheckFailure, match="singular"):
        _kernel_set(problem, forged)
    assert _kernel_set(problem, record)  # the genuine record is accepted


def test_a_line_not_in_ker_g_or_zero_is_rejected_first():
    _, problem, record = _genuine([[-1, 1], [0, -1]], [[1, 0], [-1, 0]], [1, 1], M.taylor(2))
    for line, words in ((["1", "1"], "not in ker G"), (["0", "0"], "zero vector"),
                        (["1/1000000000000", "1"], "not in ker G")):
        forged = copy.deepcopy(record)
        forged["lines"] = [line]
        with pytest.raises(CheckFailure, match=words):
            _kernel_set(problem, forged)


# ------------------------------------------------------------------ resource

def test_largest_threshold_forgeries_on_lines_records():
    """The slab whose line feeds the facet (V = {0, 1} for Taylor(2): the largest threshold is 0, attained, bound by
    the line's equality h (1 - h) = 0) and the invariant-line slab (V = [0, 2]): every other (value, attained) and a
    forged line binding are rejected; only the true claim (= the vertex route's) passes."""
    for A, method in (([[-1, 1], [0, -1]], M.taylor(2)), ([[-1, 0], [0, -1]], M.taylor(2))):
        S, P = ei.LinearSystem(A), ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])
        L = ei.largest_threshold(S, P, method, route="lp")
        W = ei.largest_threshold(S, P, method, route="vertex")
        assert (L.value, L.attained) == (W.value, W.attained)
        cert = L.certificate
        assert exactinv_check.check(cert).ok and "lines" in cert["claims"][0]["lp"]
        accepted = []
        for value in ("0", "1", "2", "1/2", "oo"):
            for attained in (True, False):
                forged = copy.deepcopy(cert)
                forged["claims"][0].update(value=value, attained=attained)
                forged["claims"][0].pop("binding", None)
                if exactinv_check.check(forged).ok:
                    accepted.append((F(value), attained))
        assert accepted == [(L.value, L.attained)]
        forged = copy.deepcopy(cert)
        forged["claims"][0]["binding"] = {"kind": "line", "generator": 0, "facet": 1, "poly": ["1", "-1"]}
        assert not exactinv_check.check(forged).ok
