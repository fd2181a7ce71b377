"""exactinv_check.routes.pruning, attacked: the secant-chord pruning test (pruning.py: _piece, _Ends, _Packed,
blocks along ``order``) and the valid set / first end started from the pruning
vertex's own set (validset.valid_set / first_end ``start``, claims_sets._require_bound).

No soundness hole was found (see the report).  What held is kept here as fast
regressions: pairs whose path touches the facet exactly at a rational h in [0, T]
survive, for tiny, huge and negative magnitudes, T = 0, one vertex, n = 1 (checked
against the exact definition); every bounding vertex k of a genuine record gives the
same verdict as the unpruned route.

The findings were RESOURCE holes, work no budget priced before it ran; both are fixed
and their tests below pass.

1. ``pruning.chord_pieces`` (the polynomial route) built D_k = sum_i C(i, k) t^(i-k) N_i
   for every piece, k and entry with Fractions, unpriced: a 3.3 KB certificate -- x' = -x
   on a simplex in R^12, the polynomial method 1 + z + z^64, vertex 0 bounding the valid
   set [0, 1] by T = 1 -- ran 56 s.  Now an integer Taylor shift per entry (R^12: 1.4 s),
   priced first (pruning.pieces_cost).
2. ``survivors_of_pieces`` followed the record's ``order``: an order that scattered near
   vertices made every block box the whole polygon, V x ends x m slot tests, unpriced
   (the engine's genuine 10,000-gon certificate: 1.3e8 slot tests and 9.6 s with its own
   order, 2.1e9 and 156 s shuffled).  Now the kernel orders the vertices itself
   (pruning.morton_order of their gridded coordinates); the record's order is only
   shape-checked.
"""

import copy
import random
from fractions import Fraction as F

import pytest
from kernel_deadline import check_within
from pruning_helpers import circle_polygon, count_slot_tests

import exactinv as ei
from exactinv_check import check
from exactinv_check.conditions import method_matrices
from exactinv_check.routes import pruning

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)

# ------------------------------------------------------------------ soundness that held


def _value(rng, kind):
    if kind == 0:
        return F(rng.randint(-9, 9), rng.randint(1, 9))
    if kind == 1:
        return F(rng.randint(-2**80, 2**80), rng.randint(1, 2**20))  # huge
    return F(rng.randint(-9, 9), 2 ** rng.randint(40, 120))  # below the grids 2^-48 and 1/K


def _path(N, h, v):
    n = len(v)
    return [sum(sum(h**k * N[k][r][c] for k in range(len(N))) * v[c] for c in range(n)) for r in range(n)]


def _touching_instance(rng):
    """A random polynomial path and facets each touched exactly (or missed by 2^-e either way)
    by one vertex's path at a rational h in [0, T]."""
    n = rng.randint(1, 3)
    ka, kv, kg = (rng.randrange(3) for _ in range(3))
    A = [[_value(rng, ka) for _ in range(n)] for _ in range(n)]
    numerator = [F(1)] + [_value(rng, 0) for _ in range(rng.randint(1, 4))]
    numerator[-1] = numerator[-1] or F(1)
    _, N = method_matrices(A, numerator, [F(1)])
    T = rng.choice([F(0), F(1), F(rng.randint(1, 50), rng.randint(1, 50)), F(1, 2 ** rng.randint(10, 60)),
                    F(rng.randint(1, 2**63), rng.randint(1, 2**63))])
    V = [[_value(rng, kv) for _ in range(n)] for _ in range(rng.randint(1, 6))]
    G, b, touch = [], [], []
    for _ in range(rng.randint(1, 6)):
        g = [_value(rng, kg) for _ in range(n)]
        g[0] = g[0] or F(1)
        i, h = rng.randrange(len(V)), T * F(rng.randint(0, 64), 64)
        beta = sum(a * x for a, x in zip(g, _path(N, h, V[i]))) + rng.choice([0, 0, 1, -1]) * F(1, 2 ** rng.randint(1, 200))
        G.append(g)
        b.append(beta)
        touch.append((i, h))
    return G, b, V, N, T, touch


@pytest.mark.parametrize("seed", range(40))
def test_a_pair_touching_its_facet_at_a_rational_h_survives(seed):
    """Soundness from the definition at the sharpest case: g_j A_d(h) v_i >= b_j at a rational
    h in [0, T] (often with equality) forces (i, j) to survive, whatever the magnitudes."""
    rng = random.Random(seed)
    G, b, V, N, T, touch = _touching_instance(rng)
    near = pruning.survivors(G, b, V, N, T)
    for j, (i, h) in enumerate(touch):
        if sum(a * x for a, x in zip(G[j], _path(N, h, V[i]))) >= b[j]:
            assert j in near[i]
    for i, v in enumerate(V):  # and every pair at the nodes' midpoints
        for h in [T * F(a, 32) for a in range(33)]:
            point = _path(N, h, v)
            for j, g in enumerate(G):
                if sum(a * x for a, x in zip(g, point)) >= b[j]:
                    assert j in near[i]


