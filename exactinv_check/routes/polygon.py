"""A fast proof that listed points generate a bounded convex polygon P = {x in Q^2 : Gx <= b}.

The general proof (:mod:`exactinv_check.polyhedra`) compares every listed point
with every facet: V x m work, hours for a 10,000-gon.  In the plane a convex
polygon is proved in O(m log m) integer operations:

1. Sort the facet normals g_j by their angle in [0, 2 pi), exactly (the half
   plane of g, then the sign of a cross product).  Of parallel normals of the
   same direction keep the tightest half-plane; drop facets shown redundant by
   their two neighbours (a search only: what follows re-proves everything).
2. The kept facets u_1, ..., u_r (cyclically, r >= 3) must turn strictly
   counterclockwise by less than pi at each step: cross(u_i, u_{i+1}) > 0,
   and their angles strictly increase along the list (so the steps add up to
   exactly one revolution).  w_i = line u_i  meet  line u_{i+1} is then one point.
3. Edge i of the closed path w_{r}, w_1, ..., w_r lies on line u_i and runs
   from w_{i-1} to w_i; it must have positive length in the counterclockwise
   tangent direction t_i = (-g_y, g_x) of u_i: t_i . (w_i - w_{i-1}) > 0.
   A closed polygon whose edge directions turn left by less than pi at every
   corner and by exactly 2 pi in all is the boundary of a convex polygon W,
   traversed counterclockwise; W lies left of every edge, i.e. in the
   half-plane u_i x <= b_i of its line, and a convex polygon is the
   intersection of the half-planes of its edges: W = Q := {x : u_i x <= b_i
   for all i}.
4. Every other facet j lies in the cone of the normals at one corner:
   cross(u_i, g_j) >= 0 and cross(g_j, u_{i+1}) >= 0, so g_j = alpha u_i +
   beta u_{i+1} with alpha, beta >= 0, and then for x in Q,
   g_j x <= alpha b_i + beta b_{i+1} = g_j w_i; g_j w_i <= b_j proves Q inside
   the half-plane of j.  So P = Q = W = conv{w_1, ..., w_r}.
5. Every corner w_i must be listed (a point set generating P contains every
   vertex of P): otherwise the claim is rejected.  A listed point equal to a
   corner is in P; any other listed point is checked against every facet.

Anything else -- dimension other than 2, rays or lines, unbounded or empty
or degenerate P, a step of pi or more, a facet step 4 cannot place -- returns
None and the general proof decides.  Integers throughout: each row of (G | b)
is scaled to integers once, corners are (x, y, d) with d > 0.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cmp_to_key
from math import gcd
from typing import Any, Sequence

from ..budget import within_budget
from ..failure import CheckFailure

__all__ = ["prove_polygon"]


def _cross(g: tuple[int, int, int], h: tuple[int, int, int]) -> Any:
    return g[0] * h[1] - g[1] * h[0]


def _half(g: tuple[int, int, int]) -> int:
    """0 for angles in [0, pi), 1 for [pi, 2 pi)."""
    return 0 if g[1] > 0 or (g[1] == 0 and g[0] > 0) else 1


def _angle_order(g: tuple[int, int, int], h: tuple[int, int, int]) -> Any:
    """Negative, zero or positive as the angle of g is below, equal to or above h's."""
    a, b = _half(g), _half(h)
    if a != b:
        return a - b
    return -_cross(g, h)


def _corner(g: tuple[int, int, int], h: tuple[int, int, int]) -> tuple[int, int, int] | None:
    """The point where the lines g.x = g[2] and h.x = h[2] meet, as integers (x, y, d), d > 0
    (Cramer's rule; None when the normals are parallel)."""
    d = _cross(g, h)
    if d == 0:
        return None
    x, y = g[2] * h[1] - h[2] * g[1], g[0] * h[2] - h[0] * g[2]
    return (x, y, d) if d > 0 else (-x, -y, -d)


def _below(g: tuple[int, int, int], point: Any) -> Any:
    """g . p <= beta for the row g = (gx, gy, beta) and the point p = (x, y, d), d > 0."""
    return g[0] * point[0] + g[1] * point[1] <= g[2] * point[2]


def _rows(G: Sequence[list[Fraction]], b: Sequence[Fraction]) -> list[tuple[int, int, int]]:
    """Each (g_j | b_j) times a positive integer: integer triples (gx, gy, beta)."""
    rows = []
    for g, beta in zip(G, b):
        q = 1
        for x in (*g, beta):
            q = q * x.denominator // gcd(q, x.denominator)
        rows.append((int(g[0] * q), int(g[1] * q), int(beta * q)))
    return rows


