"""The box route (exactinv/conditions/box.py): exact valid sets on boxes from the
sign patterns of the rows of N(h), equal to the general vertex-facet route, no vertex list."""

from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.conditions.box import box_route, detect_box, vertex_index
from exactinv.conditions.polyhedron import ConditionSet, Kind
from exactinv.errors import InvalidInput

M = ei.methods
F = Fraction


def _ends(V):
    return [(iv.lo, iv.hi, iv.lo_closed, iv.hi_closed) for iv in V]


# ------------------------------------------------------------------ worked by hand
def test_taylor2_on_an_offset_interval_by_hand():
    """x' = -x on [0, 2], r = 1 - h + h^2/2: c = w = 1, v_0 = r - 1 = -h + h^2/2 (root 2), v_1 = r > 0.
    Pattern (-1, +1) on (0, 2): q = 1 + v_0 - v_1 = 0; pattern (+1, +1) on (2, oo): q = 1 - v_0 - v_1
    = 2 - 2r = 2h - h^2: the vertex x = 2 (index 1) on the facet x <= 2 (row 0).  Valid set [0, 2]."""
    S, P, m = ei.LinearSystem([[-1]]), ei.Polyhedron.box([0], [2]), M.taylor(2)
    conditions, stats = box_route(ConditionSet(S, P, m))
    assert [(c.kind, c.generator, c.facet, c.poly) for c in conditions] == [(Kind.VERTEX, 1, 0, (0, 2, -1))]
    assert (stats.entries, stats.cells, stats.conditions) == (2, 2, 1)
    V, L = ei.valid_steplengths(S, P, m), ei.largest_threshold(S, P, m)
    assert _ends(V) == [(0, 2, True, True)] and (L.value, L.attained) == (2, True)
    assert (L.binding.generator, L.binding.facet, L.binding.poly) == (1, 0, (0, 2, -1))


def test_forward_euler_on_a_wide_offset_interval_by_hand():
    """x' = -x on [-1, 3] (c = 1, w = 2), forward Euler: v_0 = (1 - h) - 1 = -h, v_1 = 2 (1 - h).
    |v_0| + |v_1| <= 2: h + 2 - 2h <= 2 on [0, 1], 3h - 2 <= 2 beyond: h <= 4/3 (the vertex 3 meets -1)."""
    V = ei.valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [3]), M.forward_euler())
    assert _ends(V) == [(0, F(4, 3), True, True)] and V.box is not None


