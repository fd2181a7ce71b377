"""Attacks on the pruning test (the pieces by an integer
Taylor shift per entry, ``pruning._piece`` / ``_shifted``, priced by ``pruning.pieces_cost``; the
kernel's own ``pruning.morton_order`` of the vertices) and what they touch.

What held (kept as fast regressions below):

* ``_piece`` is exactly the Fraction definition (X = A_d(t), Z = A_d(t + d), M = sum_{k>=2}
  c_k d^k |D_k|) for t = 0, d = 0, degree 0 and 1, zero, negative, huge and tiny entries,
  entries whose polynomial has trailing zero coefficients, int entries; ``_shifted`` is the
  Taylor expansion of P at t.
* Pairs that touch their facet at a rational h in [0, T] survive, in the rational route as
  well (q(h) = b_j D(h) - g_j N(h) v = 0 at a rational h in [0, T], T = sU/(1 - U), or any h
  when U = 1).
* Differential: genuine certificates (polygons, polynomial and rational methods, both claim
  types) and their mutations (record, claim, problem); every mutant the pruned route accepts is
  accepted by the unpruned route as well.

The findings were RESOURCE holes (no soundness hole found), all fixed; their tests below pass:

1. ``pruning.pieces_cost`` prices the Taylor shift of an entry by the bits of the LARGEST single
   coefficient of that entry, but ``_shifted`` works on the entry's coefficients over their
   COMMON denominator L, which is up to (deg + 1) times longer: a polynomial method whose
   coefficients a_k = 1/(10^2000 + 2k + 1) (k = 2..64; pairwise almost coprime) gives N_k =
   a_k A^k with L of 418,000 bits against a largest entry of 6,600 bits.  Price 1.2e7 (under
   WORK_BUDGET = 1e8, i.e. "about 0.2 s"), real 40 s in ``chord_pieces`` (mostly the gcds of
   the Fractions X, Z, M of 400,000-bit numbers, which the price does not count at all).
   A 127 KB genuine certificate (x' = Ax on the octahedron of R^3, A = [[0,1,0],[0,0,0],
   [0,0,-1]], vertex e2 bounding by T = 1: a TRUE claim, verified) takes 112 s.
2. ``kernel.Method`` (outside the pruning code, but on the same certificate): the reduction
   r = g/h calls ``polys.gcd(num, den)`` even when den = [1]; ``_integer_gcd`` then runs 65
   pseudo-remainder steps, each taking the content of 65 coefficients over the common
   denominator (420,000 bits): 47 s of the 112 s above, before any claim is read.  Unpriced
   (rebuild_size does not see the method's coefficient sizes either).
3. ``pruning.morton_order`` scales each coordinate linearly over the vertices' range: ONE far
   vertex (an outlier at (R, -R), R = 1e5, on a polygon of rational points of the unit circle)
   puts every other vertex into the same Morton cell, so the kernel's order is the
   certificate's listing order again (``sorted`` is stable) and a scattered listing makes every
   block box the whole polygon -- a hole found before, reopened.  Slot tests: 5.6x on 1,467
   vertices, 12.7x (11.3 s against 2.1 s) on 5,860 vertices, growing linearly with the size.
   With n > 4 only the first four coordinates are keyed: [0, 1]^4 x m-gon in R^6 (16 clusters
   of m vertices equal in the first four coordinates), its vertices shuffled within the
   clusters: 2.6x at m = 300, 4.1x (16 s against 6.6 s) at m = 1000.
   Whole check of a genuine 2 MB certificate (x' = -x, Taylor 4, the 10,254-gon of circle
   points and the far vertex, vertex 0 bounding by T = 182537/65536): 18 s with its vertices
   listed along the circle, 175 s with the same vertices shuffled (load 2-4 on 2 cores).
4. ``conditions.rebuild_size`` prices the rational route's interpolation of D and N by the
   bits of A only, not of the method's coefficients: a (4, 4) method over 4000-digit
   denominators on a 4 x 4 A, price 3e4, 140 s (load 3).  The polynomial route's condition
   polynomials have the same blind spot: the octahedron certificate of 1. with 3997-digit
   denominators (253 KB, a true claim, verified) takes 574 s: Method 189 s, the pieces about
   180 s, condition_polynomials 191 s.
5. ``pruning.pieces_cost`` counts (deg + 1)^2 / 2 + 4 (deg + 1) word operations per entry and
   piece, but the Python work per entry (the Taylor shift's loops, three Fractions) is about
   100 times that for small degrees: x' = -x on the simplex of R^200 with 1 - h + h^2 (the earlier
   certificate, 646 KB, true, verified): pieces price 2.0e7 (0.4 s), whole check 36 s; R^100:
   price 5e6, survivors 13 s of a 17 s check (profiled, load 4).
"""


