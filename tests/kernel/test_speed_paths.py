"""The kernel's fast paths (issue 13) against their slow exact references:
the packed pruning test against the row-by-row test, the condition-by-condition
valid set against the plain sweep over every root, and forged certificates
that are wrong only where a condition is tangent (a double root)."""


import random
from fractions import Fraction as F
from types import SimpleNamespace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from exactinv_check import check, claims_thresholds, poly_arithmetic, validset
from exactinv_check.claims_invariance import check_H
from exactinv_check.conditions import method_matrices
from exactinv_check.failure import CheckFailure
from exactinv_check.rationals import integer_rows
from exactinv_check.routes import pruning

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


big = st.integers(-(2**130), 2**130)


small = st.integers(-9, 9)


def _reference_survivors(G, b, verts, N, T):
    """Every vertex against every row at every chord end, no blocks: the set the kernel must keep."""
    rows = [([max(x, 0) for x in g] + [min(x, 0) for x in g], pruning.K * beta) for g, beta in integer_rows(G, b)]
    ends = pruning._Ends(pruning.chord_pieces(N, T), [pruning.vertex_box(v) for v in verts])
    return {i: sorted(j for j in range(len(rows)) if any(pruning._outside(rows[j], box)
                                                         for box in ends.boxes(pruning.vertex_box(v))))
            for i, v in enumerate(verts)}


def _random_problem(rng, n, degree):
    A = [[F(rng.randint(-3, 3), 4) - (i == j) for j in range(n)] for i in range(n)]
    G = [[F(rng.randint(-5, 5)) for _ in range(n)] for _ in range(12)]
    G = [g for g in G if any(g)]
    b = [F(rng.randint(1, 9), rng.randint(1, 3)) for _ in G]
    verts = [[F(rng.randint(-20, 20), rng.randint(1, 20)) for _ in range(n)] for _ in range(30)]
    taylor = [F(1)]
    for k in range(1, degree + 1):
        taylor.append(taylor[-1] / k)
    _, N = method_matrices(A, taylor, [F(1)])
    return A, G, b, verts, N


def _path(N, h, v):
    return [sum(sum(h**k * N[k][r][c] for k in range(len(N))) * v[c] for c in range(len(v))) for r in range(len(v))]


def _secant_error_within_remainder(N, t, d, s):
    X, Z, M = pruning._piece(N, t, d)
    n = len(X)
    Ad = [[sum((t + s) ** k * N[k][r][c] for k in range(len(N))) for c in range(n)] for r in range(n)]
    return all(abs(Ad[r][c] - ((1 - s / d) * X[r][c] + s / d * Z[r][c])) <= M[r][c] for r in range(n) for c in range(n))


def _mul(*ps):
    out = [F(1)]
    for p in ps:
        out = poly_arithmetic.mul(out, [F(c) for c in p])
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


def _ratio_reference(A, G, b, gens):
    best = None
    for kind, vectors in (("vertex", gens.vertices), ("ray", gens.rays), ("line", gens.lines)):
        for x in vectors:
            Ax = [sum(a * c for a, c in zip(row, x)) for row in A]
            for g, beta in zip(G, b):
                rate = sum(a * c for a, c in zip(g, Ax))
                if kind == "line":
                    eps = None if rate == 0 else F(0)
                elif rate <= 0:
                    eps = None
                else:
                    eps = ((beta if kind == "vertex" else 0) - sum(a * c for a, c in zip(g, x))) / rate
                if eps is not None and (best is None or eps < best):
                    best = eps
    return best


def _rows(H):
    """The kernel's form of H (exactinv_check/sparse.py): per row, the (column, nonzero value) pairs."""
    return [[(k, x) for k, x in enumerate(row) if x] for row in H]