def _candidates(rows: Any) -> tuple[list[int], list[int]]:
    """(sorted facet indices, indices kept as edges): the tightest of each normal
    direction, then facets redundant for their two neighbours removed (a search)."""
    order = sorted(range(len(rows)), key=cmp_to_key(lambda i, j: _angle_order(rows[i], rows[j])))
    kept: list[Any] = []
    for j in order:
        if kept and _angle_order(rows[kept[-1]], rows[j]) == 0:
            g, h = rows[kept[-1]], rows[j]  # same direction: keep the smaller b / ||g||_1
            if h[2] * (abs(g[0]) + abs(g[1])) < g[2] * (abs(h[0]) + abs(h[1])):
                kept[-1] = j
            continue
        kept.append(j)
    alive = dict.fromkeys(kept)
    nxt = {k: kept[(i + 1) % len(kept)] for i, k in enumerate(kept)}
    prv = {v: k for k, v in nxt.items()}
    work = list(kept)
    while work and len(alive) > 3:
        k = work.pop()
        if k not in alive:
            continue
        p, q = prv[k], nxt[k]
        apex = _corner(rows[p], rows[q])
        if _cross(rows[p], rows[q]) > 0 and _below(rows[k], apex):  # k adds nothing to p and q
            del alive[k]
            nxt[p], prv[q] = q, p
            work += [p, q]
    return order, [k for k in kept if k in alive]


def _proved_corners(rows: Any, order: Any, used: Any) -> Any:
    """The corners w_i (steps 2-4 of the module docstring), or None if a step fails."""
    r = len(used)
    if r < 3:
        return None
    u = [rows[k] for k in used]
    if any(_cross(u[i], u[(i + 1) % r]) <= 0 for i in range(r)):
        return None
    if any(_angle_order(u[i], u[i + 1]) >= 0 for i in range(r - 1)):
        return None
    corners = [_corner(u[i], u[(i + 1) % r]) for i in range(r)]
    for i in range(r):
        (x0, y0, d0), (x1, y1, d1) = corners[i - 1], corners[i]  # type: ignore[misc]
        if -u[i][1] * (x1 * d0 - x0 * d1) + u[i][0] * (y1 * d0 - y0 * d1) <= 0:
            return None  # edge i has no positive length
    position = {k: i for i, k in enumerate(used)}
    slot = r - 1  # facets before the first edge in angle belong to the last corner
    for j in order:
        if j in position:
            slot = position[j]
            continue
        g, lo, hi = rows[j], u[slot], u[(slot + 1) % r]
        if _cross(lo, g) < 0 or _cross(g, hi) < 0 or not _below(g, corners[slot]):
            return None
    return corners


def prove_polygon(G: Sequence[list[Fraction]], b: Sequence[Fraction], vertices: Any) -> tuple[int, int] | None:
    """(corners, extra) for a bounded convex polygon P = {Gx <= b} in the plane whose
    every corner is among ``vertices`` (G, b, vertices: Fraction lists, proved as in the
    module docstring); ``corners`` is the number of vertices of P, ``extra`` the
    number of listed points beyond them (each proved in P).  None when the fast
    proof does not apply (then the general one must decide); CheckFailure when P
    is proved to have a corner that is not listed, or a listed point is not in P.

    >>> F = Fraction
    >>> square = [[F(1), F(0)], [F(0), F(1)], [F(-1), F(0)], [F(0), F(-1)]]
    >>> corners = [[F(1), F(1)], [F(-1), F(1)], [F(-1), F(-1)], [F(1), F(-1)]]
    >>> prove_polygon(square + [[F(1), F(1)]], [F(1)] * 4 + [F(5)], corners + [[F(0), F(0)]])
    (4, 1)
    >>> prove_polygon(square, [F(1)] * 4, corners[:3])
    Traceback (most recent call last):
    ...
    exactinv_check.failure.CheckFailure: incomplete generators: the vertex (1, -1) of P is not listed
    >>> prove_polygon(square[:3], [F(1)] * 3, corners) is None   # unbounded: the general proof decides
    True
    """
    if len(G) < 3 or any(len(g) != 2 for g in G):
        return None
    rows = _rows(G, b)
    order, used = _candidates(rows)
    corners = _proved_corners(rows, order, used)
    if corners is None:
        return None
    listed: dict[Any, Any] = {}
    for i, v in enumerate(vertices):
        listed.setdefault((Fraction(v[0]), Fraction(v[1])), i)
    hit = set()
    for x, y, d in corners:
        key = (Fraction(x, d), Fraction(y, d))
        if key not in listed:
            raise CheckFailure(f"incomplete generators: the vertex ({key[0]}, {key[1]}) of P is not listed")
        hit.add(listed[key])
    extra = [i for i in range(len(vertices)) if i not in hit]
    within_budget(len(extra) * len(rows) * 8, f"{len(extra)} listed points beyond the corners, each against {len(rows)} rows")
    for i in extra:
        _require_in(rows, vertices[i], i)
    return len(corners), len(extra)


def _require_in(rows: Sequence[tuple[int, int, int]], v: Any, i: int) -> None:
    q = v[0].denominator * v[1].denominator // gcd(v[0].denominator, v[1].denominator)
    point = (int(v[0] * q), int(v[1] * q), q)
    for j, g in enumerate(rows):
        if not _below(g, point):
            raise CheckFailure(f"vertex {i} = ({v[0]}, {v[1]}) is not in P: row {j} is violated")
