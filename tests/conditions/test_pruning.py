"""Certified pruning of vertex-facet pairs (issue 13): the same exact answers as
the unpruned route, a sound bound, and a kernel that rejects what it cannot prove."""

import math
from fractions import Fraction

import flint
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pruning_helpers import fractions_of

import exactinv as ei
import exactinv.conditions.pruning as engine_pruning
from exactinv.conditions.polyhedron import ConditionSet, Kind
from exactinv_check import check
from exactinv_check.conditions import method_matrices
from exactinv_check.routes import pruning

M = ei.methods
SPIN = ei.LinearSystem([[-1, "1/4"], ["-1/4", -1]])
# an elongated octagon: x' = Ax is not invariant on it, and the Taylor-2 valid set is [0, 0] U [594/1019, 2194/1769]
DIAMOND = ei.Polyhedron.from_vertices([[10, 0], [0, 1], [-10, 0], [0, -1], [7, "7/10"], [-7, "7/10"],
                                       [7, "-7/10"], [-7, "-7/10"]])
BOX = ei.Polyhedron.box([-1, -2], [1, 2])
ROT = ei.LinearSystem([[-1, "1/2"], ["-1/2", -1]])
INSTANCES = [(SPIN, DIAMOND), (ROT, BOX), (ROT, ei.Polyhedron.from_vertices([[1, 0], [0, 1], [-1, 0], [0, -1], [2, 2]])),
             (ei.LinearSystem([[-1, 2], [0, -3]]), ei.Polyhedron.box([0, 0], [3, 1]))]
METHODS = [M.taylor(1), M.taylor(2), M.taylor(4), M.polynomial([1, 1, 0, "1/4"])]


def test_the_taylor2_valid_set_of_the_diamond_has_a_gap(forced):
    V = ei.valid_steplengths(SPIN, DIAMOND, M.taylor(2))
    assert [(iv.lo, iv.hi) for iv in V] == [(0, 0), (Fraction(594, 1019), Fraction(2194, 1769))]
    assert V.pruning.applied and check(V.certificate).ok


@pytest.mark.parametrize("S, P", INSTANCES)
@pytest.mark.parametrize("method", METHODS, ids=lambda m: m.name)
def test_pruned_and_unpruned_routes_agree(forced, S, P, method):
    V_on, V_off = ei.valid_steplengths(S, P, method), ei.valid_steplengths(S, P, method, prune=False)
    assert list(V_on) == list(V_off) and [(i.lo_closed, i.hi_closed) for i in V_on] == [(i.lo_closed, i.hi_closed) for i in V_off]
    L_on, L_off = ei.largest_threshold(S, P, method), ei.largest_threshold(S, P, method, prune=False)
    assert L_on.value == L_off.value and L_on.attained == L_off.attained
    assert V_off.pruning is None and "pruning" not in V_off.claims()[0]
    assert check(V_on.certificate).ok and check(L_on.certificate).ok and check(V_off.certificate).ok


def test_a_shared_condition_set_builds_each_pair_once(forced):
    cs = ConditionSet(SPIN, DIAMOND, M.taylor(2))
    V = ei.valid_steplengths(SPIN, DIAMOND, M.taylor(2), conditions=cs)
    built = len(cs._built)
    L = ei.largest_threshold(SPIN, DIAMOND, M.taylor(2), conditions=cs)
    assert len(cs._built) <= built  # the largest threshold's horizon is smaller: nothing new to build
    assert L.value == 0 and V.intervals[0].hi == 0
    with pytest.raises(ei.ExactinvError, match="conditions"):
        ei.valid_steplengths(SPIN, BOX, M.taylor(2), conditions=cs)


def test_the_kernel_prunes_pairs_and_keeps_the_binding_one():
    A, G, b, verts = fractions_of(SPIN, DIAMOND)
    _, N = method_matrices(A, [Fraction(1), Fraction(1)], [Fraction(1)])
    near = pruning.survivors(G, b, verts, N, Fraction(0))
    kept = sum(len(f) for f in near.values())
    assert kept < len(verts) * len(G)  # at T = 0 only the pairs with zero slack can bind
    # the pairs with zero slack (v on facet j) are exactly the ones that must be kept at T = 0
    tight = {(i, j) for i, v in enumerate(verts) for j in range(len(G)) if sum(g * x for g, x in zip(G[j], v)) == b[j]}
    assert tight <= {(i, j) for i, f in near.items() for j in f}


