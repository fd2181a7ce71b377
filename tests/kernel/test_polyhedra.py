"""The kernel's proof that a claimed generator system is exactly {x : Gx <= b}."""


import ast
import itertools
import math
import random
import sys
from fractions import Fraction as F
from pathlib import Path

import pytest
from pruning_helpers import polygon_rows

from exactinv_check import polyhedra
from exactinv_check.failure import CheckFailure
from exactinv_check.polyhedra import Generators, prove_generators


def vec(*xs):
    return [F(x) for x in xs]


def mat(rows):
    return [[F(x) for x in row] for row in rows]


def box(n, lo=-1, hi=1):
    G = [[F(s if i == j else 0) for j in range(n)] for i in range(n) for s in (1, -1)]
    b = [F(hi if s == 1 else -lo) for _ in range(n) for s in (1, -1)]
    V = [[F(x) for x in v] for v in itertools.product([hi, lo], repeat=n)]
    return G, b, V


def rejects(G, b, V, R=(), L=(), match=None):
    with pytest.raises(CheckFailure, match=match) as info:
        prove_generators(G, b, list(V), list(R), list(L))
    assert str(info.value)  # a reason is given
    return str(info.value)


def polygon(points):
    """G, b of the convex polygon with the given vertices in counter-clockwise order."""
    return polygon_rows(points)


def circle_points(N):
    """N rational points on the unit circle, counter-clockwise (t = tan(theta/2))."""
    pts = []
    for k in range(N):
        theta = 2 * math.pi * k / N
        if abs(theta - math.pi) < 1e-12:
            pts.append((F(-1), F(0)))
        else:
            t = F(math.tan(theta / 2)).limit_denominator(10**4)
            pts.append(((1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)))
    return pts


OCTAHEDRON = (
    [[F(s) for s in signs] for signs in itertools.product([1, -1], repeat=3)],
    [F(1)] * 8,
    [[F(s if i == k else 0) for k in range(3)] for i in range(3) for s in (1, -1)],
)


# square pyramid: base [-1,1]^2 x {0}, apex (0,0,1); the apex has 4 active facets
PYRAMID = (
    mat([[1, 0, 1], [-1, 0, 1], [0, 1, 1], [0, -1, 1], [0, 0, -1]]),
    vec(1, 1, 1, 1, 0),
    [vec(1, 1, 0), vec(1, -1, 0), vec(-1, 1, 0), vec(-1, -1, 0), vec(0, 0, 1)],
)


def _ppl_generators(poly):
    P, R, L = [], [], []
    for g in poly.minimized_generators():
        c = [int(x) for x in g.coefficients()]
        if g.is_point():
            P.append([F(x, int(g.divisor())) for x in c])
        elif g.is_ray():
            R.append([F(x) for x in c])
        else:
            L.append([F(x) for x in c])
    return P, R, L


def _ppl_constraints(poly):
    G, b = [], []
    for c in poly.minimized_constraints():
        a = [int(x) for x in c.coefficients()]
        k = int(c.inhomogeneous_term())
        G.append([F(-x) for x in a])  # a.x + k >= 0
        b.append(F(k))
        if c.is_equality():
            G.append([F(x) for x in a])
            b.append(F(-k))
    return G, b


def _random_polyhedra(seed, count):
    ppl = pytest.importorskip("ppl")
    rng = random.Random(seed)
    out = []
    while len(out) < count:
        n = rng.randint(1, 5)
        if rng.random() < 0.5:
            cs = ppl.Constraint_System()
            m = rng.randint(1, 3 * n + 2)
            G = [[F(rng.randint(-3, 3)) for _ in range(n)] for _ in range(m)]
            b = [F(rng.choice([0, 0, 1, 2, 4])) for _ in range(m)]
            for g, beta in zip(G, b):
                cs.insert(ppl.Linear_Expression([-int(x) for x in g], int(beta)) >= 0)
            poly = ppl.C_Polyhedron(cs)
        else:
            gs = ppl.Generator_System()
            cube = list(itertools.product([0, 1], repeat=n)) if rng.random() < 0.5 else None
            pts = rng.sample(cube, rng.randint(1, len(cube))) if cube else [
                [rng.randint(-2, 2) for _ in range(n)] for _ in range(rng.randint(1, 2 * n + 3))
            ]
            for p in pts:
                gs.insert(ppl.point(ppl.Linear_Expression(list(p), 0), 1))
            for _ in range(rng.choice([0, 0, 1, 2])):
                r = [rng.randint(-1, 1) for _ in range(n)]
                if any(r):
                    gs.insert(ppl.ray(ppl.Linear_Expression(r, 0)))
            if rng.random() < 0.25:
                l = [rng.randint(-1, 1) for _ in range(n)]
                if any(l):
                    gs.insert(ppl.line(ppl.Linear_Expression(l, 0)))
            poly = ppl.C_Polyhedron(gs)
            G, b = _ppl_constraints(poly)
        if poly.is_empty() or poly.is_universe():
            continue
        out.append((G, b) + _ppl_generators(poly))
    return out


