"""Proof that a claimed generator system is exactly P = {x : Gx <= b}.

A certificate may claim vertices, rays and lines with
P = conv(vertices) + cone(rays) + span(lines).  :func:`prove_generators`
proves both inclusions in exact arithmetic and trusts nothing else the
certificate says.

"contains" -- every listed point is in P (Gv <= b), every ray is nonzero
with Gr <= 0, every line is nonzero with Gl = 0; so the generated set lies in
P.

"is contained" -- by an edge walk.  Let L = {x : Gx = 0}, r = rank G.  The
lines lie in L and have rank n - r, so they span L.  Modulo L, P is pointed:
P = L + conv(its vertices) + cone(the extreme rays of its recession cone),
where a "vertex" is a minimal face (a point whose active rows have rank r)
and points and directions are compared modulo L through G_B x, G_B a fixed
set of r independent rows of G (G_B x = G_B y iff x - y is in L).  At a
vertex v with active rows A the edges of P are the extreme rays d of the
cone {d : G_A d <= 0} modulo L: solved from a basis of r active rows when
|A| = r, enumerated by the double-description method when v is degenerate.
The ratio test t* = min{(b_j - g_j v)/(g_j d) : g_j d > 0} gives the other
end v + t* d, a vertex, or, when no row has g_j d > 0, an unbounded edge.
The kernel walks from a listed vertex and requires every edge end to be a
listed point and every unbounded edge to be a listed ray (modulo L, up to a
positive factor).  The vertex-edge graph of a pointed polyhedron is
connected and every extreme ray of its recession cone is the direction of an
unbounded edge, so the walk reaches every vertex and every extreme ray: the
listed generators generate all of P.

Listed points that are not vertices, repeated vertices and non-extreme rays
are in P (rec P) and so harmless; they are counted in the record as extra.

Every inner loop runs on Python integers: each row of (G | b) is scaled to
integers once, each point is an integer vector over one denominator, each
direction an integer vector.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, NamedTuple, Sequence

from .budget import MAX_DIMENSION
from .cones import integer_rank, primitive, scaled_integers
from .edge_walk import EdgeWalk, IntegerPolyhedron
from .failure import require
from .routes.polygon import prove_polygon

__all__ = ["Generators", "prove_generators"]


class Generators(NamedTuple):
    """A generator system proved to be P = conv(vertices) + cone(rays) + span(lines)."""

    vertices: tuple  # tuples of Fraction, as listed
    rays: tuple
    lines: tuple
    dimension: int  # n
    lineality: int  # dim {x : Gx = 0}
    minimal_faces: int  # vertices of P (minimal faces), each reached by the walk
    extreme_rays: int  # extreme rays of rec P modulo the lineality space
    extra_vertices: int  # listed points beyond one per minimal face
    extra_rays: int  # listed rays beyond one per extreme ray


# ----------------------------------------------------------------------------
# input


def _is_exact(x: Fraction) -> bool:
    return isinstance(x, (int, Fraction)) and not isinstance(x, bool)


def _vector(v: Sequence[Fraction], n: int, what: str) -> Any:
    require(isinstance(v, list), f"{what}: expected a list, got {type(v).__name__}")
    require(len(v) == n, f"{what}: expected {n} entries, got {len(v)}")
    for x in v:
        require(_is_exact(x), f"{what}: entry {x!r} is not an exact rational (Fraction or int)")
    return v


def _list(x: Any, what: str) -> Any:
    require(isinstance(x, list), f"{what}: expected a list, got {type(x).__name__}")
    return x


# ----------------------------------------------------------------------------
# the proof


def prove_generators(G: Any, b: Any, vertices: Any, rays: Sequence[list[Fraction]], lines: Sequence[list[Fraction]]) -> Any:
    """Prove P = {x : Gx <= b} = conv(vertices) + cone(rays) + span(lines).

    G is a list of m rows of n rationals (Fraction or int), b a list of m; the
    generators are lists of length-n vectors.  Returns a :class:`Generators`
    record, or raises :class:`CheckFailure` naming the fact that failed.

    The steps: shapes; (G | b) as integers; the lines span the lineality space
    L; the rays lie in rec(P); an edge walk from a listed vertex reaches only
    listed vertices and rays (so the lists are complete: the graph of P/L is
    connected and every extreme ray is an unbounded edge); every listed point
    lies in P.  A bounded polygon (n = 2, no rays, no lines) is proved by
    :func:`exactinv_check.routes.polygon.prove_polygon` in O(m log m) instead, when that
    proof applies.
    """
    n = _check_shapes(G, b, vertices, rays, lines)
    if n == 2 and not rays and not lines:  # a bounded polygon: O(m log m) (exactinv_check.routes.polygon)
        fast = prove_polygon(G, b, vertices)
        if fast is not None:
            corners, extra = fast
            return Generators(tuple(tuple(v) for v in vertices), (), (), 2, 0, corners, 0, extra, 0)
    return _general_proof(G, b, vertices, rays, lines, n)


def _general_proof(G: Any, b: Any, vertices: Any, rays: Any, lines: Any, n: Any) -> Generators | None:
    """The edge walk of the module docstring, for any dimension."""
    P = IntegerPolyhedron(G, b, n)
    _prove_lines(P, lines)
    ray_index = _index_rays(P, rays)
    walk = EdgeWalk(P, G, b, vertices, ray_index)
    seen, rays_hit = walk.run()
    for i in range(len(vertices)):  # every other listed point is in P too
        if i not in walk.in_P:
            walk.slacks_in_P(i)
    return Generators(
        vertices=tuple(tuple(v) for v in vertices),
        rays=tuple(tuple(d) for d in rays),
        lines=tuple(tuple(l) for l in lines),
        dimension=n,
        lineality=n - P.rank,
        minimal_faces=len(seen),
        extreme_rays=len(rays_hit),
        extra_vertices=len(vertices) - len(seen),
        extra_rays=len(rays) - len(rays_hit),
    )


def _check_shapes(G: Sequence[list[Fraction]], b: Sequence[Fraction], vertices: Sequence[Sequence[Any]],
                  rays: Sequence[list[Fraction]], lines: Sequence[list[Fraction]]) -> int | None:
    """Lists of the right lengths, at least one point; returns n."""
    for value, name in ((G, "G"), (b, "b"), (vertices, "vertices"), (rays, "rays"), (lines, "lines")):
        _list(value, name)
    require(len(b) == len(G), f"b has {len(b)} entries but G has {len(G)} rows")
    require(len(vertices) > 0, "no vertex: a generator system needs at least one point")
    first = G[0] if G else vertices[0]
    _list(first, "G row 0" if G else "vertex 0")
    n = len(first)
    require(n >= 1, "the dimension n must be at least 1")
    require(n <= MAX_DIMENSION, f"dimension {n} exceeds {MAX_DIMENSION}")
    for j, g in enumerate(G):
        _vector(g, n, f"G row {j}")
    _vector(b, len(G), "b")
    for vectors, name in ((vertices, "vertex"), (rays, "ray"), (lines, "line")):
        for i, v in enumerate(vectors):
            _vector(v, n, f"{name} {i}")
    return n


def _prove_lines(P: IntegerPolyhedron, lines: Sequence[list[Fraction]]) -> None:
    """Every line is nonzero and in L, and together they span L."""
    line_ints = []
    for i, l in enumerate(lines):
        li, _ = scaled_integers(l)
        require(any(li), f"line {i} is the zero vector")
        j = next((j for j, x in enumerate(P.times(li)) if x), None)
        require(j is None, f"line {i} is not in the lineality space: row {j} of G l is nonzero")
        line_ints.append(li)
    rank = integer_rank(line_ints, P.n)
    require(rank == P.n - P.rank, f"the lines span a space of dimension {rank}, but the lineality space "
            f"{{x : Gx = 0}} has dimension {P.n - P.rank}")


def _index_rays(P: IntegerPolyhedron, rays: Sequence[list[Fraction]]) -> Any:
    """Every ray is nonzero and in rec(P); indexed modulo L up to a positive factor."""
    ray_index: dict[Any, Any] = {}
    for i, d in enumerate(rays):
        di, _ = scaled_integers(d)
        require(any(di), f"ray {i} is the zero vector")
        gd = P.times(di)
        j = next((j for j, x in enumerate(gd) if x > 0), None)
        require(j is None, f"ray {i} is not in the recession cone: row {j} of G r is positive")
        key = primitive([gd[j] for j in P.row_basis])
        if key is not None:  # a ray inside L is harmless and represents nothing
            ray_index.setdefault(tuple(key), i)
    return ray_index