@settings(max_examples=25, deadline=None)
@given(st.integers(1, 4), st.fractions(0, 3).filter(lambda t: t >= 0), st.lists(st.fractions(0, 1), min_size=3, max_size=3))
def test_a_pruned_pair_holds_strictly_on_the_whole_horizon(p, T, hs):
    """Theorem of the module: every pair the kernel (or the engine) prunes on [0, T] has
    b_j - g_j A_d(h) v > 0 for h in [0, T]."""
    A, G, b, verts = fractions_of(SPIN, DIAMOND)
    method = M.taylor(p)
    _, N = method_matrices(A, list(method.numerator), list(method.denominator))
    near = pruning.survivors(G, b, verts, N, T)
    cs = ConditionSet(SPIN, DIAMOND, method)
    facets, vertices = engine_pruning.surviving_pairs(cs.G, cs.b, cs.W[Kind.VERTEX], cs.N, T)
    engine_kept = set(zip(vertices.tolist(), facets.tolist()))
    for h in [T * x for x in hs] + [T]:
        Ad = [[sum(h**k * N[k][i][l] for k in range(len(N))) for l in range(2)] for i in range(2)]
        for i, v in enumerate(verts):
            image = [sum(Ad[r][l] * v[l] for l in range(2)) for r in range(2)]
            for j in set(range(len(G))) - set(near[i]):
                assert b[j] - sum(g * x for g, x in zip(G[j], image)) > 0
            for j in range(len(G)):
                if (i, j) not in engine_kept:
                    assert b[j] - sum(g * x for g, x in zip(G[j], image)) > 0


def _cert(result):
    return result.certificate


def test_forged_horizon_below_the_vertex_bound_is_rejected(forced):
    cert = _cert(ei.valid_steplengths(SPIN, DIAMOND, M.taylor(2)))
    cert["claims"][0]["pruning"]["horizon"] = "1"  # vertex 0's own valid set reaches past 1
    report = check(cert)
    assert not report.ok and "does not bound" in str(report)


def test_forged_valid_set_with_pruning_is_rejected(forced):
    """A claim that would be right only if a binding pair were pruned: the kernel
    decides the survivors itself and finds the true end."""
    cert = _cert(ei.largest_threshold(ROT, BOX, M.taylor(2)))
    true = ei.largest_threshold(ROT, BOX, M.taylor(2)).upper
    cert["claims"][0]["value"] = str(true + 1)
    cert["claims"][0]["binding"] = None
    assert not check(cert).ok


@pytest.mark.parametrize("field, value, message", [
    ("order", [0, 0, 1, 2, 3, 4, 5, 6], "permutation"),
    ("order", [0, 1], "permutation"),
    ("horizon", "-1", "negative"),
    ("vertex", 8, "out of range"),
    ("extra", 1, "keys"),
])
def test_malformed_pruning_records_are_rejected(forced, field, value, message):
    cert = _cert(ei.valid_steplengths(SPIN, DIAMOND, M.taylor(2)))
    cert["claims"][0]["pruning"][field] = value
    report = check(cert)
    assert not report.ok and message in str(report)


def test_pruning_on_a_rational_method_is_rejected(forced):
    cert = _cert(ei.valid_steplengths(SPIN, DIAMOND, M.taylor(2)))
    cert["problem"]["method"] = {"name": "be", "numerator": ["1"], "denominator": ["1", "-1"]}
    cert["claims"][0].pop("determinant")
    report = check(cert)
    assert not report.ok and "polynomial methods only" in str(report)


def test_the_engine_grid_test_is_conservative():
    """Every pair the engine prunes is pruned by the kernel's own test too (and at least as
    much is pruned as by nothing): both are sound, the engine's grid is coarser."""
    cs = ConditionSet(SPIN, DIAMOND, M.taylor(2))
    T = Fraction(1, 8)
    facets, vertices = engine_pruning.surviving_pairs(cs.G, cs.b, cs.W[Kind.VERTEX], cs.N, T)
    kept = set(zip(vertices.tolist(), facets.tolist()))
    A, G, b, verts = fractions_of(SPIN, DIAMOND)
    _, N = method_matrices(A, [Fraction(1), Fraction(1), Fraction(1, 2)], [Fraction(1)])
    near = pruning.survivors(G, b, verts, N, T)
    assert {(i, j) for i, f in near.items() for j in f} <= kept < {(i, j) for i in range(8) for j in range(len(G))}


