"""exactinv_check.edge_walk: the walk over the vertex-edge graph of P/L behind prove_generators, on its own
classes.  IntegerPolyhedron against exact rational arithmetic and sympy's rank; EdgeWalk against pplpy's
minimized generators: from a listed vertex the walk reaches exactly the vertices of P (modulo the lineality
space L) and the rays it meets are exactly P's extreme rays, and it rejects a list missing any one of them."""

import itertools
import random
from fractions import Fraction as F

import ppl
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from exactinv_check.budget import account
from exactinv_check.cones import primitive
from exactinv_check.edge_walk import EdgeWalk, IntegerPolyhedron
from exactinv_check.failure import CheckFailure, OverBudget

entry = st.fractions(min_value=-5, max_value=5, max_denominator=7)


def _walk(G, b, vertices, rays=()):
    """An EdgeWalk over P = {Gx <= b} with the rays indexed as prove_generators indexes them (modulo L)."""
    G, b = [[F(x) for x in g] for g in G], [F(x) for x in b]
    vertices = [[F(x) for x in v] for v in vertices]
    P = IntegerPolyhedron(G, b, len(G[0]))
    index = {}
    for i, d in enumerate(rays):
        gd = P.times([int(x) for x in d])
        index.setdefault(tuple(primitive([gd[j] for j in P.row_basis])), i)
    return EdgeWalk(P, G, b, vertices, index)


def _ppl_generators(G, b):
    """(vertices, rays) of {Gx <= b} (integer G, b, bounded or not, no lines) by pplpy."""
    n = len(G[0])
    x = [ppl.Variable(i) for i in range(n)]
    cs = ppl.Constraint_System()
    for g, beta in zip(G, b):
        cs.insert(sum((c * xi for c, xi in zip(g, x)), ppl.Linear_Expression(0)) <= beta)
    points, rays = [], []
    for gen in ppl.C_Polyhedron(cs).minimized_generators():
        c = [int(v) for v in gen.coefficients()]
        if gen.is_point():
            points.append([F(v, int(gen.divisor())) for v in c])
        elif gen.is_ray():
            rays.append(c)
    return points, rays


# ------------------------------------------------------------------ soundness
@settings(max_examples=30, deadline=None)
@given(st.lists(st.lists(entry, min_size=3, max_size=3), min_size=1, max_size=5), st.lists(entry, min_size=5, max_size=5))
def test_the_integer_rows_are_positive_multiples_and_the_rank_is_sympys(G, b):
    b = b[:len(G)]
    P = IntegerPolyhedron(G, b, 3)
    assert P.rank == sp.Matrix(G).rank() and len(P.row_basis) == P.rank
    assert sp.Matrix([G[j] for j in P.row_basis]).rank() == P.rank  # a row basis, not just rank-many rows
    x, (p, q) = [3, -1, 2], ([1, 4, -2], 3)
    for j, (g, beta) in enumerate(zip(G, b)):
        ints = P.rows[j] + [P.rhs[j]]
        nonzero = next((c for c in list(g) + [beta] if c), None)
        if nonzero is None:
            assert not any(ints)
            continue
        factor = F(next(i for i in ints if i), 1) / nonzero
        assert factor > 0 and [factor * c for c in list(g) + [beta]] == ints
        assert abs(sp.igcd(*ints)) == 1
        assert P.times(x)[j] == factor * sum(c * xi for c, xi in zip(g, x))
        assert P.slacks(p, q)[j] == factor * q * (beta - sum(c * F(pi, q) for c, pi in zip(g, p)))


def test_a_point_key_is_the_same_for_every_representative_of_a_minimal_face():
    # P = {-1 <= x_1 <= 1} in R^2: L = span (0, 1), so (1, 0) and (1, 7) are one minimal face, (-1, 0) another
    walk = _walk([[1, 0], [-1, 0]], [1, 1], [[1, 0], [1, 7], [F(2, 2), F(-1, 3)], [-1, 5]])
    assert walk.keys[0] == walk.keys[1] == walk.keys[2] != walk.keys[3]
    seen, rays = walk.run()
    assert seen == {walk.keys[0], walk.keys[3]} and rays == set()


