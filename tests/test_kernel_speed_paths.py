"""The kernel's fast paths (issue 13) against their slow exact references:
the packed pruning test against the row-by-row test, the condition-by-condition
valid set against the plain sweep over every root, and forged certificates
that are wrong only where a condition is tangent (a double root)."""

import random
from fractions import Fraction as F

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from exactinv_check import check, polys, pruning, validset
from exactinv_check.conditions import method_matrices

big = st.integers(-(2**130), 2**130)
small = st.integers(-9, 9)


@settings(max_examples=60, deadline=None)
@given(st.data(), st.integers(1, 3))
def test_the_packed_test_is_the_row_by_row_test(data, n):
    """_Packed.outside(box) lists exactly the rows with _outside(row, box), for any
    magnitudes (the slot width follows the largest row and box entries)."""
    entries = data.draw(st.sampled_from([small, big]))
    m = data.draw(st.integers(1, 12))
    rows = []
    for _ in range(m):
        g = [data.draw(entries) for _ in range(n)]
        rows.append(([max(x, 0) for x in g] + [min(x, 0) for x in g] + [sum(map(abs, g))], data.draw(entries)))
    boxes = [[[data.draw(entries) for _ in range(2 * n)] + [abs(data.draw(entries))] for _ in range(3)]
             for _ in range(data.draw(st.integers(1, 4)))]
    table = pruning._Packed.table(rows, pruning._slot_bytes(rows, [box for per_vertex in boxes for box in per_vertex]))
    J = data.draw(st.lists(st.integers(0, m - 1), min_size=1, max_size=m, unique=True))
    packed = pruning._Packed(table, J)
    for per_vertex in boxes:
        for box in per_vertex:
            assert packed.outside(box) == [j for j in J if pruning._outside(rows[j], box)]


def test_the_slots_hold_the_rows_even_when_every_box_is_zero():
    """Regression (found by hypothesis): the slot width must cover the row entries
    themselves, not only |g . box - K b|."""
    rows = [([2**130, 0, 2**130], 1), ([0, -5, 5], -3)]
    table = pruning._Packed.table(rows, pruning._slot_bytes(rows, [[0, 0, 0]]))
    assert pruning._Packed(table, [0, 1]).outside([0, 0, 0]) == [1]


def _reference_survivors(G, b, verts, N, T):
    """Every pair tested row by row on every piece: the set the kernel must keep."""
    rows, boxes = pruning._integer_rows(G, b), pruning._boxes(verts, pruning.chord_pieces(N, T))
    return {i: sorted(j for j in range(len(rows)) if any(pruning._outside(rows[j], box) for ends in boxes[i]
                                                         for box in ends))
            for i in range(len(verts))}


@pytest.mark.parametrize("seed", range(4))
def test_survivors_are_the_pairs_of_the_row_by_row_test(seed):
    rng = random.Random(seed)
    n = rng.choice([2, 3])
    A = [[F(rng.randint(-3, 3), 4) - (i == j) for j in range(n)] for i in range(n)]
    G = [[F(rng.randint(-5, 5)) for _ in range(n)] for _ in range(12)]
    G = [g for g in G if any(g)]
    b = [F(rng.randint(1, 9), rng.randint(1, 3)) for _ in G]
    verts = [[F(rng.randint(-20, 20), rng.randint(1, 20)) for _ in range(n)] for _ in range(30)]
    _, N = method_matrices(A, [F(1), F(1), F(1, 2), F(1, 6)], [F(1)])
    T = F(rng.randint(1, 40), 16)
    order = list(range(len(verts)))
    rng.shuffle(order)
    assert pruning.survivors(G, b, verts, N, T, order) == _reference_survivors(G, b, verts, N, T)


# ---------------------------------------------------------------- the valid set, condition by condition


def _mul(*ps):
    out = [F(1)]
    for p in ps:
        out = polys.mul(out, [F(c) for c in p])
    return out


def _same(a, b):
    return len(a) == len(b) and all(
        x.lo.compare(y.lo) == 0 and x.hi.compare(y.hi) == 0 and (x.lo_closed, x.hi_closed) == (y.lo_closed, y.hi_closed)
        for x, y in zip(a, b))


def _plain(D, ineq, eq):
    """The reference: one sweep over every positive root of every condition."""
    return validset._valid_set(D, ineq, eq, len(ineq), None)