SPIN = ei.LinearSystem([[-1, "1/4"], ["-1/4", -1]])
DIAMOND = ei.Polyhedron.from_vertices([[10, 0], [0, 1], [-10, 0], [0, -1], [7, "7/10"], [-7, "7/10"],
                                       [7, "-7/10"], [-7, "-7/10"]])


@pytest.mark.parametrize("kind", ["valid", "largest"])
def test_every_bounding_vertex_starts_the_same_set(forced, kind):
    """The valid set (first end) started from vertex k's own set is the unpruned one for every
    vertex k that bounds it: a true claim verifies whichever k and order the record names, and
    a k that does not bound is rejected as such (never a different recomputed set)."""
    f = ei.valid_steplengths if kind == "valid" else ei.largest_threshold
    cert = f(SPIN, DIAMOND, ei.methods.taylor(2)).certificate
    assert cert["claims"][-1]["pruning"] is not None and check(cert).ok
    rng = random.Random(0)
    for k in range(8):
        for horizon in (cert["claims"][-1]["pruning"]["horizon"], "1000", "1/1000"):
            forged = copy.deepcopy(cert)
            record = forged["claims"][-1]["pruning"]
            record["vertex"], record["horizon"] = k, horizon
            rng.shuffle(record["order"])
            report = check(forged)
            assert report.ok or "does not bound" in str(report), str(report)


# ------------------------------------------------------------------ resource holes


def _simplex_certificate(n, degree):
    """x' = -x on the simplex {x_i >= -1, sum x <= 1} of R^n, the method 1 + z + z^degree:
    A_d(h) = (1 - h + h^degree) I, valid set [0, 1] (vertex 0 alone bounds it by T = 1)."""
    G = [[-1 if j == i else 0 for j in range(n)] for i in range(n)] + [[1] * n]
    V = [[-1] * n] + [[n if j == i else -1 for j in range(n)] for i in range(n)]
    claim = {"type": "valid_steplengths", "vertices": [[str(x) for x in v] for v in V], "rays": [], "lines": [],
             "intervals": [{"lo": "0", "hi": "1", "lo_closed": True, "hi_closed": True}],
             "pruning": {"horizon": "1", "vertex": 0, "order": list(range(len(V)))}}
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": [["-1" if i == j else "0" for j in range(n)] for i in range(n)],
                        "G": [[str(x) for x in g] for g in G], "b": ["1"] * (n + 1),
                        "method": {"name": "custom", "numerator": ["1", "1"] + ["0"] * (degree - 2) + ["1"],
                                   "denominator": ["1"]}},
            "claims": [claim]}


def test_the_small_simplex_certificate_is_true():
    """The instance of the resource test, small: genuine, and verified."""
    assert check(_simplex_certificate(2, 6)).ok


def test_the_chord_pieces_of_a_high_degree_method_are_priced():
    """Fixed: the pieces are built by an integer Taylor shift per entry (R^16, degree 64: 2.5 s
    instead of about 100 s) and priced first (pruning.pieces_cost); R^24 is over the price and
    rejected at once (the deadline only guards against a hang)."""
    report = check_within(_simplex_certificate(24, 64), 30)
    assert not report.ok and "pieces of the pruning test" in str(report)


def _polygon_certificate(m, order):
    pts, G, b = circle_polygon(m)
    s = str
    claim = {"type": "valid_steplengths", "vertices": [[s(x) for x in p] for p in pts], "rays": [], "lines": [],
             "intervals": [{"lo": "0", "hi": "1", "lo_closed": True, "hi_closed": True}],
             "pruning": {"horizon": "167127/65536", "vertex": 0, "order": order(len(pts))}}
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": [["-1", "1/2"], ["-1/2", "-1"]], "G": [[s(x) for x in g] for g in G], "b": [s(x) for x in b],
                        "method": {"name": "taylor(4)", "numerator": ["1", "1", "1/2", "1/6", "1/24"], "denominator": ["1"]}},
            "claims": [claim]}


def _scattered(V):
    order = list(range(V))
    random.Random(1).shuffle(order)
    return order


def _slot_tests(monkeypatch, m, order, limit):
    """The packed slot tests of pruning.survivors on the m-gon, its vertices listed in the given order."""
    pts, G, b = circle_polygon(m)
    _, N = method_matrices([[F(-1), F(1, 2)], [F(-1, 2), F(-1)]], [F(1), F(1), F(1, 2), F(1, 6), F(1, 24)], [F(1)])
    return count_slot_tests(monkeypatch, G, b, [list(pts[i]) for i in order(len(pts))], N, F(167127, 65536), limit)


def test_a_scattered_order_is_priced(monkeypatch):
    """The 1500-gon's slot tests with its vertices listed in order and scattered: the scattered
    listing must not cost 5 times more (it cost about 10 times when the kernel followed the
    record's order, the ratio growing linearly with the size: 8x at 1000, 12x at 3000, 11x at
    4000 -- 13.5 s against 1.4 s).  Fixed: the kernel orders the vertices itself
    (pruning.morton_order), so the listing does not matter."""
    own = _slot_tests(monkeypatch, 1500, lambda V: list(range(V)), float("inf"))
    _slot_tests(monkeypatch, 1500, _scattered, 5 * own)
