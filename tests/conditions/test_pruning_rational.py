"""Certified pruning of rational methods in u = h/(s + h) (issue 13): the same exact
answers as the unpruned route, a sound test up to h = oo, and a kernel that rejects
every record it cannot prove."""

import copy
import math
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pruning_helpers import fractions_of

import exactinv as ei
import exactinv.conditions.pruning as engine_pruning
from exactinv.conditions import pruning_rational as engine_rational
from exactinv.conditions.polyhedron import ConditionSet
from exactinv_check import check
from exactinv_check.conditions import method_matrices
from exactinv_check.failure import CheckFailure
from exactinv_check.routes import pruning_rational as kernel_rational

M = ei.methods
SPIN = ei.LinearSystem([[-1, "1/4"], ["-1/4", -1]])
DIAMOND = ei.Polyhedron.from_vertices([[10, 0], [0, 1], [-10, 0], [0, -1], [7, "7/10"], [-7, "7/10"],
                                       [7, "-7/10"], [-7, "-7/10"]])
# an octagon with the origin as a vertex: x' = -x pulls every point towards 0, which it reaches only at h = oo
CORNER = ei.Polyhedron.from_vertices([[0, 0], [4, 0], [6, 1], [7, 3], [6, 5], [4, 6], [1, 5], [0, 3]])
DECAY = ei.LinearSystem([[-1, 0], [0, -1]])
RATIONAL = [M.backward_euler(), M.trapezoid(), M.pade(2, 2), M.theta("1/3"), M.pade(1, 3), M.pade(3, 3),
            M.pade(2, 1)]


def _image_slack(S, P, method, h, i, j):
    """b_j - g_j r(hA) v_i, exactly (the slack of vertex i at facet j after one step)."""
    Ad = method.matrix(S, h)
    v = [Fraction(x) for x in P.vertices[i]]
    image = [sum(Fraction(a) * x for a, x in zip(row, v)) for row in Ad]
    return Fraction(P.b[j]) - sum(Fraction(g) * x for g, x in zip(P.G[j], image))


def _agree(S, P, method):
    V_on, V_off = ei.valid_steplengths(S, P, method), ei.valid_steplengths(S, P, method, prune=False)
    assert list(V_on) == list(V_off)
    assert [(i.lo_closed, i.hi_closed) for i in V_on] == [(i.lo_closed, i.hi_closed) for i in V_off]
    L_on, L_off = ei.largest_threshold(S, P, method), ei.largest_threshold(S, P, method, prune=False)
    assert L_on.value == L_off.value and L_on.attained == L_off.attained
    return V_on, L_on


@pytest.mark.parametrize("S, P", [(SPIN, DIAMOND), (DECAY, CORNER)], ids=["spin-diamond", "decay-corner"])
@pytest.mark.parametrize("method", RATIONAL, ids=lambda m: m.name)
def test_pruned_and_unpruned_routes_agree(forced, S, P, method):
    V, L = _agree(S, P, method)
    for result in (V, L):
        record = result.claims()[0].get("pruning")
        if record is not None:
            assert record["variable"] == "h/(s+h)" and 0 <= Fraction(record["horizon"]) <= 1
        assert check(result.certificate).ok


@st.composite
def polygons(draw):
    """A random convex polygon with 7 to 10 vertices (so n/m <= 0.3 and pruning applies)."""
    k = draw(st.integers(7, 10))
    radii = draw(st.lists(st.integers(2, 9), min_size=k, max_size=k))
    points = [[Fraction(round(r * 8 * math.cos(2 * math.pi * a / k))), Fraction(round(r * 8 * math.sin(2 * math.pi * a / k)))]
              for a, r in enumerate(radii)]
    return ei.Polyhedron.from_vertices(points)


@settings(max_examples=12, deadline=None)
@given(polygons(), st.sampled_from(RATIONAL), st.integers(-3, 3), st.integers(1, 4))
def test_pruned_equals_unpruned_on_random_polygons(P, method, skew, decay):
    engine_pruning.WORTHWHILE, saved = 1.0, engine_pruning.WORTHWHILE
    try:
        if P.m < 7:
            return
        S = ei.LinearSystem([[-decay, Fraction(skew, 4)], [Fraction(-skew, 4), -decay]])
        V, L = _agree(S, P, method)
        assert check(V.certificate).ok and check(L.certificate).ok
    finally:
        engine_pruning.WORTHWHILE = saved


