from fractions import Fraction

import pytest

import exactinv as ei


def test_linear_system_and_closed_loop():
    S = ei.LinearSystem([[0, 1], [0, 0]])
    assert S.n == 2
    C = ei.LinearSystem.closed_loop([[0, 1], [0, 0]], [[0], [1]], [["-1", "-2"]])
    assert C.A == ((0, 1), (-1, -2))
    with pytest.raises(ei.InvalidInput, match="F: expected 1 rows"):
        ei.LinearSystem.closed_loop([[0, 1], [0, 0]], [[0], [1]], [[1, 2], [3, 4]])
    with pytest.raises(ei.InvalidInput, match="B: expected 2 rows"):
        ei.LinearSystem.closed_loop([[0, 1], [0, 0]], [[0]], [[1, 2]])
    with pytest.raises(ei.InvalidInput, match="square"):
        ei.LinearSystem([[1, 2]])


def test_polyhedron_validation():
    with pytest.raises(ei.InvalidInput, match="G has 2 rows but b has 1"):
        ei.Polyhedron([[1, 0], [0, 1]], [1])
    with pytest.raises(ei.InvalidInput, match="row 1 is zero"):
        ei.Polyhedron([[1, 0], [0, 0]], [1, 1])
    with pytest.raises(ei.InvalidInput, match="lo\\[0\\] = 2 exceeds"):
        ei.Polyhedron.box([2], [1])
    with pytest.raises(ei.InvalidInput, match="whole space"):
        ei.Polyhedron.from_vertices([[0, 0]], lines=[[1, 0], [0, 1]])


def test_box_vertices_and_properties():
    P = ei.Polyhedron.box([-1, 0], [1, "1/2"])
    assert set(P.vertices) == {(-1, 0), (-1, Fraction(1, 2)), (1, 0), (1, Fraction(1, 2))}
    assert P.is_bounded and not P.is_empty and P.dimension == 2
    assert P.rays == () and P.lines == ()
    assert [0, "1/4"] in P and [2, 0] not in P


def test_from_vertices_round_trip():
    V = [[1, 0], [0, 1], [-1, 0], [0, -1]]
    P = ei.Polyhedron.from_vertices(V)
    assert P.m == 4
    assert set(P.vertices) == {tuple(map(Fraction, v)) for v in V}
    Q = ei.Polyhedron(P.G, P.b)
    assert set(Q.vertices) == set(P.vertices)


def test_unbounded_and_lower_dimensional():
    cone = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
    assert not cone.is_bounded and cone.vertices == ((0, 0),)
    assert set(cone.rays) == {(1, 0), (0, 1)}
    strip = ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])
    assert strip.lines and strip.dimension == 2
    segment = ei.Polyhedron.from_vertices([[0, 0], [1, 1]])
    assert segment.dimension == 1 and segment.m >= 3
    ray_set = ei.Polyhedron.from_vertices([[0, 0]], rays=[[1, 1]])
    assert ray_set.dimension == 1 and not ray_set.is_bounded


def test_empty_polyhedron_is_reported():
    P = ei.Polyhedron([[1], [-1]], [0, -1])
    assert P.is_empty and P.dimension == -1
    S = ei.LinearSystem([[-1]])
    with pytest.raises(ei.EmptyPolyhedron, match="empty"):
        ei.optimal_gamma(S, P)
    with pytest.raises(ei.EmptyPolyhedron):
        ei.discrete_invariance([[1]], P)