import copy
import random
import signal
from fractions import Fraction as F
from math import comb

import pytest
from kernel_deadline import TooSlow
from pruning_helpers import circle_polygon, count_slot_tests, polygon_rows

import exactinv as ei
from exactinv_check import check
from exactinv_check.budget import WORK_BUDGET
from exactinv_check.conditions import method_matrices
from exactinv_check.failure import CheckFailure
from exactinv_check.kernel import Method
from exactinv_check.routes import pruning
from exactinv_check.routes import pruning_rational as kernel_rational

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


class _Deadline:
    """Raise TooSlow in the block after ``seconds`` of this process's CPU time
    (ITIMER_PROF: other processes' load does not count)."""

    def __init__(self, seconds):
        self.seconds = seconds

    def __enter__(self):
        def alarm(*_):
            raise TooSlow(f"no verdict after {self.seconds} s")
        self.old = signal.signal(signal.SIGPROF, alarm)
        signal.setitimer(signal.ITIMER_PROF, self.seconds)

    def __exit__(self, *exc):
        signal.setitimer(signal.ITIMER_PROF, 0)
        signal.signal(signal.SIGPROF, self.old)
        return False


def _reference_piece(N, t, d):
    """(X, Z, M) straight from the definition, in Fractions (the code before the integer Taylor shift)."""
    n = len(N[0])
    D = [[[sum(comb(i, k) * t ** (i - k) * N[i][r][c] for i in range(k, len(N))) for c in range(n)] for r in range(n)]
         for k in range(len(N))]
    Z = [[sum(d**k * D[k][r][c] for k in range(len(D))) for c in range(n)] for r in range(n)]
    M = [[sum(min(F(1), F(k - 1, 4)) * d**k * abs(D[k][r][c]) for k in range(2, len(D))) for c in range(n)]
         for r in range(n)]
    return D[0], Z, M


def _entry(rng):
    kind = rng.randrange(6)
    if kind == 0:
        return F(0)
    if kind == 1:
        return F(rng.randint(-9, 9), rng.randint(1, 9))
    if kind == 2:
        return F(rng.randint(-2**90, 2**90), rng.randint(1, 2**70))  # huge
    if kind == 3:
        return F(rng.randint(-3, 3), 2 ** rng.randint(50, 130))  # below the grids
    if kind == 4:
        return F(rng.randint(-9, 9), rng.choice([3, 7, 11, 10**30 + 7]))  # coprime denominators per degree
    return F(rng.randint(-10**6, 10**6))


def _random_N(rng):
    n, degree = rng.randint(1, 3), rng.choice([0, 0, 1, 1, 2, 3, 5, 8])
    N = [[[_entry(rng) for _ in range(n)] for _ in range(n)] for _ in range(degree + 1)]
    if rng.random() < 0.3:  # trailing zero coefficients
        for Nk in N[-rng.randint(1, degree + 1):]:
            for row in Nk:
                row[:] = [F(0)] * n
    return N


def _stable_A(rng):
    while True:
        A = [[F(rng.randint(-6, 6), rng.choice([1, 2, 4])) for _ in range(2)] for _ in range(2)]
        if A[0][0] + A[1][1] < 0 and A[0][0] * A[1][1] - A[0][1] * A[1][0] > 0:
            return A


def _poly_at(p, h):
    return sum(c * h**k for k, c in enumerate(p))


_METHODS = [lambda: ei.methods.taylor(2), lambda: ei.methods.taylor(4), lambda: ei.methods.rk4(),
            lambda: ei.methods.heun(), lambda: ei.methods.backward_euler(), lambda: ei.methods.pade(1, 1),
            lambda: ei.methods.pade(2, 2), lambda: ei.methods.radau_iia2()]


def _polygon(rng):
    while True:
        pts = set()
        for _ in range(rng.randint(7, 12)):  # rational points near an ellipse
            s = F(rng.randint(-40, 40), 41)
            c, si = (1 - s * s) / (1 + s * s), 2 * s / (1 + s * s)
            pts.add((F(rng.randint(1, 5)) * c, rng.choice([1, -1]) * si * F(rng.randint(1, 3), rng.randint(1, 3))))
        P = ei.Polyhedron.from_vertices([[str(x) for x in p] for p in pts])
        if P.m >= 7:
            return P


