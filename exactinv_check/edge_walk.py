"""The edge walk of :func:`exactinv_check.polyhedra.prove_generators`: from a listed
vertex over the vertex-edge graph of P/L (L = {x : Gx = 0}), every edge end
must be a listed point and every unbounded edge a listed ray (modulo L, up to
a positive factor).  P is held as integers: each row of (G | b) scaled once to
coprime integers, with its rank r and a row basis B (G_B x determines x
modulo L).  The edges at a vertex are the extreme rays of its tangent cone
(module :mod:`exactinv_check.cones`).
"""

from __future__ import annotations

from collections import deque
from fractions import Fraction
from math import gcd
from operator import mul
from typing import Any, Iterator, Sequence

from .budget import PYTHON_OP, charge
from .cones import basis_rays, cone_rays, primitive, reduce_rows, scaled_integers
from .failure import CheckFailure, require


def _text(v: Sequence[int | Fraction]) -> str:
    return "(" + ", ".join(str(x) for x in v) + ")"


class IntegerPolyhedron:
    """(G | b) with each row scaled once to coprime integers (a positive factor),
    its rank r and a row basis B; G_B x determines x modulo L = {x : Gx = 0}."""

    def __init__(self, G: Sequence[list[Fraction]], b: Sequence[Fraction], n: int) -> None:
        self.rows, self.rhs = [], []
        for g, beta in zip(G, b):
            ints, _ = scaled_integers(list(g) + [beta])
            ints = primitive(ints) or ints
            self.rows.append(ints[:n])
            self.rhs.append(ints[n])
        self.n, self.m = n, len(self.rows)
        self.columns = [[row[i] for row in self.rows] for i in range(n)]
        self.rank, _, self.row_basis, _, _ = reduce_rows(self.rows, n)

    def times(self, x: Sequence[int]) -> list[int]:
        """G x for an integer vector x (column by column, skipping zeros)."""
        acc = None
        for xi, col in zip(x, self.columns):
            if xi:
                acc = [xi * c for c in col] if acc is None else [a + xi * c for a, c in zip(acc, col)]
        return [0] * self.m if acc is None else acc

    def slacks(self, p: Sequence[int], q: int) -> list[int]:
        """q (b - G p/q) = b q - G p, row by row."""
        acc = [beta * q for beta in self.rhs]
        for pi, col in zip(p, self.columns):
            if pi:
                acc = [a - pi * c for a, c in zip(acc, col)]
        return acc

    @staticmethod
    def point_key(num: Sequence[int], den: int) -> Any:
        """Canonical form of the minimal face (x + L) from (G_B x) = num / den."""
        g = gcd(*num, den)
        if g == 1:
            return (*num, den)
        return (*[x // g for x in num], den // g)


class EdgeWalk:
    """The walk over the vertex-edge graph of P/L from the first listed vertex."""

    def __init__(self, P: Any, G: Any, b: Any, vertices: Any, ray_index: Any) -> None:
        self.P, self.G, self.b, self.vertices, self.ray_index = P, G, b, vertices, ray_index
        self.points = [scaled_integers(v) for v in vertices]
        self.keys = [P.point_key([sum(map(mul, P.rows[j], p)) for j in P.row_basis], q) for p, q in self.points]
        self.point_index: dict[Any, Any] = {}
        for i, key in enumerate(self.keys):  # points indexed by their minimal face modulo L
            self.point_index.setdefault(key, i)
        self.in_P: set[Any] = set()

    def slacks_in_P(self, i: int) -> Any:
        """The slacks b q - G p of listed point i = p/q, all proved >= 0."""
        p, q = self.points[i]
        s = self.P.slacks(p, q)
        if s and min(s) < 0:
            j = next(j for j, x in enumerate(s) if x < 0)
            v = self.vertices[i]
            excess = sum(x * y for x, y in zip(self.G[j], v)) - self.b[j]
            raise CheckFailure(f"vertex {i} = {_text(v)} is not in P: row {j} has g.v - b = {excess} > 0")
        self.in_P.add(i)
        return s

    def edges_at(self, i: Any) -> Any:
        """(slacks, active rows, integer edge directions) at listed point i, or
        None if the point is not a vertex (its active rows have rank < r)."""
        P = self.P
        charge(PYTHON_OP * len(P.rows) * (P.rank + 2) * 4, "the edge walk")  # the slacks and the active rows of a point
        s = self.slacks_in_P(i)
        active = [j for j, x in enumerate(s) if x == 0]
        A = [P.rows[j] for j in active]
        if len(active) < P.rank:
            return None
        if len(active) == P.rank:  # the active rows are a basis, or v is no vertex
            found = basis_rays(A, P.n)
            if found is None:
                return None
            cols, ys = found
        else:  # degenerate: more than r active rows
            rank, cols, basis, _, _ = reduce_rows(A, P.n)
            if rank != P.rank:
                return None
            ys = cone_rays([[row[c] for c in cols] for row in A], basis, P.rank)
        directions = []
        for y in ys:
            d = [0] * P.n
            for c, yc in zip(cols, y):
                d[c] = yc
            directions.append(d)
        return s, active, directions

    def run(self) -> Any:
        """(minimal faces reached, ray keys hit); CheckFailure if an edge leaves the lists."""
        start = found = None
        for i in self.point_index.values():
            found = self.edges_at(i)
            if found is not None:
                start = i
                break
        require(start is not None,
                f"no listed point is a vertex of P (none has active rows of rank {self.P.rank} = rank G)")
        seen, rays_hit = {self.keys[start]}, set()  # type: ignore[index]
        queue = deque([(start, found)])
        while queue:
            i, found = queue.popleft()
            if found is None:  # cannot happen: every edge of a vertex ends at a vertex
                raise CheckFailure(f"internal: listed point {i} reached by the walk is not a vertex")
            for key, kind in self._ends(i, *found):
                if kind == "ray":
                    rays_hit.add(key)
                elif key not in seen:
                    seen.add(key)
                    j = self.point_index[key]
                    queue.append((j, self.edges_at(j)))
        return seen, rays_hit

    def _ends(self, i: Any, s: Any, active: Any, directions: Any) -> Iterator[Any]:
        """For each edge at vertex i: ("ray", key) of a listed ray, or ("vertex", key)
        of the listed vertex where it ends."""
        P = self.P
        p, q = self.points[i]
        base = [P.rhs[j] * q - s[j] for j in P.row_basis]  # G_B p
        for d in directions:
            gd = P.times(d)
            require(all(gd[j] <= 0 for j in active) and any(gd[j] for j in active),
                    "internal: an edge direction leaves the tangent cone")
            best_s, best_g = None, None  # ratio test: t* = min over g_j d > 0 of s_j / (q g_j d)
            for sj, gj in zip(s, gd):
                if gj > 0 and (best_g is None or sj * best_g < best_s * gj):
                    best_s, best_g = sj, gj
            gd_basis = [gd[j] for j in P.row_basis]
            if best_g is None:
                key = tuple(primitive(gd_basis))
                require(key in self.ray_index,
                        f"incomplete generators: P has an unbounded edge from vertex {i} = "
                        f"{_text(self.vertices[i])} in direction {_text(d)}, and no listed ray is that "
                        f"direction (modulo the lines)")
                yield key, "ray"
                continue
            den = q * best_g  # the other end: v + t* d = (p best_g + best_s d) / (q best_g)
            key = P.point_key([best_g * x + best_s * y for x, y in zip(base, gd_basis)], den)
            if key not in self.point_index:
                w = [Fraction(best_g * pk + best_s * dk, den) for pk, dk in zip(p, d)]
                raise CheckFailure(
                    f"incomplete generators: the edge from vertex {i} = {_text(self.vertices[i])} "
                    f"in direction {_text(d)} ends at the vertex {_text(w)} of P, which is not "
                    f"listed (modulo the lines)")
            yield key, "vertex"