@settings(max_examples=15, deadline=None)
@given(st.sampled_from(RATIONAL), st.lists(st.fractions(0, 1).filter(lambda x: x < 1), min_size=4, max_size=4))
def test_a_pair_pruned_in_u_holds_strictly_for_every_h(method, us):
    """The theorem of the module: a pair pruned on [0, 1] in u (engine or kernel) has
    b_j - g_j r(hA) v > 0 at every h >= 0 -- tried at h = s u/(1 - u), up to h near oo."""
    S, P = SPIN, DIAMOND
    cs = ConditionSet(S, P, method)
    s = engine_rational.scale_of(cs.D)
    f, v = engine_rational.rational_survivors(cs, s, Fraction(1), 8)
    engine_kept = set(zip(v.tolist(), f.tolist()))
    A, G, b, verts = fractions_of(S, P)
    D, N = method_matrices(A, list(method.numerator), list(method.denominator))
    near = kernel_rational.survivors(G, b, verts, D, N, s, Fraction(1), 8)
    kernel_kept = {(i, j) for i, fs in near.items() for j in fs}
    for u in us + [Fraction(999, 1000)]:
        h = s * u / (1 - u)
        for i in range(len(verts)):
            for j in range(len(G)):
                if (i, j) not in engine_kept or (i, j) not in kernel_kept:
                    assert _image_slack(S, P, method, h, i, j) > 0


def test_a_pair_that_touches_only_at_h_infinity_survives():
    """Backward Euler, x' = -x: r(hA)v = v/(1 + h) reaches the vertex 0 of CORNER only as h -> oo,
    so a pair (v, j) with facet j through 0 has slack > 0 for every h and -> 0: the strict test
    at u = 1 cannot drop it (the kernel keeps it, and decides it exactly)."""
    method = M.backward_euler()
    A, G, b, verts = fractions_of(DECAY, CORNER)
    D, N = method_matrices(A, list(method.numerator), list(method.denominator))
    near = kernel_rational.survivors(G, b, verts, D, N, Fraction(1), Fraction(1), 8)
    through_zero = [j for j in range(len(G)) if b[j] == 0]
    far = [i for i, v in enumerate(verts) if any(sum(g * x for g, x in zip(G[j], v)) < 0 for j in through_zero)]
    assert far and all(any(j in near[i] for j in through_zero if sum(g * x for g, x in zip(G[j], verts[i])) < 0)
                       for i in far)
    assert list(ei.valid_steplengths(DECAY, CORNER, method)) == list(ei.valid_steplengths(DECAY, CORNER, method, prune=False))


def _pruned_certificate(S=SPIN, P=DIAMOND, method=None, largest=False):
    method = method or M.backward_euler()
    engine_pruning.WORTHWHILE, saved = 1.0, engine_pruning.WORTHWHILE
    try:
        result = (ei.largest_threshold if largest else ei.valid_steplengths)(S, P, method)
    finally:
        engine_pruning.WORTHWHILE = saved
    cert = copy.deepcopy(result.certificate)
    assert "pruning" in cert["claims"][0] and check(cert).ok
    return cert


@pytest.mark.parametrize("field, value, message", [
    ("variable", "h/(1+h)", "pruning variable must be"),
    ("variable", None, "pruning variable must be"),
    ("scale", "0", "positive rational"),
    ("scale", "-2", "positive rational"),
    ("scale", "1/" + "3" * 30, "positive rational"),
    ("pieces", 0, "out of range"),
    ("pieces", 10**6, "out of range"),
    ("horizon", "3/2", "at most 1"),
    ("horizon", "-1", "negative"),
    ("extra", 1, "keys"),
])
def test_malformed_records_in_u_are_rejected(field, value, message):
    cert = _pruned_certificate()
    cert["claims"][0]["pruning"][field] = value
    report = check(cert)
    assert not report.ok and message in str(report)


def test_a_record_in_u_without_its_scale_is_rejected():
    cert = _pruned_certificate()
    del cert["claims"][0]["pruning"]["scale"]
    report = check(cert)
    assert not report.ok and "keys" in str(report)


def test_a_tampered_horizon_that_vertex_k_does_not_bound_is_rejected():
    """The trapezoid's valid set on the diamond is bounded, so its record has U < 1; a smaller
    U is a horizon in h that vertex k's own valid set reaches past."""
    cert = _pruned_certificate(method=M.trapezoid())
    record = cert["claims"][0]["pruning"]
    assert Fraction(record["horizon"]) < 1
    record["horizon"] = str(Fraction(record["horizon"]) / 4)
    report = check(cert)
    assert not report.ok and "does not bound" in str(report)


def test_a_forged_unbounded_valid_set_under_pruning_is_rejected():
    """The record's U = 1 claims nothing about vertex k, but the kernel still finds every
    binding pair itself: a valid set [0, oo) that is really bounded is rejected."""
    cert = _pruned_certificate(method=M.trapezoid())
    cert["claims"][0]["pruning"]["horizon"] = "1"
    cert["claims"][0]["intervals"] = [{"lo": "0", "hi": "oo", "lo_closed": True, "hi_closed": False}]
    assert not check(cert).ok