# ------------------------------------------------------------------ soundness

def test_box_and_record():
    G, b, V = box(2)
    rec = prove_generators(G, b, V, [], [])
    assert isinstance(rec, Generators)
    assert rec.minimal_faces == 4 and rec.extreme_rays == 0 and rec.extra_vertices == 0
    assert rec.dimension == 2 and rec.lineality == 0
    assert rec.vertices == tuple(tuple(v) for v in V)
    with pytest.raises(AttributeError):
        rec.vertices = ()


def test_triangle_in_any_order_with_int_entries():
    G, b = mat([[-1, 0], [0, -1], [1, 1]]), vec(0, 0, 1)
    for V in itertools.permutations([[0, 0], [1, 0], [0, 1]]):
        assert prove_generators(G, b, [list(v) for v in V], [], []).minimal_faces == 3


@pytest.mark.parametrize(
    "points",
    [
        [(2, 1), (1, 2), (-1, 2), (-2, 1), (-2, -1), (-1, -2), (1, -2), (2, -1)],  # octagon-like
        [(F(1), F(0)), (F(3, 5), F(4, 5)), (F(-3, 5), F(4, 5)), (F(-1), F(0)), (F(-3, 5), F(-4, 5)), (F(3, 5), F(-4, 5))],
        circle_points(7),
        circle_points(60),
    ],
)
def test_rational_polygons(points):
    points = [(F(x), F(y)) for x, y in points]
    G, b = polygon(points)
    rec = prove_generators(G, b, [list(p) for p in points], [], [])
    assert rec.minimal_faces == len(points)
    for i in range(len(points)):
        rejects(G, b, [list(p) for p in points[:i] + points[i + 1 :]], match="incomplete")


def test_orthant():
    G, b = mat([[-1, 0, 0], [0, -1, 0], [0, 0, -1]]), vec(0, 0, 0)
    R = [vec(1, 0, 0), vec(0, 2, 0), vec(0, 0, F(1, 3))]
    rec = prove_generators(G, b, [vec(0, 0, 0)], R, [])
    assert rec.extreme_rays == 3 and rec.minimal_faces == 1


def test_half_plane_with_a_line():
    # {x1 <= 1} in R^2: one vertex modulo the line (0, 1), one ray (-1, 0)
    G, b = mat([[1, 0]]), vec(1)
    prove_generators(G, b, [vec(1, 0)], [vec(-1, 0)], [vec(0, 1)])
    # any representatives modulo the line, any positive scale
    rec = prove_generators(G, b, [vec(1, 7)], [vec(-2, 5)], [vec(0, -3)])
    assert rec.lineality == 1 and rec.minimal_faces == 1 and rec.extreme_rays == 1


def test_slab():
    G, b = mat([[1, 0], [-1, 0]]), vec(1, 0)
    rec = prove_generators(G, b, [vec(0, 0), vec(1, 3)], [], [vec(0, 1)])
    assert rec.minimal_faces == 2
    rejects(G, b, [vec(0, 0), vec(0, 3)], L=[vec(0, 1)], match="incomplete")


def test_single_point_and_whole_space():
    G, b = mat([[1, 0], [-1, 0], [0, 1], [0, -1]]), vec(2, -2, 3, -3)
    assert prove_generators(G, b, [vec(2, 3)], [], []).minimal_faces == 1
    # no inequality (or only 0 <= 1): P = R^2, generated by a point and two lines
    prove_generators([], [], [vec(5, 5)], [], [vec(1, 0), vec(1, 1)])
    prove_generators([vec(0, 0)], [F(1)], [vec(5, 5)], [], [vec(1, 0), vec(1, 1)])
    rejects([], [], [vec(5, 5)], L=[vec(1, 0)], match="lines span")


def test_cone_with_apex():
    # {x : x1 + x2 <= 2 x3, x1 - x2 <= x3, ...}: a pointed cone with apex (1, 1, 1)
    G = mat([[1, 0, -1], [-1, 0, -1], [0, 1, -1], [0, -1, -1]])  # |x1|, |x2| <= x3 after the shift
    apex = vec(1, 1, 1)
    b = [sum(g * a for g, a in zip(row, apex)) for row in G]
    R = [vec(1, 1, 1), vec(1, -1, 1), vec(-1, 1, 1), vec(-1, -1, 1)]
    rec = prove_generators(G, b, [apex], R, [])
    assert rec.extreme_rays == 4
    for i in range(4):
        rejects(G, b, [apex], R[:i] + R[i + 1 :], match="unbounded edge")


