"""The kernel's O(m log m) proof of a bounded convex polygon (exactinv_check.routes.polygon),
against the general edge walk and against forged generator lists."""


import copy
import random
from fractions import Fraction as F

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from pruning_helpers import polygon_rows

import exactinv as ei
from exactinv_check import check, polyhedra
from exactinv_check.failure import CheckFailure
from exactinv_check.polyhedra import prove_generators
from exactinv_check.routes.polygon import prove_polygon


def hull(points):
    """The corners of the convex hull, counter-clockwise (Andrew's monotone chain, exact;
    collinear points dropped)."""
    pts = sorted(set(points))
    if len(pts) < 3:
        return pts

    def turn(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for p in pts:
        while len(lower) >= 2 and turn(lower[-2], lower[-1], p) <= 0:
            lower.pop()
        lower.append(p)
    for p in reversed(pts):
        while len(upper) >= 2 and turn(upper[-2], upper[-1], p) <= 0:
            upper.pop()
        upper.append(p)
    return lower[:-1] + upper[:-1]


def facets(corners):
    """G, b with one row per edge of the counter-clockwise corners (outward normals)."""
    return polygon_rows(corners)


def general(G, b, V):
    """The edge walk alone: (corners, extra) or the failure message."""
    try:
        g = polyhedra._general_proof(G, b, V, [], [], 2)
    except CheckFailure as exc:
        return str(exc)
    return g.minimal_faces, g.extra_vertices


def fast(G, b, V):
    try:
        return prove_polygon(G, b, V)
    except CheckFailure as exc:
        return str(exc)


def as_lists(points):
    return [[F(x), F(y)] for x, y in points]


coordinate = st.fractions(min_value=-5, max_value=5, max_denominator=7)


point_sets = st.lists(st.tuples(coordinate, coordinate), min_size=3, max_size=14)


SQUARE_G = [[F(1), F(0)], [F(0), F(1)], [F(-1), F(0)], [F(0), F(-1)]]


SQUARE_V = as_lists([(1, 1), (-1, 1), (-1, -1), (1, -1)])


# ------------------------------------------------------------------ soundness

@settings(max_examples=50, deadline=None)
@given(point_sets, st.randoms(use_true_random=False))
def test_random_polygons_agree_with_the_edge_walk(points, rng):
    corners = hull(points)
    if len(corners) < 3:
        return
    G, b = facets(corners)
    # redundant rows: a scaled parallel copy (looser or equal), a far facet, a facet touching one corner
    x, y = corners[0]
    G += [[3 * G[0][0], 3 * G[0][1]], [F(1), F(1)], [F(1), F(0)]]
    b += [3 * b[0] + rng.choice([0, 1]), F(100), max(p[0] for p in corners)]
    rows = list(zip(G, b))
    rng.shuffle(rows)
    G, b = [list(g) for g, _ in rows], [beta for _, beta in rows]
    listed = as_lists(corners) + as_lists(points)  # every input point is in P: extras
    rng.shuffle(listed)
    result = fast(G, b, listed)
    assert result == (len(corners), len(listed) - len(corners))
    assert general(G, b, listed) == result
    # forged: one corner missing (all copies of it) -> both reject
    gone = corners[rng.randrange(len(corners))]
    short = [v for v in listed if tuple(v) != gone]
    assert isinstance(fast(G, b, short), str) and "not listed" in fast(G, b, short)
    assert isinstance(general(G, b, short), str)
    # forged: a listed point outside P -> both reject
    outside = listed + [[F(6), F(6)]]
    assert "not in P" in fast(G, b, outside)
    assert isinstance(general(G, b, outside), str)


def test_regular_polygon_with_many_facets():
    pts = [(F(1, 1), F(0)), (F(0), F(1)), (F(-1), F(0)), (F(0), F(-1))]
    pts += [((1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)) for t in (F(k, 97) for k in range(-96, 97))]
    corners = hull(pts)
    G, b = facets(corners)
    assert prove_polygon(G, b, as_lists(reversed(corners))) == (len(corners), 0)
    g = prove_generators(G, b, as_lists(corners), [], [])
    assert (g.minimal_faces, g.extra_vertices, g.dimension, g.lineality) == (len(corners), 0, 2, 0)


def test_collinear_points_and_any_order_are_harmless():
    listed = SQUARE_V[::-1] + as_lists([(0, 1), (1, 0), (0, 0), (1, 1)])  # edge midpoints, centre, a repeat
    assert prove_polygon(SQUARE_G, [F(1)] * 4, listed) == (4, 4)


def test_a_redundant_facet_through_a_corner_and_a_cutting_one():
    G, b = SQUARE_G + [[F(1), F(1)]], [F(1)] * 4 + [F(2)]  # x + y <= 2 touches (1, 1) only
    assert prove_polygon(G, b, SQUARE_V) == (4, 0)
    b[-1] = F(3, 2)  # now it cuts the corner (1, 1) off: two new corners
    with pytest.raises(CheckFailure, match="not listed"):
        prove_polygon(G, b, SQUARE_V)
    cut = as_lists([(1, F(1, 2)), (F(1, 2), 1), (-1, 1), (-1, -1), (1, -1)])
    assert prove_polygon(G, b, cut) == (5, 0) == general(G, b, cut)


@pytest.mark.parametrize("G, b", [
    (SQUARE_G[:3], [F(1)] * 3),  # unbounded strip end
    (SQUARE_G + [[F(1), F(0)]], [F(1)] * 4 + [F(-2)]),  # empty: x <= -2 and x >= -1
    ([[F(1), F(0)], [F(-1), F(0)], [F(0), F(1)], [F(0), F(-1)]], [F(0), F(0), F(1), F(1)]),  # a segment
    ([[F(1), F(0)], [F(-1), F(0)], [F(0), F(1)]], [F(1)] * 3),  # parallel: a half strip
])
def test_not_a_bounded_polygon_is_left_to_the_general_proof(G, b):
    assert prove_polygon(G, b, SQUARE_V) is None
    with pytest.raises(CheckFailure):  # the listed square is not a generator system of these sets
        prove_generators(G, b, SQUARE_V, [], [])


def test_a_segment_is_still_proved_by_the_general_walk():
    G, b = [[F(1), F(0)], [F(-1), F(0)], [F(0), F(1)], [F(0), F(-1)]], [F(0), F(0), F(1), F(1)]
    g = prove_generators(G, b, as_lists([(0, 1), (0, -1)]), [], [])
    assert (g.minimal_faces, g.extra_vertices) == (2, 0)


def test_fuzzed_small_polygons_never_disagree():
    rng = random.Random(7)
    for _ in range(300):
        pts = [(F(rng.randint(-4, 4)), F(rng.randint(-4, 4))) for _ in range(rng.randint(3, 7))]
        corners = hull(pts)
        if len(corners) < 3:
            continue
        G, b = facets(corners)
        listed = as_lists(corners)
        if rng.random() < 0.5:  # tamper: move, drop or add a point, or shift a row
            k = rng.randrange(len(listed))
            choice = rng.randrange(4)
            if choice == 0:
                listed[k][rng.randrange(2)] += F(rng.choice([-1, 1]), rng.randint(1, 3))
            elif choice == 1:
                del listed[k]
            elif choice == 2:
                listed.append([F(rng.randint(-5, 5)), F(rng.randint(-5, 5))])
            else:
                b[rng.randrange(len(b))] += rng.choice([-1, 1])
        if not listed:
            continue
        f, g = fast(G, b, listed), general(G, b, listed)
        if f is None:
            continue
        assert isinstance(f, str) == isinstance(g, str), (G, b, listed, f, g)
        if not isinstance(f, str):
            assert f == g


def test_forged_polygon_certificates():
    """A valid-set certificate of the engine on a 12-gon, then forged generator lists and rows."""
    pts = [[F(x), F(y)] for x, y in hull(
        [((1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)) for t in (F(k, 5) for k in range(-6, 7))] + [(F(-1), F(0))])]
    V = ei.valid_steplengths(ei.LinearSystem([[-1, "1/2"], ["-1/2", -1]]), ei.Polyhedron.from_vertices(pts),
                             ei.methods.taylor(2), prune=False)
    cert = V.certificate
    assert check(cert).ok

    def forged(change):
        c = copy.deepcopy(cert)
        change(c["problem"], c["claims"][0])
        return check(c)

    dropped = forged(lambda p, c: c["vertices"].pop(3))
    assert not dropped.ok and "not listed" in str(dropped)
    outside = forged(lambda p, c: c["vertices"].append(["2", "0"]))
    assert not outside.ok and "not in P" in str(outside)
    assert forged(lambda p, c: c["vertices"].reverse()).ok  # any order of the corners
    assert forged(lambda p, c: c["vertices"].append(["0", "0"])).ok  # an interior point is harmless

    def add_row(g, beta):
        return lambda p, c: (p["G"].append(g), p["b"].append(beta))

    assert forged(add_row(["1", "1"], "10")).ok  # a redundant facet: P and the valid set unchanged
    assert forged(add_row([str(2 * F(x)) for x in cert["problem"]["G"][0]], str(2 * F(cert["problem"]["b"][0])))).ok
    tighter = forged(add_row(cert["problem"]["G"][0], str(F(cert["problem"]["b"][0]) / 2)))
    assert not tighter.ok and "not listed" in str(tighter)


# ------------------------------------------------------------------ resource

def test_a_duplicate_row_that_is_tighter_changes_P():
    G, b = SQUARE_G + [[F(2), F(0)]], [F(1)] * 5  # 2x <= 1: P is [-1, 1/2] x [-1, 1]
    with pytest.raises(CheckFailure, match="not listed"):
        prove_polygon(G, b, SQUARE_V)
    assert prove_polygon(G, b, as_lists([(F(1, 2), 1), (-1, 1), (-1, -1), (F(1, 2), -1)])) == (4, 0)
    assert isinstance(general(G, b, SQUARE_V), str)