# ------------------------------------------------------------------ soundness

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
        rows.append(([max(x, 0) for x in g] + [min(x, 0) for x in g], data.draw(entries)))
    boxes = [[data.draw(entries) for _ in range(2 * n)] for _ in range(data.draw(st.integers(1, 6)))]
    table = pruning._Packed.table(rows, pruning._slot_bytes(rows, max(abs(x) for box in boxes for x in box)))
    J = data.draw(st.lists(st.integers(0, m - 1), min_size=1, max_size=m, unique=True))
    packed = pruning._Packed(table, J)
    for box in boxes:
        assert packed.outside(box) == [j for j in J if pruning._outside(rows[j], box)]


def test_the_slots_hold_the_rows_even_when_every_box_is_zero():
    """Regression (found by hypothesis): the slot width must cover the row entries
    themselves, not only |g . box - K b|."""
    rows = [([2**130, 0], 1), ([0, -5], -3)]
    table = pruning._Packed.table(rows, pruning._slot_bytes(rows, 0))
    assert pruning._Packed(table, [0, 1]).outside([0, 0]) == [1]


@pytest.mark.parametrize("seed", range(4))
def test_survivors_are_the_pairs_of_the_row_by_row_test(seed):
    rng = random.Random(seed)
    _, G, b, verts, N = _random_problem(rng, rng.choice([2, 3]), 3)
    T = F(rng.randint(1, 40), 16)
    order = list(range(len(verts)))
    rng.shuffle(order)
    verts = [verts[i] for i in order]  # the kernel orders the vertices itself: any listing, the same pairs
    assert pruning.survivors(G, b, verts, N, T) == _reference_survivors(G, b, verts, N, T)


def test_the_kernels_own_order_is_a_permutation_that_sorts_a_line():
    """morton_order: a permutation; in one dimension the points sorted by their coordinate;
    equal points (and a single one, or none) in their listed order."""
    line = [[F(x, 7)] for x in (5, -3, 12, 0, -3, 2)]
    order = pruning.morton_order([pruning.vertex_box(v) for v in line])
    assert [line[i][0] for i in order] == sorted(v[0] for v in line) and sorted(order) == list(range(6))
    assert pruning.morton_order([pruning.vertex_box([F(1), F(2)])] * 3) == [0, 1, 2]
    assert pruning.morton_order([]) == []
    cloud = [[F(random.Random(k).randint(-10**30, 10**30), 3) for _ in range(6)] for k in range(50)]
    assert sorted(pruning.morton_order([pruning.vertex_box(v) for v in cloud])) == list(range(50))


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 10**6), st.integers(2, 3), st.integers(1, 6), st.fractions(0, 3, max_denominator=64),
       st.lists(st.fractions(0, 1, max_denominator=1000), min_size=4, max_size=4))
def test_the_end_boxes_hold_the_path(seed, n, degree, T, xs):
    """The lemma under the pruning test: on each piece, A_d(h) v lies in the box around the
    integer boxes of the piece's two ends (the ends meet at the nodes), divided by K -- for
    random systems, vertices (rational, off the grid), Taylor degrees and horizons."""
    rng = random.Random(seed)
    _, _, _, verts, N = _random_problem(rng, n, degree)
    ends_of = pruning.nodes(T)
    ends = pruning._Ends(pruning.chord_pieces(N, T), [pruning.vertex_box(v) for v in verts])
    assert ends.count == len(ends_of)  # secants: one end per node
    for v in verts[:5]:
        boxes = ends.boxes(pruning.vertex_box(v))
        for a, (t, u) in enumerate(zip(ends_of, ends_of[1:])):
            hi = [max(x, z) for x, z in zip(boxes[a][:n], boxes[a + 1][:n])]
            lo = [min(x, z) for x, z in zip(boxes[a][n:], boxes[a + 1][n:])]
            for x in xs:
                point = _path(N, t + x * (u - t), v)
                assert all(l <= pruning.K * p <= h for l, p, h in zip(lo, point, hi))


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 10**6), st.integers(1, 3), st.integers(1, 7), st.fractions(0, 3, max_denominator=64),
       st.fractions(1, 2, max_denominator=64), st.lists(st.fractions(0, 1, max_denominator=1000), min_size=3, max_size=3))
