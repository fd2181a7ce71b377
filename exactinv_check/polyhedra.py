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

from collections import deque
from fractions import Fraction
from math import gcd, lcm
from operator import mul
from typing import NamedTuple

from .polygon import prove_polygon
from .rationals import MAX_DIMENSION, CheckFailure, require

__all__ = ["Generators", "prove_generators", "MAX_CONE_PAIRS", "MAX_CONE_RAYS"]

MAX_CONE_PAIRS = 2_000_000  # bound on the adjacency tests at one degenerate vertex
MAX_CONE_RAYS = 200_000  # bound on the rays the double description holds at once


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


def _is_exact(x):
    return isinstance(x, (int, Fraction)) and not isinstance(x, bool)


def _vector(v, n, what):
    require(isinstance(v, list), f"{what}: expected a list, got {type(v).__name__}")
    require(len(v) == n, f"{what}: expected {n} entries, got {len(v)}")
    for x in v:
        require(_is_exact(x), f"{what}: entry {x!r} is not an exact rational (Fraction or int)")
    return v


def _list(x, what):
    require(isinstance(x, list), f"{what}: expected a list, got {type(x).__name__}")
    return x


def _scaled(v):
    """(integer vector p, denominator q > 0) with v = p / q."""
    q = lcm(*(x.denominator for x in v)) if v else 1
    return [x.numerator * (q // x.denominator) for x in v], q


def _primitive(v):
    """v divided by the gcd of its entries (a positive factor); None if v = 0."""
    g = gcd(*v)
    if g == 0:
        return None
    return [x // g for x in v] if g != 1 else list(v)


def _text(v):
    return "(" + ", ".join(str(x) for x in v) + ")"


# ----------------------------------------------------------------------------
# integer linear algebra


def _reduce(rows, ncols, aug=None):
    """Fraction-free elimination of integer rows.

    Returns (rank, pivot columns, original indices of the pivot rows, reduced
    pivot rows, their augmented parts).  The pivot rows are a maximal
    independent subset of ``rows``.  With ``aug`` (one augmented row per row)
    it is Gauss-Jordan and every row operation is applied to the augmented
    part too, so reduced = T * rows and augmented = T * aug for one invertible T.
    """
    work = [list(r) for r in rows]
    ext = [list(a) for a in aug] if aug is not None else None
    order = list(range(len(work)))
    rank, cols = 0, []
    for c in range(ncols):
        if rank == len(work):
            break
        pr = next((i for i in range(rank, len(work)) if work[i][c]), None)
        if pr is None:
            continue
        work[rank], work[pr] = work[pr], work[rank]
        order[rank], order[pr] = order[pr], order[rank]
        if ext is not None:
            ext[rank], ext[pr] = ext[pr], ext[rank]
        prow, pv = work[rank], work[rank][c]
        targets = range(len(work)) if ext is not None else range(rank + 1, len(work))
        for i in targets:
            f = work[i][c]
            if i == rank or not f:
                continue
            row = [pv * x - f * y for x, y in zip(work[i], prow)]
            if ext is not None:
                e = [pv * x - f * y for x, y in zip(ext[i], ext[rank])]
                g = gcd(*row, *e)
                if g > 1:
                    row = [x // g for x in row]
                    e = [x // g for x in e]
                ext[i] = e
            else:
                g = gcd(*row)
                if g > 1:
                    row = [x // g for x in row]
            work[i] = row
        cols.append(c)
        rank += 1
    return rank, cols, order[:rank], work[:rank], (ext[:rank] if ext is not None else None)


def _rank(rows, ncols):
    return _reduce(rows, ncols)[0] if rows else 0


def _basis_rays(B, ncols):
    """Edge directions of a simplicial cone.

    For integer rows B (k of them, length ncols): None if they are dependent;
    otherwise (cols, ys) with k independent columns ``cols`` and, for each row
    b, an integer y_b in Q^k such that the vector d_b with d_b[cols] = y_b and
    zeros elsewhere has B d_b = -c_b e_b, c_b > 0.  So d_b is tight on every
    row of B but b, and the d_b are the extreme rays of {d : B d <= 0}
    modulo its lineality space {d : B d = 0}.
    """
    k = len(B)
    identity = [[int(i == j) for j in range(k)] for i in range(k)]
    rank, cols, _, R, T = _reduce(B, ncols, identity)
    if rank != k:
        return None
    # Gauss-Jordan: R = T B with R[i][cols[i']] = 0 for i != i'; so with
    # c_i = R[i][cols[i]] and y_b[i] = -T[i][b] M / c_i (M = lcm |c_i| > 0),
    # R d_b = -M T e_b, hence B d_b = T^{-1} R d_b = -M e_b.
    c = [R[i][cols[i]] for i in range(k)]
    M = lcm(*(abs(x) for x in c))
    ys = [_primitive([-T[i][b] * (M // c[i]) for i in range(k)]) for b in range(k)]
    return cols, ys


def _cone_rays(A, basis, r):
    """The extreme rays of the pointed cone {y in Q^r : A y <= 0} (A integer,
    rank r, ``basis`` the indices of r independent rows), by the
    double-description method with the algebraic adjacency test."""
    if r == 0:
        return []
    S = [A[i] for i in basis]
    full = 0
    for i in basis:
        full |= 1 << i
    _, initial = _basis_rays(S, r)  # S is square and nonsingular: its columns are 0..r-1
    rays = [(y, full & ~(1 << basis[k])) for k, y in enumerate(initial)]
    in_basis = set(basis)
    pairs = 0
    for j, a in enumerate(A):
        if j in in_basis:
            continue
        bit = 1 << j
        pos, neg, kept = [], [], []
        for y, Z in rays:
            v = sum(x * z for x, z in zip(a, y))
            if v > 0:
                pos.append((v, y, Z))
            elif v < 0:
                neg.append((v, y, Z))
                kept.append((y, Z))
            else:
                kept.append((y, Z | bit))
        for vp, p, Zp in pos:
            for vq, q, Zq in neg:
                pairs += 1
                Z = Zp & Zq
                if Z.bit_count() < r - 2:
                    continue
                tight = []
                while Z:
                    low = Z & -Z
                    tight.append(A[low.bit_length() - 1])
                    Z ^= low
                if _rank(tight, r) != r - 2:
                    continue
                # vp > 0 > vq: a positive combination with a.y = 0
                y = _primitive([vp * qi - vq * pi for pi, qi in zip(p, q)])
                if y is not None:
                    kept.append((y, (Zp & Zq) | bit))
            if pairs > MAX_CONE_PAIRS:
                raise CheckFailure(
                    f"a degenerate vertex needs more than {MAX_CONE_PAIRS} adjacency tests to enumerate its edges"
                )
        require(
            len(kept) <= MAX_CONE_RAYS,
            f"a degenerate vertex has more than {MAX_CONE_RAYS} intermediate edge directions",
        )
        rays = kept
    return [y for y, _ in rays]


# ----------------------------------------------------------------------------
# the proof


def prove_generators(G, b, vertices, rays, lines):
    """Prove P = {x : Gx <= b} = conv(vertices) + cone(rays) + span(lines).

    G is a list of m rows of n rationals (Fraction or int), b a list of m; the
    generators are lists of length-n vectors.  Returns a :class:`Generators`
    record, or raises :class:`CheckFailure` naming the fact that failed.

    The steps: shapes; (G | b) as integers; the lines span the lineality space
    L; the rays lie in rec(P); an edge walk from a listed vertex reaches only
    listed vertices and rays (so the lists are complete: the graph of P/L is
    connected and every extreme ray is an unbounded edge); every listed point
    lies in P.  A bounded polygon (n = 2, no rays, no lines) is proved by
    :func:`exactinv_check.polygon.prove_polygon` in O(m log m) instead, when that
    proof applies.
    """
    n = _check_shapes(G, b, vertices, rays, lines)
    if n == 2 and not rays and not lines:  # a bounded polygon: O(m log m) (exactinv_check.polygon)
        fast = prove_polygon(G, b, vertices)
        if fast is not None:
            corners, extra = fast
            return Generators(tuple(tuple(v) for v in vertices), (), (), 2, 0, corners, 0, extra, 0)
    return _general_proof(G, b, vertices, rays, lines, n)


def _general_proof(G, b, vertices, rays, lines, n):
    """The edge walk of the module docstring, for any dimension."""
    P = _IntegerPolyhedron(G, b, n)
    _prove_lines(P, lines)
    ray_index = _index_rays(P, rays)
    walk = _EdgeWalk(P, G, b, vertices, ray_index)
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


def _check_shapes(G, b, vertices, rays, lines):
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


class _IntegerPolyhedron:
    """(G | b) with each row scaled once to coprime integers (a positive factor),
    its rank r and a row basis B; G_B x determines x modulo L = {x : Gx = 0}."""

    def __init__(self, G, b, n):
        self.rows, self.rhs = [], []
        for g, beta in zip(G, b):
            ints, _ = _scaled(list(g) + [beta])
            ints = _primitive(ints) or ints
            self.rows.append(ints[:n])
            self.rhs.append(ints[n])
        self.n, self.m = n, len(self.rows)
        self.columns = [[row[i] for row in self.rows] for i in range(n)]
        self.rank, _, self.row_basis, _, _ = _reduce(self.rows, n)

    def times(self, x):
        """G x for an integer vector x (column by column, skipping zeros)."""
        acc = None
        for xi, col in zip(x, self.columns):
            if xi:
                acc = [xi * c for c in col] if acc is None else [a + xi * c for a, c in zip(acc, col)]
        return [0] * self.m if acc is None else acc

    def slacks(self, p, q):
        """q (b - G p/q) = b q - G p, row by row."""
        acc = [beta * q for beta in self.rhs]
        for pi, col in zip(p, self.columns):
            if pi:
                acc = [a - pi * c for a, c in zip(acc, col)]
        return acc

    @staticmethod
    def point_key(num, den):
        """Canonical form of the minimal face (x + L) from (G_B x) = num / den."""
        g = gcd(*num, den)
        if g == 1:
            return (*num, den)
        return (*[x // g for x in num], den // g)


def _prove_lines(P, lines):
    """Every line is nonzero and in L, and together they span L."""
    line_ints = []
    for i, l in enumerate(lines):
        li, _ = _scaled(l)
        require(any(li), f"line {i} is the zero vector")
        j = next((j for j, x in enumerate(P.times(li)) if x), None)
        require(j is None, f"line {i} is not in the lineality space: row {j} of G l is nonzero")
        line_ints.append(li)
    rank = _rank(line_ints, P.n)
    require(rank == P.n - P.rank, f"the lines span a space of dimension {rank}, but the lineality space "
            f"{{x : Gx = 0}} has dimension {P.n - P.rank}")


def _index_rays(P, rays):
    """Every ray is nonzero and in rec(P); indexed modulo L up to a positive factor."""
    ray_index = {}
    for i, d in enumerate(rays):
        di, _ = _scaled(d)
        require(any(di), f"ray {i} is the zero vector")
        gd = P.times(di)
        j = next((j for j, x in enumerate(gd) if x > 0), None)
        require(j is None, f"ray {i} is not in the recession cone: row {j} of G r is positive")
        key = _primitive([gd[j] for j in P.row_basis])
        if key is not None:  # a ray inside L is harmless and represents nothing
            ray_index.setdefault(tuple(key), i)
    return ray_index


class _EdgeWalk:
    """The walk over the vertex-edge graph of P/L from the first listed vertex."""

    def __init__(self, P, G, b, vertices, ray_index):
        self.P, self.G, self.b, self.vertices, self.ray_index = P, G, b, vertices, ray_index
        self.points = [_scaled(v) for v in vertices]
        self.keys = [P.point_key([sum(map(mul, P.rows[j], p)) for j in P.row_basis], q) for p, q in self.points]
        self.point_index = {}
        for i, key in enumerate(self.keys):  # points indexed by their minimal face modulo L
            self.point_index.setdefault(key, i)
        self.in_P = set()

    def slacks_in_P(self, i):
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

    def edges_at(self, i):
        """(slacks, active rows, integer edge directions) at listed point i, or
        None if the point is not a vertex (its active rows have rank < r)."""
        P = self.P
        s = self.slacks_in_P(i)
        active = [j for j, x in enumerate(s) if x == 0]
        A = [P.rows[j] for j in active]
        if len(active) < P.rank:
            return None
        if len(active) == P.rank:  # the active rows are a basis, or v is no vertex
            found = _basis_rays(A, P.n)
            if found is None:
                return None
            cols, ys = found
        else:  # degenerate: more than r active rows
            rank, cols, basis, _, _ = _reduce(A, P.n)
            if rank != P.rank:
                return None
            ys = _cone_rays([[row[c] for c in cols] for row in A], basis, P.rank)
        directions = []
        for y in ys:
            d = [0] * P.n
            for c, yc in zip(cols, y):
                d[c] = yc
            directions.append(d)
        return s, active, directions

    def run(self):
        """(minimal faces reached, ray keys hit); CheckFailure if an edge leaves the lists."""
        start = found = None
        for i in self.point_index.values():
            found = self.edges_at(i)
            if found is not None:
                start = i
                break
        require(start is not None,
                f"no listed point is a vertex of P (none has active rows of rank {self.P.rank} = rank G)")
        seen, rays_hit = {self.keys[start]}, set()
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

    def _ends(self, i, s, active, directions):
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
                key = tuple(_primitive(gd_basis))
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