def _genuine(rng):
    for _ in range(50):
        S = ei.LinearSystem([[str(x) for x in row] for row in _stable_A(rng)])
        f = rng.choice([ei.valid_steplengths, ei.largest_threshold])
        cert = f(S, _polygon(rng), rng.choice(_METHODS)()).certificate
        if cert["claims"][-1].get("pruning"):
            return cert
    raise AssertionError("no pruned certificate")


def _nearby(rng, s):
    if s == "oo":
        return rng.choice(["1000", "0"])
    x = F(s)
    return str(x + rng.choice([F(1, 10 ** rng.randint(1, 30)), -F(1, 10 ** rng.randint(1, 30)), x / 1000]))


def _mutant(rng, cert):
    """1 to 3 mutations of the record, the claim or the problem."""
    c = copy.deepcopy(cert)
    claim = c["claims"][-1]
    record = claim["pruning"]
    rational = "variable" in record
    for op in rng.sample(range(10), rng.randint(1, 3)):
        if op == 0:
            scaled = str(F(record["horizon"]) * F(rng.randint(1, 20), rng.randint(1, 20)))
            record["horizon"] = rng.choice(["0", "1", "1/2", scaled])
            if rational and F(record["horizon"]) > 1:
                record["horizon"] = "1"
        elif op == 1:
            record["vertex"] = rng.randrange(len(claim["vertices"]))
        elif op == 2 and rational:
            record["scale"] = str(F(rng.randint(1, 100), rng.randint(1, 100)))
        elif op == 3 and rational:
            record["pieces"] = rng.randint(1, 40)
        elif op == 4 and claim["type"] == "valid_steplengths":
            interval = rng.choice(claim["intervals"])
            key = rng.choice(["lo", "hi"])
            if isinstance(interval[key], str):
                interval[key] = _nearby(rng, interval[key])
        elif op == 5 and claim["type"] == "valid_steplengths":
            interval = rng.choice(claim["intervals"])
            key = rng.choice(["lo_closed", "hi_closed"])
            interval[key] = not interval[key]
        elif op == 6 and claim["type"] == "valid_steplengths" and len(claim["intervals"]) > 1:
            del claim["intervals"][rng.randrange(len(claim["intervals"]))]
        elif op == 7:
            j = rng.randrange(len(c["problem"]["b"]))
            c["problem"]["b"][j] = str(F(c["problem"]["b"][j]) * F(rng.choice([99, 101, 1000001]), rng.choice([100, 1000000])))
        elif op == 8:
            c["problem"]["A"][rng.randrange(2)][rng.randrange(2)] = _nearby(rng, c["problem"]["A"][0][0])
        elif op == 9 and claim["type"] == "largest_threshold":
            if isinstance(claim.get("value"), str) and claim["value"] != "oo":
                claim["value"] = _nearby(rng, claim["value"])
            else:
                claim["attained"] = not claim.get("attained", True)
    return c


def _coprime_method(digits, degree=64):
    """1 - z + sum_{k>=2} z^k / (10^digits + 2k + 1): coefficients over almost coprime denominators."""
    return [F(1), F(-1)] + [F(1, 10**digits + 2 * k + 1) for k in range(2, degree + 1)]


_NILPOTENT_BLOCK = [[F(0), F(1), F(0)], [F(0), F(0), F(0)], [F(0), F(0), F(-1)]]  # A^2 e2 = 0: vertex e2's conditions are linear


def _octahedron_certificate(digits):
    """x' = Ax on the octahedron |x| + |y| + |z| <= 1 with the method above: vertex e2 = (0, 1, 0)
    moves to (-h, 1, 0), outside for every h > 0, so the valid set is [0, 0] and vertex 2 bounds
    it by T = 1 (a true claim)."""
    G = [[sx, sy, sz] for sx in (1, -1) for sy in (1, -1) for sz in (1, -1)]
    V = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]
    claim = {"type": "valid_steplengths", "vertices": [[str(x) for x in v] for v in V], "rays": [], "lines": [],
             "intervals": [{"lo": "0", "hi": "0", "lo_closed": True, "hi_closed": True}],
             "pruning": {"horizon": "1", "vertex": 2, "order": list(range(6))}}
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": [[str(x) for x in row] for row in _NILPOTENT_BLOCK], "G": [[str(x) for x in g] for g in G],
                        "b": ["1"] * 8, "method": {"name": "custom", "numerator": [str(x) for x in _coprime_method(digits)],
                                                   "denominator": ["1"]}},
            "claims": [claim]}


def _hull(points):
    """The convex hull, counter-clockwise (exact monotone chain)."""
    pts = sorted(set(points))

    def half(seq):
        out = []
        for p in seq:
            while len(out) >= 2 and ((out[-1][0] - out[-2][0]) * (p[1] - out[-2][1])
                                     - (out[-1][1] - out[-2][1]) * (p[0] - out[-2][0])) <= 0:
                out.pop()
            out.append(p)
        return out[:-1]
    return half(pts) + half(reversed(pts))