@pytest.mark.parametrize("method", [M.backward_euler(), M.trapezoid(), M.pade(2, 2), M.theta("1/3"), M.pade(1, 3)],
                         ids=lambda m: m.name)
@pytest.mark.parametrize("S, P", [(SPIN, DIAMOND), (ei.LinearSystem([[1, 2], [-3, -1]]), BOX)])
def test_rational_valid_sets_agree_with_direct_checks(S, P, method):
    """N(h) = D(h) r(hA) from the n x n interpolation and the Descartes pre-filter:
    membership of rational steps agrees with A_d(h) v in P checked vertex by vertex."""
    V = ei.valid_steplengths(S, P, method)
    A, G, b, verts = fractions_of(S, P)
    for k in range(0, 40):
        h = Fraction(k, 9)
        try:
            Ad = method.matrix(S, h)
        except ei.ExactinvError:  # h(hA) singular: h is no valid steplength
            assert h not in V
            continue
        inside = all(sum(g * sum(a * x for a, x in zip(row, v)) for g, row in zip(G[j], Ad)) <= b[j]
                     for v in verts for j in range(len(G)))
        assert (h in V) == inside, h


def test_any_vertex_order_gives_the_same_verdict(forced):
    """The order only groups vertices into blocks for speed: a poor one still verifies."""
    V = ei.valid_steplengths(SPIN, DIAMOND, M.taylor(3))
    cert = V.certificate
    assert "pruning" in cert["claims"][0] and check(cert).ok
    cert["claims"][0]["pruning"]["order"] = list(reversed(cert["claims"][0]["pruning"]["order"]))
    assert check(cert).ok


@pytest.mark.parametrize("call, message", [
    (lambda S, P, m: ei.ConditionSet("A", P, m), "system: expected"),
    (lambda S, P, m: ei.ConditionSet(S, "P", m), "polyhedron: expected"),
    (lambda S, P, m: ei.ConditionSet(S, P, "taylor"), "method: expected"),
    (lambda S, P, m: ei.valid_steplengths(S, P, m, conditions="cached"), "conditions: expected a ConditionSet"),
    (lambda S, P, m: ei.largest_threshold(S, P, m, conditions={}), "conditions: expected a ConditionSet"),
    (lambda S, P, m: ei.valid_steplengths(S, P, m, prune="yes"), "prune: expected True or False"),
    (lambda S, P, m: ei.largest_threshold(S, P, m, prune=1), "prune: expected True or False"),
])
def test_bad_pruning_and_condition_arguments_are_named(call, message):
    S, P, m = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(2)
    with pytest.raises(ei.ExactinvError, match=message):
        call(S, P, m)


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 4), st.lists(st.tuples(st.lists(st.integers(-40, 40), min_size=4, max_size=4),
                                             st.integers(1, 8), st.fractions(-10**4, 10**4, max_denominator=99)),
                                   min_size=1, max_size=12),
       st.sampled_from([3, 8, 24]), st.integers(0, 5))
def test_facet_grid_is_the_rounded_normalised_rows(n, rows, bits, r):
    """The integer facet grid equals round(K g / ||g||_1) (ties to even) and floor(K^2 clamp(b / (||g||_1 R)))
    computed in Fractions (small integers and K = 8 make ties)."""
    rows = [(g[:n] if any(g[:n]) else [1] * n, q, bj) for g, q, bj in rows]
    G = flint.fmpq_mat(len(rows), n, [flint.fmpq(x, q) for g, q, _ in rows for x in g])
    b = [flint.fmpq(bj.numerator, bj.denominator) for _, _, bj in rows]
    K, R = 1 << bits, 2**r
    Gt, bt = engine_pruning._facet_grid(G, b, K, R)
    for j, (g, q, bj) in enumerate(rows):
        norm = sum(abs(Fraction(x, q)) for x in g)
        assert Gt[j].tolist() == [round(Fraction(x, q) / norm * K) for x in g]
        assert bt[j] == math.floor(min(max(bj / norm / R, Fraction(-n - 4)), Fraction(n + 4)) * K * K)