def test_the_piece_remainder_bounds_the_secant_error(seed, n, degree, t, d, xs):
    """_piece's M bounds A_d(t + s) minus the secant from A_d(t) to A_d(t + d), entrywise, on [0, d]."""
    _, _, _, _, N = _random_problem(random.Random(seed), n, degree)
    assert all(_secant_error_within_remainder(N, t, d, x * d) for x in xs + [F(577, 1000)])


def test_the_remainder_covers_a_pure_cubic_term():
    """A_d(s) = 1 - s - 1000 s^3 on the piece [0, 1]: the secant misses by 1000 (s - s^3), largest
    (385 and a bit) at s = 1/sqrt(3) -- more than d^3/4 |D_3| = 250, within c_3 d^3 |D_3| = 500."""
    N = [[[F(1)]], [[F(-1)]], [[F(0)]], [[F(-1000)]]]
    assert _secant_error_within_remainder(N, F(0), F(1), F(577, 1000))
    assert pruning._piece(N, F(0), F(1))[2] == [[F(500)]]


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 10**6), st.integers(2, 3), st.integers(1, 5), st.fractions(0, 2, max_denominator=64),
       st.lists(st.fractions(0, 1, max_denominator=1000), min_size=6, max_size=6))
def test_a_pair_that_leaves_its_half_space_survives(seed, n, degree, T, xs):
    """Soundness of the pruning test, from the definition: whenever g_j A_d(h) v >= b_j at some
    sampled h in [0, T], the pair (v, j) is among the survivors."""
    rng = random.Random(seed)
    _, G, b, verts, N = _random_problem(rng, n, degree)
    order = list(range(len(verts)))
    rng.shuffle(order)
    verts = [verts[i] for i in order]
    near = pruning.survivors(G, b, verts, N, T)
    for h in [T * x for x in xs] + [F(0), T]:
        for i, v in enumerate(verts):
            point = _path(N, h, v)
            for j, g in enumerate(G):
                if sum(a * c for a, c in zip(g, point)) >= b[j]:
                    assert j in near[i], (h, i, j)


@settings(max_examples=120, deadline=None)
@given(st.lists(condition, min_size=1, max_size=6), st.integers(0, 3), st.sampled_from([[F(1)], [F(1), F(-1, 3)]]))
def test_condition_by_condition_is_the_plain_sweep(ineq, k, D):
    """Products of (h - r), (h - r)^2 and positive quadratics: sign changes, tangencies
    (isolated valid points, touching zeros), shared roots; any first subset."""
    ineq = [poly_arithmetic.integer_coefficients(p) for p in ineq]
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
    ineq = list(dict.fromkeys(map(tuple, (poly_arithmetic.integer_coefficients(p) for p in ineq))))
    done = ineq[:k]
    V0 = validset.valid_set(D, [], [], done)
    truth = _plain(D, [list(p) for p in ineq], [list(e) for e in eq])
    assert _same(validset.valid_set(D, ineq, [list(e) for e in eq], (), (V0, done)), truth)


@settings(max_examples=120, deadline=None)
@given(st.lists(condition, min_size=1, max_size=6), st.integers(0, 6), st.sampled_from([[F(1)], [F(1), F(-1, 3)]]))
def test_first_end_started_from_a_subsets_end_is_the_plain_first_end(ineq, k, D):
    """first_end started from the first end of the first k conditions (and D) alone is the
    first end of all of them: the same end, the same attained flag (a pole of D included)."""
    ineq = list(dict.fromkeys(map(tuple, (poly_arithmetic.integer_coefficients(p) for p in ineq))))
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