def test_cube_octahedron_pyramid():
    prove_generators(*box(3), [], [])
    G, b, V = OCTAHEDRON
    assert prove_generators(G, b, V, [], []).minimal_faces == 6
    for i in range(6):
        rejects(G, b, V[:i] + V[i + 1 :], match="incomplete")
    G, b, V = PYRAMID
    assert prove_generators(G, b, V, [], []).minimal_faces == 5
    for i in range(5):
        rejects(G, b, V[:i] + V[i + 1 :], match="incomplete")


def test_hypercube_6():
    G, b, V = box(6, lo=0, hi=F(1, 2))
    rec = prove_generators(G, b, V, [], [])
    assert rec.minimal_faces == 64
    rejects(G, b, V[:-1], match="incomplete")


def test_redundant_and_zero_rows():
    G, b, V = box(2)
    G = G + [vec(2, 0), vec(0, 0), vec(1, 1)]
    b = b + vec(2, 0, 2)  # x1 <= 1 twice, 0 <= 0, and x1 + x2 <= 2 (makes (1, 1) degenerate)
    assert prove_generators(G, b, V, [], []).minimal_faces == 4
    rejects(G, b, V[1:], match="incomplete")


def test_extra_points_and_rays_are_harmless():
    G, b = mat([[-1, 0], [0, -1], [1, -1]]), vec(0, 0, 1)  # unbounded: x >= 0, y >= 0, x - y <= 1
    V = [vec(0, 0), vec(1, 0)]
    R = [vec(0, 1), vec(1, 1)]
    rec = prove_generators(G, b, V, R, [])
    assert (rec.minimal_faces, rec.extreme_rays, rec.extra_vertices, rec.extra_rays) == (2, 2, 0, 0)
    rec = prove_generators(G, b, [vec(F(1, 2), 3)] + V + [vec(0, 0)], R + [vec(1, 2), vec(0, 5)], [])
    assert (rec.minimal_faces, rec.extreme_rays, rec.extra_vertices, rec.extra_rays) == (2, 2, 2, 2)


def test_empty_vertex_list():
    G, b, V = box(2)
    rejects(G, b, [], match="no vertex")
    rejects(mat([[1, 0]]), vec(1), [], R=[vec(-1, 0)], L=[vec(0, 1)], match="no vertex")


def test_missing_vertex():
    G, b, V = box(3)
    rejects(G, b, V[:3] + V[4:], match="incomplete")


def test_vertices_of_a_smaller_polytope_inside():
    G, b, V = box(3)  # the general proof (a polygon is proved by exactinv_check.routes.polygon)
    inner = [[x / 2 for x in v] for v in V]
    msg = rejects(G, b, inner)
    assert "no listed point is a vertex" in msg
    G, b, V = box(2)
    rejects(G, b, [[x / 2 for x in v] for v in V], match=r"incomplete generators: the vertex \(1, 1\) of P is not listed")
    # a smaller polytope sharing one vertex with P
    rejects(G, b, [vec(1, 1), vec(0, 1), vec(1, 0), vec(0, 0)], match="incomplete")


def test_wrong_length_vectors():
    G, b, V = box(2)
    rejects(G, b, V[:3] + [vec(1)], match="expected 2 entries")
    rejects(G, b, V, R=[vec(1, 0, 0)], match="expected 2 entries")
    rejects(G, b, V, L=[vec(1)], match="expected 2 entries")
    rejects(G[:3] + [vec(0, -1, 0)], b, V, match="expected 2 entries")
    rejects(G, b[:3], V, match="b has 3 entries")


def test_vertex_outside():
    G, b, V = box(2)
    rejects(G, b, V + [vec(2, 0)], match="not in P")
    rejects(G, b, [vec(2, 0)] + V, match="not in P")


def test_ray_not_in_the_recession_cone():
    G, b = mat([[-1, 0], [0, -1]]), vec(0, 0)
    rejects(G, b, [vec(0, 0)], R=[vec(1, 0), vec(0, 1), vec(-1, 1)], match="not in the recession cone")
    G, b, V = box(2)
    rejects(G, b, V, R=[vec(1, 0)], match="not in the recession cone")


def test_missing_ray():
    G, b = mat([[-1, 0], [0, -1]]), vec(0, 0)
    rejects(G, b, [vec(0, 0)], R=[vec(1, 0)], match="unbounded edge")
    # a non-extreme ray does not stand in for an extreme one
    rejects(G, b, [vec(0, 0)], R=[vec(1, 0), vec(1, 1)], match="unbounded edge")