def _outlier_polygon():
    """Rational points of the unit circle (the earlier 5000-gon) and one far vertex (1e5, -1e5):
    1,467 vertices, all but the far one in one Morton cell of the kernel's 12-bit grid."""
    pts, _, _ = circle_polygon(5000)
    P = _hull(list(pts) + [(F(10**5), F(-10**5))])
    return P, *polygon_rows(P)


_ROT_TAYLOR4 = ([[F(-1), F(1, 2)], [F(-1, 2), F(-1)]], [F(1), F(1), F(1, 2), F(1, 6), F(1, 24)])


# ------------------------------------------------------------------ soundness

@pytest.mark.parametrize("seed", range(150))
def test_a_piece_is_the_fraction_definition(seed):
    rng = random.Random(seed)
    N = _random_N(rng)
    t = rng.choice([F(0), F(1), F(rng.randint(0, 100), rng.randint(1, 100)), F(rng.randint(0, 2**64), rng.randint(1, 2**64))])
    d = rng.choice([F(0), F(1), F(rng.randint(0, 100), rng.randint(1, 100)), F(rng.randint(0, 2**64), rng.randint(1, 2**64))])
    assert list(pruning._piece(N, t, d)) == list(_reference_piece(N, t, d))


def test_a_piece_of_integer_entries_and_of_the_real_nodes():
    """int entries (no Fraction) and every piece of the nodes of a 64-bit horizon."""
    rng = random.Random(7)
    N = [[[rng.randint(-5, 5) for _ in range(2)] for _ in range(2)] for _ in range(4)]
    ends = pruning.nodes(F(rng.randint(1, 2**64), rng.randint(1, 2**64)))
    for t, u in zip(ends, ends[1:]):
        assert list(pruning._piece(N, t, u - t)) == list(_reference_piece(N, t, u - t))


@pytest.mark.parametrize("seed", range(40))
def test_shifted_is_the_taylor_expansion(seed):
    """P(t + s) = sum_k e_k s^k / (L q^(deg - k)) at several s, for t of either sign."""
    rng = random.Random(seed)
    a = [_entry(rng) for _ in range(rng.randint(1, 9))]
    t = F(rng.randint(-50, 50), rng.randint(1, 50))
    e, L = pruning._shifted(a, t)
    top, q = len(a) - 1, t.denominator
    for s in (F(0), F(1), F(-3, 7), F(rng.randint(-99, 99), rng.randint(1, 99))):
        assert sum(x * (t + s) ** i for i, x in enumerate(a)) == sum(F(x, L * q ** (top - k)) * s**k for k, x in enumerate(e))


@pytest.mark.parametrize("seed", range(30))
def test_a_pair_touching_at_a_rational_h_survives_in_u(seed):
    """q(h) = b_j D(h) - g_j N(h) v_i = 0 at a rational h in [0, T] (T = sU/(1 - U); any h >= 0
    when U = 1), or q(h) < 0 there: the rational route must keep (i, j)."""
    rng = random.Random(seed)
    method = rng.choice([ei.methods.backward_euler(), ei.methods.pade(1, 1), ei.methods.pade(2, 2),
                         ei.methods.pade(1, 2), ei.methods.radau_iia2()])
    A = _stable_A(rng)
    D, N = method_matrices(A, [F(x) for x in method.numerator], [F(x) for x in method.denominator])
    s = rng.choice([F(1), F(rng.randint(1, 30), rng.randint(1, 30))])
    U = rng.choice([F(1), F(1, 2), F(rng.randint(1, 63), 64), F(rng.randint(1, 2**40), 2**40 + 1)])
    T = None if U == 1 else s * U / (1 - U)
    V = [[F(rng.randint(-9, 9), rng.randint(1, 4)) for _ in range(2)] for _ in range(rng.randint(1, 6))]
    G, b, touch = [], [], []
    for _ in range(rng.randint(1, 6)):
        g = [F(rng.randint(-9, 9), rng.randint(1, 3)) for _ in range(2)]
        g[0] = g[0] or F(1)
        i = rng.randrange(len(V))
        h = (T if T is not None else F(rng.randint(1, 10**6))) * F(rng.randint(0, 64), 64)
        Dh = _poly_at(D, h)
        image = [sum(_poly_at([Nk[r][c] for Nk in N], h) * V[i][c] for c in range(2)) for r in range(2)]
        beta = sum(x * y for x, y in zip(g, image)) / Dh + rng.choice([0, 0, F(-1, 2**rng.randint(1, 90))])
        G.append(g)
        b.append(beta)
        touch.append((i, h))
    near = kernel_rational.survivors(G, b, V, D, N, s, U, rng.choice([1, 8, 33]))
    for j, (i, h) in enumerate(touch):
        q = b[j] * _poly_at(D, h) - sum(g * sum(_poly_at([Nk[r][c] for Nk in N], h) * V[i][c] for c in range(2))
                                        for r, g in enumerate(G[j]))
        if q <= 0:
            assert j in near[i], (i, j, h)