def test_a_determinant_vanishing_in_the_range_is_rejected():
    """x' = Ax with an eigenvalue 1: det(I - hA) = 0 at h = 1 for backward Euler, so q > 0
    does not give c = q D > 0 past it; a record with U = 1 is rejected."""
    cert = _pruned_certificate(method=M.backward_euler())
    cert["problem"]["A"] = [["1", "0"], ["0", "-1"]]
    cert["claims"][0]["determinant"] = None
    cert["claims"][0]["pruning"]["horizon"] = "1"
    report = check(cert)
    assert not report.ok and "vanishes in the pruning range" in str(report)


def test_a_polynomial_record_on_a_rational_method_is_still_rejected():
    cert = _pruned_certificate()
    for key in ("variable", "scale", "pieces"):
        del cert["claims"][0]["pruning"][key]
    report = check(cert)
    assert not report.ok and "polynomial methods only" in str(report)


def test_a_forged_largest_threshold_under_pruning_is_rejected():
    cert = _pruned_certificate(method=M.trapezoid(), largest=True)
    claim = cert["claims"][0]
    claim["value"], claim["binding"] = "oo", None
    assert not check(cert).ok


def test_the_lifted_path_is_the_condition_up_to_a_positive_factor():
    """g' P(u) w = -(1 - u)^E q(h) at h = s u/(1 - u): checked exactly at a few u (kernel and engine lifts)."""
    method = M.pade(2, 2)
    A, G, b, verts = fractions_of(SPIN, DIAMOND)
    D, N = method_matrices(A, list(method.numerator), list(method.denominator))
    s = Fraction(2)
    P = kernel_rational.lifted(D, N, s)
    E = len(P) - 1
    cs = ConditionSet(SPIN, DIAMOND, method)
    P_engine = engine_rational.lifted(cs.D, cs.N, s)
    assert len(P_engine) == len(P)
    for u in (Fraction(1, 3), Fraction(9, 10)):
        h = s * u / (1 - u)
        Pu = [[sum(P[k][r][c] * u**k for k in range(E + 1)) for c in range(3)] for r in range(3)]
        Dh = sum(c * h**k for k, c in enumerate(D))
        Nh = [[sum(N[k][r][c] * h**k for k in range(len(N))) for c in range(2)] for r in range(2)]
        for v in verts:
            for g, beta in zip(G, b):
                w = [Fraction(1)] + v
                lhs = sum(gp * sum(Pu[r][c] * w[c] for c in range(3)) for r, gp in enumerate([-beta] + g))
                q = beta * Dh - sum(g[r] * sum(Nh[r][c] * v[c] for c in range(2)) for r in range(2))
                assert lhs == -(1 - u) ** E * q


def test_a_record_that_would_cost_minutes_is_priced_and_rejected_first():
    """pieces = 512 on 5000 vertices in R^6: about 5000 * 538 * 3 * 49 box products, over the
    kernel's work budget -- rejected by the parser before any piece is built."""

    record = {"horizon": "1", "vertex": 0, "order": list(range(5000)), "variable": "h/(s+h)", "scale": "8",
              "pieces": 512}
    with pytest.raises(CheckFailure, match="work budget"):
        kernel_rational.parse(record, 5000, 6)
    record["pieces"] = 48
    assert kernel_rational.parse(record, 5000, 6)[:3] == (Fraction(8), Fraction(1), 48)


@settings(max_examples=80, deadline=None)
@given(st.lists(st.fractions(min_value=Fraction(-100), max_value=Fraction(100), max_denominator=40), min_size=2, max_size=9),
       st.fractions(min_value=Fraction(0), max_value=Fraction(5), max_denominator=30),
       st.fractions(min_value=Fraction(1, 30), max_value=Fraction(5), max_denominator=30))
def test_entry_bernstein_in_integers_is_the_bernstein_definition(coeffs, t, d):
    """X = B_0, Z = B_E, M = max_k |B_k - (1 - k/E) B_0 - (k/E) B_E| with B_k = sum_{i<=k} C(k,i)/C(E,i) c_i,
    c_i the coefficients of p(t + d x) -- computed here in Fractions from the definition."""
    E = len(coeffs) - 1
    shifted = [Fraction(0)] * (E + 1)  # p(t + d x) by expanding each (t + d x)^i
    for i, a in enumerate(coeffs):
        for j in range(i + 1):
            shifted[j] += a * math.comb(i, j) * t ** (i - j) * d ** j
    B = [sum(Fraction(math.comb(k, i), math.comb(E, i)) * shifted[i] for i in range(k + 1)) for k in range(E + 1)]
    M = max(abs(B[k] - (1 - Fraction(k, E)) * B[0] - Fraction(k, E) * B[E]) for k in range(E + 1))
    assert kernel_rational._entry_bernstein(coeffs, t, d) == (B[0], B[E], M)