def test_a_shear_on_the_square_by_hand():
    """A = [[-1, 1], [0, -1]] on [-1, 1]^2, forward Euler: A_d = [[1 - h, h], [0, 1 - h]].
    Row 1: |1 - h| + |h| = 1 on [0, 1], 2h - 1 beyond; row 2: |1 - h| <= 1 iff h <= 2.  Valid set [0, 1]."""
    S, P = ei.LinearSystem([[-1, 1], [0, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    V, L = ei.valid_steplengths(S, P, M.forward_euler()), ei.largest_threshold(S, P, M.forward_euler())
    assert _ends(V) == [(0, 1, True, True)] and (L.value, L.attained) == (1, True)
    # the binding condition is row 1 at a vertex with x_1 x_2 = -1 ... = 2 - 2h up to a positive factor:
    # e.g. vertex (-1, 1) (index 1), facet x <= 1: 1 - ((1 - h)(-1) + h) = 2 - 2h
    assert L.binding.poly in {(2, -2)} and L.binding.generator in (1, 2)


# ------------------------------------------------------------------ detection
def test_detect_box_takes_the_tightest_bounds_and_their_rows():
    G = [[2, 0], [0, 1], [-1, 0], [0, -3], [1, 0], [0, -1]]
    b = [4, 1, 1, 3, 5, 7]  # x <= 2, y <= 1, x >= -1, y >= -1, x <= 5 (implied), y >= -7 (implied)
    box = detect_box([[F(x) for x in r] for r in G], [F(x) for x in b])
    assert box.lo == (-1, -1) and box.hi == (2, 1) and box.upper == (0, 1) and box.lower == (2, 3)
    assert box.scale_upper == (2, 1) and box.scale_lower == (1, 3)


@pytest.mark.parametrize("G, b", [
    ([[1, 1], [-1, 0], [0, -1]], [1, 0, 0]),          # a triangle
    ([[1, 0], [-1, 0], [0, 1]], [1, 1, 1]),           # y unbounded below
    ([[1], [-1]], [1, -1]),                           # lo = hi: a point
    ([[1, 0], [-1, 0], [0, 1], [0, -1], [1, 1]], [1, 1, 1, 1, 5]),  # a redundant row with two entries
])
def test_detect_box_refuses_what_is_not_a_full_box(G, b):
    assert detect_box([[F(x) for x in r] for r in G], [F(x) for x in b]) is None


def test_vertex_index_is_the_position_in_the_sorted_vertex_list():
    P = ei.Polyhedron.box([0, -2, 1], [1, 3, 2])
    for i, v in enumerate(P.vertices):
        assert vertex_index(tuple(1 if x == hi else -1 for x, hi in zip(v, (1, 3, 2)))) == i


# ------------------------------------------------------------------ the routes agree
def test_the_box_route_enumerates_no_vertex():
    S = ei.LinearSystem([[-2 if i == j else F(1, 4) for j in range(12)] for i in range(12)])
    P = ei.Polyhedron.box([-1] * 12, [1] * 12)
    V = ei.valid_steplengths(S, P, M.taylor(4))
    assert "_generators" not in P.__dict__ and "vertices" not in V.claims()[0]
    assert V.box.conditions < 12 * 2**12  # against 2n 2^n = 98,304 pairs
    assert ei.check(V.certificate).ok


def test_box_false_takes_the_general_route_and_box_must_be_a_bool():
    S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([0], [2])
    V = ei.valid_steplengths(S, P, M.taylor(2), box=False)
    assert V.box is None and V.claims()[0]["vertices"] == [["0"], ["2"]]
    with pytest.raises(InvalidInput, match="box"):
        ei.largest_threshold(S, P, M.taylor(2), box="yes")


def test_redundant_rows_and_a_non_box_fall_back_or_agree():
    S = ei.LinearSystem([[-1, "1/2"], ["-1/3", -2]])
    P = ei.Polyhedron([[1, 0], [0, 1], [-1, 0], [0, -1], [3, 0], [0, -2]], [1, 2, 1, "1/2", 7, 9])
    V1, V2 = ei.valid_steplengths(S, P, M.taylor(3)), ei.valid_steplengths(S, P, M.taylor(3), box=False)
    assert V1.box is not None and _ends(V1) == _ends(V2)
    T = ei.Polyhedron([[1, 1], [-1, 0], [0, -1]], [1, 0, 0])
    assert ei.valid_steplengths(S, T, M.taylor(3)).box is None


def test_a_shared_condition_set_builds_the_box_route_once():
    S, P = ei.LinearSystem([[-1, 1], [0, -1]]), ei.Polyhedron.box([-1, 0], [1, 3])
    cs = ConditionSet(S, P, M.taylor(3))
    V = ei.valid_steplengths(S, P, M.taylor(3), conditions=cs)
    L = ei.largest_threshold(S, P, M.taylor(3), conditions=cs)
    assert V.box is L.box


METHODS = [M.taylor(p) for p in range(1, 9)] + [M.backward_euler(), M.pade(1, 1), M.pade(2, 2), M.theta("1/3"),
                                                M.polynomial([1, 1, 0, "1/4"])]


@st.composite
def boxes(draw):
    n = draw(st.integers(1, 4))
    q = st.fractions(min_value=-3, max_value=3, max_denominator=3)
    A = [[draw(q) for _ in range(n)] for _ in range(n)]
    lo = [draw(st.fractions(min_value=-3, max_value=1, max_denominator=3)) for _ in range(n)]
    hi = [x + draw(st.fractions(min_value=F(1, 3), max_value=4, max_denominator=3)) for x in lo]
    return ei.LinearSystem(A), ei.Polyhedron.box(lo, hi), draw(st.sampled_from(METHODS))


@settings(max_examples=40, deadline=None)
@given(boxes())
def test_box_route_equals_the_general_route(problem):
    """Random boxes (offsets, unequal half-widths): intervals, ends, flags, tau, attained identical;
    the binding condition is the general route's condition of that vertex and facet."""
    S, P, m = problem
    V1, V2 = ei.valid_steplengths(S, P, m), ei.valid_steplengths(S, P, m, box=False)
    assert V1.box is not None and _ends(V1) == _ends(V2)
    L1, L2 = ei.largest_threshold(S, P, m), ei.largest_threshold(S, P, m, box=False)
    assert (L1.value, L1.attained) == (L2.value, L2.attained)
    if L1.binding is not None:
        cs = ConditionSet(S, P, m)
        general = cs.pairs(Kind.VERTEX, [(L1.binding.generator, L1.binding.facet)])
        assert [c.poly for c in general] == [L1.binding.poly]


def test_a_five_dimensional_box_with_a_rational_method():
    S = ei.LinearSystem([[-2 if i == j else F((i - j) % 3 - 1, 2) for j in range(5)] for i in range(5)])
    P = ei.Polyhedron.box([-1, 0, -2, F(-1, 2), -1], [1, 1, 1, 2, 3])
    for m in (M.taylor(4), M.theta("1/4")):
        assert _ends(ei.valid_steplengths(S, P, m)) == _ends(ei.valid_steplengths(S, P, m, box=False))