roots = st.fractions(min_value=0, max_value=4, max_denominator=6)
factor = st.one_of(
    st.tuples(roots).map(lambda r: [-r[0], 1]),  # h - r
    st.tuples(roots).map(lambda r: [r[0] ** 2, -2 * r[0], 1]),  # (h - r)^2: tangent
    st.tuples(st.integers(1, 5), st.integers(-4, 4)).map(lambda t: [t[0] + t[1] ** 2, -2 * t[1], 1]),  # no real root
)
condition = st.tuples(st.sampled_from([1, -1]), st.lists(factor, min_size=1, max_size=3)).map(
    lambda t: _mul([t[0]], *t[1]))


@settings(max_examples=120, deadline=None)
@given(st.lists(condition, min_size=1, max_size=6), st.integers(0, 3), st.sampled_from([[F(1)], [F(1), F(-1, 3)]]))
def test_condition_by_condition_is_the_plain_sweep(ineq, k, D):
    """Products of (h - r), (h - r)^2 and positive quadratics: sign changes, tangencies
    (isolated valid points, touching zeros), shared roots; any first subset."""
    ineq = [polys.integer_coefficients(p) for p in ineq]
    ineq = list(dict.fromkeys(map(tuple, ineq)))
    truth = _plain(D, [list(p) for p in ineq], [])
    assert _same(validset.valid_set(D, ineq, [], ineq[:k]), truth)


@settings(max_examples=120, deadline=None)
@given(st.lists(condition, min_size=1, max_size=6), st.integers(0, 6), st.sampled_from([[F(1)], [F(1), F(-1, 3)]]),
       st.sampled_from([[], [(0, -1, 1)], [(-1, 1)]]))
def test_starting_from_a_subsets_set_is_the_plain_sweep(ineq, k, D, eq):
    """valid_set started from the set of the first k conditions (and D) alone -- how the
    kernel reuses the pruning vertex's own set -- is the valid set of all of them, with
    or without equalities."""
    ineq = list(dict.fromkeys(map(tuple, (polys.integer_coefficients(p) for p in ineq))))
    done = ineq[:k]
    V0 = validset.valid_set(D, [], [], done)
    truth = _plain(D, [list(p) for p in ineq], [list(e) for e in eq])
    assert _same(validset.valid_set(D, ineq, [list(e) for e in eq], (), (V0, done)), truth)


@settings(max_examples=120, deadline=None)
@given(st.lists(condition, min_size=1, max_size=6), st.integers(0, 6), st.sampled_from([[F(1)], [F(1), F(-1, 3)]]))
def test_first_end_started_from_a_subsets_end_is_the_plain_first_end(ineq, k, D):
    """first_end started from the first end of the first k conditions (and D) alone is the
    first end of all of them: the same end, the same attained flag (a pole of D included)."""
    ineq = list(dict.fromkeys(map(tuple, (polys.integer_coefficients(p) for p in ineq))))
    done = ineq[:k]
    tau0, _ = validset.first_end(D, done, [])
    tau, attained = validset.first_end(D, ineq, [])
    started, started_attained = validset.first_end(D, ineq, [], (), (tau0, done))
    assert started.compare(tau) == 0 and started_attained == attained


def test_tangent_conditions_by_hand():
    one = [F(1)]
    # p1 = 2 - h >= 0 and p2 = -(h - 1)^2 >= 0: the valid set is the single point {1}
    V = validset.valid_set(one, [(2, -1), (-1, 2, -1)], [], [(2, -1)])
    assert [(str(i.lo), str(i.hi), i.lo_closed, i.hi_closed) for i in V] == [("1", "1", True, True)]
    # p2 = (h - 1)^2 (1 + h) touches 0 at 1 and stays valid: [0, 2] in one piece
    V = validset.valid_set(one, [(2, -1), (1, -1, -1, 1)], [], [(2, -1)])
    assert [(str(i.lo), str(i.hi), i.lo_closed, i.hi_closed) for i in V] == [("0", "2", True, True)]
    # an equality and a pole: {h : h (h - 1) = 0, 3 - h != 0} under 2 - h >= 0
    V = validset.valid_set([F(3), F(-1)], [(2, -1)], [(0, -1, 1)], [])
    assert [(str(i.lo), str(i.hi)) for i in V] == [("0", "0"), ("1", "1")]
    # conditions with no positive root keep an unbounded set: (1 + h)^2 > 0, h >= 0, 1 - h + h^2 > 0
    V = validset.valid_set(one, [(1, 2, 1), (0, 1), (1, -1, 1)], [], [(1, 2, 1)])
    assert [(str(i.lo), str(i.hi), i.lo_closed, i.hi_closed) for i in V] == [("0", "oo", True, False)]
    # a pole where a condition starts: h - 1 >= 0 and D = 1 - h != 0 leave (1, oo), open at 1
    V = validset.valid_set([F(1), F(-1)], [(-1, 1)], [], [])
    assert [(str(i.lo), str(i.hi), i.lo_closed, i.hi_closed) for i in V] == [("1", "oo", False, False)]
    V = validset.valid_set([F(1), F(-1)], [(-1, 1), (3, -1)], [], [(3, -1)])
    assert [(str(i.lo), str(i.hi), i.lo_closed, i.hi_closed) for i in V] == [("1", "3", False, True)]