def test_missing_line():
    G, b = mat([[1, 0]]), vec(1)
    rejects(G, b, [vec(1, 0)], R=[vec(-1, 0)], match="lines span")
    # a ray in each direction of the line is not a line here: the count is by rank
    rejects(G, b, [vec(1, 0)], R=[vec(-1, 0), vec(0, 1), vec(0, -1)], match="lines span")


def test_zero_ray_zero_line_and_a_line_outside_the_lineality_space():
    G, b = mat([[-1, 0], [0, -1]]), vec(0, 0)
    rejects(G, b, [vec(0, 0)], R=[vec(1, 0), vec(0, 1), vec(0, 0)], match="zero vector")
    H, c = mat([[1, 0]]), vec(1)
    rejects(H, c, [vec(1, 0)], R=[vec(-1, 0)], L=[vec(0, 1), vec(0, 0)], match="zero vector")
    rejects(H, c, [vec(1, 0)], R=[vec(-1, 0)], L=[vec(1, 1)], match="not in the lineality space")


def test_not_lists_or_not_exact():
    G, b, V = box(2)
    rejects(G, b, [tuple(v) for v in V], match="expected a list")
    for args in [(tuple(G), b, V, [], []), (G, b, tuple(V), [], []), (G, b, V, (), []), (G, b, V, [], ())]:
        with pytest.raises(CheckFailure, match="expected a list"):
            prove_generators(*args)
    rejects(G, b, V[:3] + [[1.0, 1.0]], match="not an exact rational")
    rejects(G, b, V[:3] + [[True, F(1)]], match="not an exact rational")
    rejects(G, b, V[:3] + [["1", "1"]], match="not an exact rational")
    rejects([[]], [F(0)], [[]], match="at least 1")


def test_polytope_forged_as_unbounded():
    # claiming a ray for a bounded polytope: the ray is not in rec P
    G, b, V = box(2)
    rejects(G, b, V, R=[vec(0, 1)], match="not in the recession cone")
    # an unbounded P claimed bounded
    G, b = mat([[-1, 0], [0, -1], [1, 0]]), vec(0, 0, 1)
    rejects(G, b, [vec(0, 0), vec(1, 0)], match="unbounded edge")


@pytest.mark.parametrize("seed", [0, 1])
def test_agrees_with_ppl(seed):
    for G, b, P, R, L in _random_polyhedra(seed, 120):
        rec = prove_generators(G, b, P, R, L)
        assert (rec.minimal_faces, rec.extreme_rays, rec.lineality) == (len(P), len(R), len(L))
        # a minimal generator system minus any one generator does not generate P
        for i in range(len(P)):
            with pytest.raises(CheckFailure):
                prove_generators(G, b, P[:i] + P[i + 1 :], R, L)
        for i in range(len(R)):
            with pytest.raises(CheckFailure):
                prove_generators(G, b, P, R[:i] + R[i + 1 :], L)
        for i in range(len(L)):
            with pytest.raises(CheckFailure):
                prove_generators(G, b, P, R, L[:i] + L[i + 1 :])


def test_thousand_gon():
    points = circle_points(1000)
    G, b = polygon(points)
    V = [list(p) for p in points]
    assert prove_generators(G, b, V, [], []).minimal_faces == 1000
    rejects(G, b, V[:500] + V[501:], match="incomplete")


def test_hypercube_12():
    G, b, V = box(12)
    assert prove_generators(G, b, V, [], []).minimal_faces == 4096


def test_cone_over_a_polygon_has_a_very_degenerate_apex():
    points = circle_points(200)
    G2, b2 = polygon(points)
    G = [g + [-beta] for g, beta in zip(G2, b2)]  # g.x <= beta z
    b = [F(0)] * len(G)
    R = [[x, y, F(1)] for x, y in points]
    assert prove_generators(G, b, [vec(0, 0, 0)], R, []).extreme_rays == 200
    rejects(G, b, [vec(0, 0, 0)], R[:7] + R[8:], match="unbounded edge")
    # the pyramid cut at z <= 1: apex plus the base polygon
    G, b = G + [vec(0, 0, 1)], b + [F(1)]
    assert prove_generators(G, b, [vec(0, 0, 0)] + R, [], []).minimal_faces == 201
    rejects(G, b, R, match="incomplete")


def test_imports_only_the_standard_library_and_the_kernel():
    source = Path(polyhedra.__file__).read_text()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Import):
            names = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level > 0:  # relative: inside exactinv_check
                assert node.module is None or node.module.split(".")[0] in {
                    p.stem for p in Path(polyhedra.__file__).parent.glob("*.py")
                } | {"routes"}  # the kernel's routes package
                continue
            names = [node.module]
        else:
            continue
        for name in names:
            top = name.split(".")[0]
            assert top in sys.stdlib_module_names or top == "exactinv_check", name


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