@pytest.mark.parametrize("seed", range(8))
def test_a_mutant_accepted_when_pruned_is_accepted_unpruned(seed):
    """The unpruned route (every pair built) is the reference: a mutant whose pruned check
    passes must pass it too (else the pruning left out a pair that binds)."""
    rng = random.Random(1000 + seed)
    cert = _genuine(rng)
    assert check(cert).ok
    for _ in range(6):
        mutant = _mutant(rng, cert)
        if check(mutant).ok:
            reference = copy.deepcopy(mutant)
            del reference["claims"][-1]["pruning"]
            assert check(reference).ok


def test_the_small_octahedron_certificate_is_true():
    assert check(_octahedron_certificate(5)).ok


def test_one_far_vertex_does_not_hand_the_order_back(monkeypatch):
    """Fixed: morton_order keys the ranks of the coordinates, not their values, so one far vertex
    leaves the others spread over the grid; the scattered listing costs what the listed one does."""
    P, G, b = _outlier_polygon()
    _, N = method_matrices(_ROT_TAYLOR4[0], _ROT_TAYLOR4[1], [F(1)])
    T = F(167127, 65536)
    listed = count_slot_tests(monkeypatch, G, b, [list(p) for p in P], N, T, float("inf"))
    scattered = [list(p) for p in P]
    random.Random(1).shuffle(scattered)
    count_slot_tests(monkeypatch, G, b, scattered, N, T, 3 * listed)


# ------------------------------------------------------------------ resource

def test_the_pieces_are_priced_by_the_common_denominator():
    """Fixed: pieces_cost counts the entries' common denominators (bounded by the product of
    theirs) and the gcds of X, Z, M: this method is priced far over the budget, rejected at once."""
    _, N = method_matrices(_NILPOTENT_BLOCK, _coprime_method(2000), [F(1)])
    assert pruning.pieces_cost(N, pruning.nodes(F(1))) > WORK_BUDGET
    with _Deadline(20), pytest.raises(CheckFailure, match="pieces of the pruning test"):
        pruning.survivors([[F(1), F(1), F(1)]], [F(1)], [[F(0), F(1), F(0)]], N, F(1))


def test_the_method_reduction_is_priced():
    """Fixed: a polynomial r (h = 1) needs no gcd; a rational one is priced first
    (polys.affordable_gcd: the common denominator built under a running bound)."""
    numerator = [str(x) for x in _coprime_method(2000)]
    with _Deadline(20):
        assert Method({"numerator": numerator, "denominator": ["1"]}).is_polynomial
    with _Deadline(20), pytest.raises(CheckFailure, match="work budget"):
        Method({"numerator": numerator, "denominator": numerator})


def test_the_rational_rebuild_is_priced_by_the_method_coefficients():
    """Fixed: rebuild_size counts the method's coefficients over their common denominator."""
    base = 10**3990
    numerator = [F(1)] + [F(1, base + 2 * k + 1) for k in range(1, 5)]
    denominator = [F(1)] + [F(-1, base + 2 * k + 1001) for k in range(1, 5)]
    A = [[F(-2 if i == j else (1 if j == i + 1 else 0)) for j in range(4)] for i in range(4)]
    with _Deadline(20), pytest.raises(CheckFailure, match="work budget"):
        method_matrices(A, numerator, denominator)


def test_the_pieces_of_a_large_low_degree_problem_are_priced():
    """Fixed: pieces_cost counts the Python work of each entry (R^100, degree 2: priced at 2e8,
    3 s of pieces and 3 s of boxes measured), and the boxes are priced too: rejected at once."""
    n = 100
    A = [[F(-1 if i == j else 0) for j in range(n)] for i in range(n)]
    _, N = method_matrices(A, [F(1), F(1), F(1)], [F(1)])
    assert pruning.pieces_cost(N, pruning.nodes(F(1))) > WORK_BUDGET
    with _Deadline(20), pytest.raises(CheckFailure, match="work budget"):
        pruning.survivors([[F(1)] * n], [F(1)], [[F(0)] * n], N, F(1))