# ------------------------------------------------- forged certificates, wrong only at a tangency


def _certificate(numerator, intervals):
    """x' = -x on P = [-1, 1], a polynomial method r with the given numerator: the conditions
    are 1 - r(-h) >= 0 and 1 + r(-h) >= 0 (vertex 1; vertex -1 gives the same)."""
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": [["-1"]], "G": [["1"], ["-1"]], "b": ["1", "1"],
                        "method": {"name": "custom", "numerator": numerator, "denominator": ["1"]}},
            "claims": [{"type": "valid_steplengths", "vertices": [["1"], ["-1"]], "rays": [], "lines": [],
                        "intervals": [{"lo": lo, "hi": hi, "lo_closed": lc, "hi_closed": hc} for lo, hi, lc, hc in intervals]}]}


# r(z) = 1 + z + 2z^2 + z^3: 1 - r(-h) = h (h - 1)^2 touches 0 at h = 1, 1 + r(-h) = 2 - h (h - 1)^2 ends the set at 2
TOUCHING = ["1", "1", "2", "1"]
# r(z) = 1 - z - 2z^2 - z^3: 1 - r(-h) = -h (h - 1)^2 <= 0, zero only at 0 and 1: the valid set is {0, 1}
ISOLATED = ["1", "-1", "-2", "-1"]


@pytest.mark.parametrize("numerator, truth, forgeries", [
    (TOUCHING, [("0", "2", True, True)],
     [[("0", "1", True, False), ("1", "2", False, True)], [("0", "1", True, True)], [("0", "2", True, False)]]),
    (ISOLATED, [("0", "0", True, True), ("1", "1", True, True)],
     [[("0", "0", True, True)], [("0", "1", True, True)], [("1", "1", True, True)]]),
])
def test_a_valid_set_wrong_only_at_a_tangency_is_rejected(numerator, truth, forgeries):
    assert check(_certificate(numerator, truth)).ok
    for forged in forgeries:
        assert not check(_certificate(numerator, forged)).ok


def _ceil(q):
    return -((-q.numerator) // q.denominator)


def _floor(q):
    return q.numerator // q.denominator


def test_boxes_are_the_outward_rounded_chords():
    """_boxes against its definition in Fractions: for each piece and each chord end, hi/lo =
    the K-scaled coordinates of X v (and of Z v = (X + Y) v) rounded up/down, B = K rho rounded up."""
    rng = random.Random(3)
    n = 3
    A = [[F(rng.randint(-3, 3), 4) - (i == j) for j in range(n)] for i in range(n)]
    verts = [[F(rng.randint(-20, 20), rng.randint(1, 20)) for _ in range(n)] for _ in range(6)]
    _, N = method_matrices(A, [F(1), F(1), F(1, 2), F(1, 6), F(1, 24)], [F(1)])
    T = F(7, 5)
    ends = pruning.nodes(T)
    K = pruning.K
    for v, mine in zip(verts, pruning._boxes(verts, pruning.chord_pieces(N, T))):
        for (t, u), (box_x, box_z) in zip(zip(ends, ends[1:]), mine):
            X, Y, M = pruning._piece(N, t, u - t)
            x = [sum(a * c for a, c in zip(row, v)) * K for row in X]
            z = [sum((a + b) * c for a, b, c in zip(rx, ry, v)) * K for rx, ry in zip(X, Y)]
            rho = max(sum(a * abs(c) for a, c in zip(row, v)) for row in M) * K
            assert box_x == [_ceil(a) for a in x] + [_floor(a) for a in x] + [_ceil(rho)]
            assert box_z == [_ceil(c) for c in z] + [_floor(c) for c in z] + [_ceil(rho)]