def test_the_end_boxes_are_the_rounded_bound():
    """_Ends.boxes against its definition in Fractions: at each end E (X of the first piece, then
    the secants' ends Z, one per node) with remainder W (the larger of the two pieces' M there),
    hi/lo = the K-scaled (E v)_k +- (W |v|)_k widened by the grids and rounded outwards;
    the integer box is never more than a few grid steps wider than that."""
    rng = random.Random(3)
    n = 3
    _, _, _, verts, N = _random_problem(rng, n, 4)
    T = F(7, 5)
    pieces = pruning.chord_pieces(N, T)
    ends = pruning._Ends(pieces, [pruning.vertex_box(v) for v in verts])
    matrices = [(pieces[0][0], pieces[0][2])] + [
        (Z, [[max(a, c) for a, c in zip(ra, rc)] for ra, rc in zip(M, pieces[a + 1][2])] if a + 1 < len(pieces) else M)
        for a, (X, Z, M) in enumerate(pieces)]
    K = pruning.K
    for v in verts:
        for (E, W), box in zip(matrices, ends.boxes(pruning.vertex_box(v))):
            for k in range(n):
                centre = sum(a * c for a, c in zip(E[k], v)) * K
                spread = sum(a * abs(c) for a, c in zip(W[k], v)) * K
                assert centre + spread <= box[k] <= centre + spread + 1 + K * F(2 * n * 64, 2**48)
                assert centre - spread >= box[n + k] >= centre - spread - 1 - K * F(2 * n * 64, 2**48)


@settings(max_examples=80, deadline=None)
@given(st.integers(0, 10**6), st.integers(1, 3))
def test_the_integer_ratio_tests_are_the_fraction_ones(seed, n):
    """claims_thresholds._ratio_tests (integers, cross-multiplied) against the forward-Euler ratio
    tests in Fractions, over random rational A, rows, vertices, rays and lines."""
    rng = random.Random(seed)
    q = lambda: F(rng.randint(-9, 9), rng.randint(1, 12))  # noqa: E731
    A = [[q() for _ in range(n)] for _ in range(n)]
    G = [[q() for _ in range(n)] for _ in range(rng.randint(1, 6))]
    b = [q() for _ in G]
    gens = SimpleNamespace(**{k: [[q() for _ in range(n)] for _ in range(rng.randint(0, 4))]
                              for k in ("vertices", "rays", "lines")})
    problem = SimpleNamespace(A=A, G=G, b=b)
    assert claims_thresholds._ratio_tests(problem, gens) == _ratio_reference(A, G, b, gens)


def test_a_sparse_H_is_checked_like_a_dense_one():
    """check_H reads only the nonzero entries of H's rows: a correct H passes, and each of the
    three conditions fails when one entry is spoiled."""
    # x' = -x on the square [-1, 1]^2: H = -I (HG = GA = -G, Hb = -b <= 0)
    G = [[F(1), F(0)], [F(-1), F(0)], [F(0), F(1)], [F(0), F(-1)]]
    problem = SimpleNamespace(A=[[F(-1), F(0)], [F(0), F(-1)]], G=G, b=[F(1)] * 4, n=2, m=4)
    H = [[F(-1) if i == k else F(0) for k in range(4)] for i in range(4)]
    check_H(problem, _rows(H))
    # rows 0 and 1 of G are g and -g: adding t (e_0 + e_1) to row 0 of H keeps HG = GA
    for changes, message in [({(0, 0): F(-2)}, "HG"), ({(0, 0): F(-2), (0, 1): F(-1)}, "off-diagonal"),
                             ({(1, 1): F(0)}, "HG")]:
        spoiled = [list(r) for r in H]
        for (i, k), value in changes.items():
            spoiled[i][k] = value
        with pytest.raises(CheckFailure, match=message):
            check_H(problem, _rows(spoiled))
    check_H(problem, _rows([[F(-1) + F(1, 2), F(1, 2), F(0), F(0)]] + H[1:]))  # t = 1/2: still a certificate
    # Hb <= 0: x' = 0 on the square and H with rows e_i + e_(i xor 1): HG = 0 = GA (g and -g cancel),
    # off-diagonal 1 >= 0, but Hb = (2, 2, 2, 2) > 0
    zero = SimpleNamespace(A=[[F(0), F(0)], [F(0), F(0)]], G=G, b=[F(1)] * 4, n=2, m=4)
    swap = [[F(int(k in (i, i ^ 1))) for k in range(4)] for i in range(4)]
    with pytest.raises(CheckFailure, match="Hb"):
        check_H(zero, _rows(swap))


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