@settings(max_examples=12, deadline=None)
@given(st.randoms(use_true_random=False))
def test_the_walk_reaches_exactly_pplpys_vertices_and_each_missing_one_is_found(rnd):
    n = 3
    G = [[int(i == k) * s for k in range(n)] for i in range(n) for s in (1, -1)]  # the box [-3, 3]^3 ...
    b = [3] * (2 * n)
    for _ in range(rnd.randint(1, 4)):  # ... cut by a few random half-spaces through points near the centre
        G.append([rnd.randint(-3, 3) for _ in range(n)])
        b.append(rnd.randint(1, 6))
    vertices, _ = _ppl_generators(G, b)
    rnd.shuffle(vertices)
    walk = _walk(G, b, vertices)
    seen, rays = walk.run()
    assert len(seen) == len(vertices) and rays == set()
    drop = rnd.randrange(len(vertices))
    with pytest.raises(CheckFailure, match="which is not listed"):
        _walk(G, b, vertices[:drop] + vertices[drop + 1:]).run()


def test_an_unbounded_polyhedron_needs_its_extreme_rays():
    # {x >= 0, y >= 0, x + y >= 1}: vertices (1, 0), (0, 1), extreme rays (1, 0), (0, 1) (pplpy agrees)
    G, b = [[-1, 0], [0, -1], [-1, -1]], [0, 0, -1]
    vertices, rays = _ppl_generators(G, b)
    assert sorted(map(tuple, vertices)) == [(0, 1), (1, 0)] and sorted(map(tuple, rays)) == [(0, 1), (1, 0)]
    seen, hit = _walk(G, b, vertices, rays).run()
    assert len(seen) == 2 and len(hit) == 2
    for missing in rays:
        with pytest.raises(CheckFailure, match="no listed ray is that direction"):
            _walk(G, b, vertices, [r for r in rays if r != missing]).run()


def test_forged_points_are_rejected_for_their_reason():
    cube = [[int(i == k) * s for k in range(3)] for i in range(3) for s in (1, -1)]
    corners = [list(v) for v in itertools.product((-1, 1), repeat=3)]
    outside = corners[:-1] + [[1, 1, F(11, 10)]]
    with pytest.raises(CheckFailure, match=r"is not in P: row 4 has g.v - b = 1/10 > 0"):
        walk = _walk(cube, [1] * 6, outside)
        for i in range(len(outside)):
            walk.slacks_in_P(i)
    with pytest.raises(CheckFailure, match="no listed point is a vertex of P"):
        _walk(cube, [1] * 6, [[0, 0, 0], [1, 0, 0], [1, 1, 0]]).run()  # the centre, a facet centre, an edge centre
    with pytest.raises(CheckFailure, match=r"ends at the vertex \(-1, 1, 1\)"):  # one corner left out
        _walk(cube, [1] * 6, [c for c in corners if c != [-1, 1, 1]]).run()
    assert _walk(cube, [1] * 6, corners + [[0, 0, 0]]).edges_at(8) is None  # an interior point is no vertex


# ------------------------------------------------------------------ resources
def test_every_point_the_walk_visits_is_charged():
    rnd = random.Random(5)
    n = 4
    G = [[int(i == k) * s for k in range(n)] for i in range(n) for s in (1, -1)]
    vertices = [list(v) for v in itertools.product((-1, 1), repeat=n)]
    rnd.shuffle(vertices)
    with account() as acc:
        seen, _ = _walk(G, [1] * (2 * n), vertices).run()
    assert len(seen) == 2 ** n and acc.spent > 0
    with account(limit=acc.spent // 4):
        with pytest.raises(OverBudget, match="the edge walk"):
            _walk(G, [1] * (2 * n), vertices).run()
