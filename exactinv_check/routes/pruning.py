"""Pruned vertex-facet pairs: which conditions a claim may leave unbuilt.

A claim may carry ``"pruning": {"horizon": T, "vertex": k, "order": [...]}``
(polynomial methods only).  The kernel trusts none of it beyond what it proves:

1. Vertex k bounds the set: the valid set of vertex k's own conditions lies
   in [0, T] (for a largest-threshold claim: its first interval ends by T).
   The valid set of all conditions lies inside it, so nothing beyond T counts.
2. On [0, T] a pair (v, j) cannot bind when the path A_d(h) v stays strictly
   inside facet j's half-space.  [0, T] is cut into pieces [t, t + d] at the
   nodes T x, x in {0, 1, a/16, 2^-i, 1 - 2^-i : a < 16, i <= 12}; with
   A_d(h) = sum_k h^k N_k (N_0 = I) and s = h - t in [0, d],
       A_d(t + s) = sum_k s^k D_k,  D_k = sum_{i>=k} C(i, k) t^(i-k) N_i,
       A_d(t + s) v = (1 - s/d) X v + (s/d) Z v + R(s) v,  X = A_d(t),  Z = A_d(t + d),
       |R(s) v| <= M |v| entrywise,  M = sum_{k>=2} c_k d^k |D_k|,  c_k = min(1, (k - 1)/4)
   (:func:`_piece`), so on the piece the path lies in the box around X v and
   Z v widened by M |v| in each coordinate: the secant's ends are the path at
   the nodes, so each node is one end, widened by the larger remainder of its
   two pieces.  A linear function is largest on a box at a corner: every end's
   box inside the open half-space g_j x < b_j proves the condition positive on
   [0, T].  The kernel decides this itself for every pair, in integers: the
   ends' matrices, the remainders and the vertices are rounded outwards to
   grids of step 2^-48 and the boxes to the grid 1/K (:class:`_Ends`, all ends
   of one vertex at once), so it may keep more pairs than needed, never fewer.
   To stay cheap it tests the box around a block of consecutive vertices in
   its own :func:`morton_order` (near vertices together; the record's
   ``order`` is only shape-checked, so no certificate can make the blocks
   large) at every end against every facet first, then each vertex of the block at
   every end against the facets the block's box did not clear there; each box
   against many facets at once (:class:`_Packed`: one integer, one facet per
   fixed-width slot).  The kept pairs are exactly those of the
   vertex-by-vertex test: a block's box holds the boxes of its vertices.
3. Every surviving pair, all of vertex k's pairs, every ray and line pair are
   built; with 1 and 2 their valid set (or first interval) is that of all pairs.
The horizon is short (numerator and denominator of at most 64 bits): the pieces' exact powers t^i then stay
small; a longer one is rejected before any piece is built, and the pieces themselves are
priced first (:func:`pieces_cost`).
"""

from __future__ import annotations

from fractions import Fraction
from math import gcd, isqrt
from typing import Any

from .. import budget
from ..budget import (
    FRACTION_WEIGHT,
    HORIZON_BITS,  # the horizon's numerator and denominator: the pieces' powers t^i stay short
    MAX_PACKED_BYTES,
    MAX_SLOT_TESTS,
    charge,
    within_budget,
)
from ..failure import require, require_budget
from ..rationals import integer, integer_rows, rational

K_BITS = 40
K = 1 << K_BITS  # the grid of the blocks' coordinate boxes (the packed row table)
MATRIX_BITS = 48  # X and Z rounded down, M up, to the grid 2^-48
VERTEX_BITS = 48  # vertex coordinates rounded outwards to the grid 2^-48
SHIFT = MATRIX_BITS + VERTEX_BITS + 1 - K_BITS  # from the scale 2^(s + w + 1) of (1) in _Ends to the grid 1/K


def parse(record: Any, vertex_count: Any) -> Any:
    """(T, k, order) from a pruning record, shape-checked."""
    require(isinstance(record, dict) and set(record) == {"horizon", "vertex", "order"},
            "pruning has the keys horizon, vertex, order")
    T = rational(record["horizon"], "pruning horizon")
    require(T >= 0, "the pruning horizon is negative")
    require_budget(max(T.numerator.bit_length(), T.denominator.bit_length()) <= HORIZON_BITS,
            f"over the kernel's work budget: the pruning horizon needs a numerator and denominator of at most "
            f"{HORIZON_BITS} bits (a short upper bound of the set's end)")
    k = integer(record["vertex"], "pruning vertex", 0, vertex_count)
    order = record["order"]
    require(isinstance(order, list) and len(order) == vertex_count
            and all(type(i) is int for i in order) and sorted(order) == list(range(vertex_count)),
            "pruning order is not a permutation of the vertices")
    return T, k, order


def nodes(T: Any) -> Any:
    """The ends of the pieces of [0, T]."""
    if T == 0:
        return [Fraction(0), Fraction(0)]
    xs = {Fraction(0), Fraction(1)} | {Fraction(a, 16) for a in range(1, 16)}
    xs |= {Fraction(1, 2**i) for i in range(1, 13)} | {1 - Fraction(1, 2**i) for i in range(1, 13)}
    return [T * x for x in sorted(xs)]


def _piece(N: Any, t: Any, d: Any) -> Any:
    """(X, Z, M) for the piece [t, t + d]: the secant's ends X = A_d(t), Z = A_d(t + d) and the
    remainder M = sum_{k>=2} c_k d^k |D_k| entrywise, c_k = min(1, (k - 1)/4), where
    A_d(t + s) = sum_k s^k D_k, D_k = sum_{i>=k} C(i, k) t^(i-k) N_i.  (A_d(t + s) minus the
    secant is sum_{k>=2} (s^k - s d^(k-1)) D_k, and s (d^(k-1) - s^(k-1)) = s (d - s) (d^(k-2)
    + ... + s^(k-2)) is at most (d^2/4) (k - 1) d^(k-2) and at most d^k.)  Entry by entry in
    integers: the D_k of an entry are a Taylor shift (:func:`_shifted`)."""
    n = len(N[0])
    X = [[Fraction(0)] * n for _ in range(n)]
    Z = [[Fraction(0)] * n for _ in range(n)]
    M = [[Fraction(0)] * n for _ in range(n)]
    u, w = d.numerator, d.denominator
    for r in range(n):
        for c in range(n):
            e, scale = _shifted([Nk[r][c] for Nk in N], t)  # D_k = e_k / (scale q^(deg - k)), t = p/q
            q, top = t.denominator, len(e) - 1
            # d^k D_k = e_k u^k q^k w^(top-k) / (scale q^top w^top): one common denominator
            terms = [x * u**k * q**k * w ** (top - k) for k, x in enumerate(e)]
            whole = scale * q**top * w**top
            X[r][c] = Fraction(e[0], scale * q**top)
            Z[r][c] = Fraction(sum(terms), whole)
            M[r][c] = Fraction(sum(min(4, k - 1) * abs(x) for k, x in enumerate(terms) if k >= 2), 4 * whole)
    return X, Z, M


def _shifted(a: Any, t: Any) -> Any:
    """(e, L): the coefficients of P(t + s) = sum_k e_k s^k / (L q^(deg - k)) for P(h) = sum_i a_i h^i
    (rationals a_i, t = p/q): with L a_i = c_i integers and h = (p + sigma)/q, sigma = q s,
    L q^deg P = sum_i c_i q^(deg - i) (p + sigma)^i = sum_k e_k sigma^k, a Taylor shift by the
    integer p (Horner, integers only)."""
    L = 1
    for x in a:
        L = L * x.denominator // gcd(L, x.denominator)
    p, q, top = t.numerator, t.denominator, len(a) - 1
    e = [int(x * L) * q ** (top - i) for i, x in enumerate(a)]
    if p:
        for j in range(top):
            for i in range(top - 1, j - 1, -1):
                e[i] += p * e[i + 1]
    return e, L


def pieces_cost(N: Any, ends: Any) -> Any:
    """The price of :func:`chord_pieces` in word operations: per piece and entry a Taylor shift of
    (deg + 1)^2 / 2 products of a short integer by one of B bits (a product in C, counted per 512
    bits), 4 (deg + 1) more for the ends and the remainder, and three gcds of B-bit integers
    (quadratic, per 64-bit word squared).  B: the entry's coefficients over their common
    denominator (at most the product of their denominators) plus deg times the bits of t.
    Measured: 7.8e7 (n = 16, degree 64, horizon 1) and 9.2e7 (n = 8, degree 64, a 64-bit
    horizon) run in about 2 s."""
    top, n = len(N) - 1, len(N[0])
    entry_bits = max(sum(Nk[r][c].denominator.bit_length() for Nk in N) + max(Nk[r][c].numerator.bit_length() for Nk in N)
                     for r in range(n) for c in range(n))
    bits = entry_bits + top * max(t.numerator.bit_length() + t.denominator.bit_length() for t in ends)
    per_entry = (((top + 1) ** 2 // 2 + 4 * (top + 1)) * (1 + bits // 512) + 3 * (1 + bits // 64) ** 2
                 + FRACTION_WEIGHT * (top + 4))  # the Python work of an entry: its loops, three Fractions
    return (len(ends) - 1) * n * n * per_entry


def morton_order(boxes: Any) -> Any:
    """The vertices in Morton order of the ranks of their coordinates (equal values, equal
    ranks), each scaled to 12 bits: near vertices stay near, so a block's box stays small.
    Ranks, not values: one far vertex cannot put all the others in one cell; every coordinate:
    vertices that agree in some cannot fall back on their listing.  Any order gives the same
    pairs; this one is the kernel's own, not the certificate's."""
    count = len(boxes)
    dims = len(boxes[0][0]) if boxes else 0
    spread = [0] * 4096
    for x in range(4096):
        for bit in range(12):
            spread[x] |= ((x >> bit) & 1) << (bit * dims)
    keys = [0] * count
    for l in range(dims):
        values = sorted({c2[l] for c2, _ in boxes})
        rank = {x: k * 4096 // len(values) for k, x in enumerate(values)}
        for i, (c2, _) in enumerate(boxes):
            keys[i] |= spread[rank[c2[l]]] << (dims - 1 - l)
    return sorted(range(count), key=keys.__getitem__)


def chord_pieces(N: Any, T: Any) -> Any:
    """(X, Z, M) per piece of [0, T] (:func:`_piece`)."""
    ends = nodes(T)
    return [_piece(N, t, u - t) for t, u in zip(ends, ends[1:])]


def _on_grid(x: Any, bits: Any, up: Any) -> Any:
    """floor (up: ceil) of x 2^bits, an integer."""
    y = x.numerator << bits
    return -((-y) // x.denominator) if up else y // x.denominator


def vertex_box(v: Any) -> Any:
    """(c2, r2): the vertex's coordinates rounded outwards to the grid 2^-w, as centre and
    radius times 2^(w + 1) -- c2 = lo + hi, r2 = hi - lo, with lo, hi = floor, ceil of 2^w v."""
    lo = [_on_grid(x, VERTEX_BITS, False) for x in v]
    hi = [_on_grid(x, VERTEX_BITS, True) for x in v]
    return [a + z for a, z in zip(lo, hi)], [z - a for a, z in zip(lo, hi)]


def group_box(boxes: Any) -> Any:
    """The box (c2, r2) around boxes given as (c2, r2): per coordinate the least lo and the
    greatest hi (c2 - r2 = 2 lo and c2 + r2 = 2 hi are even)."""
    lo2 = [min(column) for column in zip(*([c - r for c, r in zip(c2, r2)] for c2, r2 in boxes))]
    hi2 = [max(column) for column in zip(*([c + r for c, r in zip(c2, r2)] for c2, r2 in boxes))]
    return [(a + z) // 2 for a, z in zip(lo2, hi2)], [(z - a) // 2 for a, z in zip(lo2, hi2)]


class _Ends:
    """The paths of the vertices in a box near the chord ends, every end at once.

    The ends: the two ends of each piece's chord, with that piece's remainder M; an end that
    is the previous piece's other end (the same matrix: secants meet at the nodes) is one end,
    with the larger remainder of the two, entrywise.  Per end E, XL = floor(2^s E) and
    MU = ceil(2^s M) + 1 entrywise (E = XL 2^-s + F with |F| < 2^-s, so MU >= 2^s (M + |F|)).
    For v in a box of centre c and radius r (:func:`vertex_box`: c2 = 2^(w+1) c, r2 = 2^(w+1) r)
    and every row k, the path's coordinate k near the end satisfies

        2^(s+w+1) |x_k - (XL c)_k 2^-s| <= (|XL| r2 + MU (|c2| + r2))_k          (1)

    (|XL (v - c)| <= |XL| r, |F v| + |M v| <= 2^-s MU |v|, |v| <= |c| + r).  Slot e of width
    S bits of the integers PX[k][c] = sum_e XL_e[k][c] 2^(S e), PW[k][c] = sum_e (|XL_e| +
    MU_e)[k][c] 2^(S e) and PM[k][c] = sum_e MU_e[k][c] 2^(S e) (base-2^S digits that may be
    negative: only sums of them are read) holds that end's entry, so one integer holds the
    centre sum_c PX[k][c] c2_c and one the width sum_c PW[k][c] r2_c + PM[k][c] |c2_c| of (1)
    at every end, identities of integers.  Each |centre +- width| < 2^(S - 2) in every slot
    (the width S is chosen so); adding 2^(S - 1) to every slot makes each digit lie in
    [0, 2^S), and the digits are read off the bytes."""

    def __init__(self, pieces: Any, boxes: Any) -> None:
        s = MATRIX_BITS
        ends: list[Any] = []  # (E, M): each end's matrix and remainder
        for X, Z, M in pieces:
            if ends and ends[-1][0] == X:
                ends[-1] = (X, [[max(a, z) for a, z in zip(ra, rz)] for ra, rz in zip(ends[-1][1], M)])
            else:
                ends.append((X, M))
            ends.append((Z, M))
        grid = [([[_on_grid(x, s, False) for x in row] for row in E], [[_on_grid(x, s, True) + 1 for x in row] for row in M])
                for E, M in ends]
        n = len(grid[0][0])
        x_max = max(max(abs(x) for XL, MU in grid for row in XL + MU for x in row), 1)
        v_max = max([abs(c) + r for c2, r2 in boxes for c, r in zip(c2, r2)] + [1])  # >= |c2|, r2 of any group
        self.coordinate_max = 4 * n * x_max * v_max  # |centre| + width <= 4 n x_max v_max for every box
        self.width = ((self.coordinate_max.bit_length() + 2) + 7) // 8
        S, count = 8 * self.width, len(grid)
        self.count, self.n = count, n
        pack = lambda values: sum(x << (S * e) for e, x in enumerate(values))  # noqa: E731
        self.PX = [[pack([XL[k][c] for XL, _ in grid]) for c in range(n)] for k in range(n)]
        self.PW = [[pack([abs(XL[k][c]) + MU[k][c] for XL, MU in grid]) for c in range(n)] for k in range(n)]
        self.PM = [[pack([MU[k][c] for _, MU in grid]) for c in range(n)] for k in range(n)]
        self.half = 1 << (S - 1)
        self.bias = pack([self.half] * count)

    def boxes(self, box: Any) -> Any:
        """Per end, the integer box (hi + lo, on the grid 1/K) around the path of every vertex in
        the box near that end: (1) rounded outwards."""
        n, size = self.n, self.width
        c2, r2 = box
        his: list[Any] = []
        los: list[Any] = []
        for k in range(n):
            centre = sum(self.PX[k][c] * c2[c] for c in range(n) if c2[c])
            width = sum(self.PW[k][c] * r2[c] + self.PM[k][c] * abs(c2[c]) for c in range(n)) + self.bias
            for value, target in ((width + centre, his), (width - centre, los)):  # 2^(S-1) + (width +- centre)
                data = value.to_bytes(size * self.count, "little")
                target.append([-((self.half - int.from_bytes(data[e:e + size], "little")) >> SHIFT)  # ceilings
                               for e in range(0, size * self.count, size)])
        return [list(hi) + [-x for x in lo] for hi, lo in zip(zip(*his), zip(*los))]


def _hull(boxes: Any) -> Any:
    """The box (hi + lo) around boxes given as hi + lo: coordinate-wise max of hi, min of lo."""
    n = len(boxes[0]) // 2
    columns = list(zip(*boxes))
    return [max(c) for c in columns[:n]] + [min(c) for c in columns[n:]]


def _outside(row: Any, box: Any) -> Any:
    """True unless the box [lo, hi] / K lies in g x < b (then the pairs are pruned):
    max over the box of g x is g+ hi + g- lo."""
    return row[1] <= sum(map(int.__mul__, row[0], box))


def _slot_bytes(rows: Any, entry: Any) -> Any:
    """Bytes per slot of a :class:`_Packed` test: |g . box - K b| < 2^(8 W - 2) for every
    row and every box with entries at most ``entry`` in size, and every |row entry| and
    |K b| as well."""
    coefficient = max(abs(x) for row in rows for x in row[0])
    threshold = max(abs(row[1]) for row in rows)
    bound = len(rows[0][0]) * coefficient * entry + threshold + coefficient
    return (bound.bit_length() + 2 + 7) // 8


class _Packed:
    """The test :func:`_outside` of one box against many rows at once, in one integer.

    Slot t of width S = 8 W bits holds row J_t.  With the columns
    C_c = sum_t |a_{J_t c}| 2^(S t) (a column of the rows has one sign s_c: g+ >= 0,
    g- <= 0) and E = sum_t (2^(S-1) - K b_{J_t}) 2^(S t),

        X = E + sum_c s_c box_c C_c = sum_t (2^(S-1) + v_t) 2^(S t),
        v_t = a_{J_t} . box - K b_{J_t},

    an identity of integers.  |v_t| < 2^(S-2) (:func:`_slot_bytes`), so each
    2^(S-1) + v_t is a digit in [0, 2^S) of X in base 2^S, and its top bit is set
    iff v_t >= 0, i.e. iff :func:`_outside` holds for row J_t: those slots are read
    off X masked to the top bits (bytes 0x80 of its little-endian bytes)."""

    def __init__(self, table: Any, J: Any) -> None:
        width, signs, cells = table
        self.J, self.width, self.size, self.signs = J, width, width * len(J), signs
        self.columns = [int.from_bytes(b"".join([column[j] for j in J]), "little") for column in cells[:-1]]
        self.base = int.from_bytes(b"".join([cells[-1][j] for j in J]), "little")
        self.mask = int.from_bytes((bytes(width - 1) + b"\x80") * len(J), "little")

    @staticmethod
    def table(rows: Any, width: Any) -> Any:
        """(width, signs s_c, cells): each |a_jc| and 2^(S-1) - K b_j as W little-endian bytes,
        column by column, once; a :class:`_Packed` joins the cells of its rows."""
        columns = len(rows[0][0])
        n = columns // 2
        half = 1 << (8 * width - 1)
        cells = [[abs(row[0][c]).to_bytes(width, "little") for row in rows] for c in range(columns)]
        cells.append([(half - row[1]).to_bytes(width, "little") for row in rows])
        return width, [1] * n + [-1] * n, cells

    def outside(self, box: Any) -> Any:
        """The rows J_t for which :func:`_outside` holds (in the order of J)."""
        X = self.base
        for C, s, x in zip(self.columns, self.signs, box):
            if x:
                X += C * (x if s > 0 else -x)
        Y = X & self.mask
        if not Y:
            return []
        data, out = Y.to_bytes(self.size, "little"), []
        at = data.find(0x80)
        while at >= 0:
            out.append(self.J[at // self.width])
            at = data.find(0x80, at + 1)
        return out


def survivors(G: Any, b: Any, vertices: Any, N: Any, T: Any) -> Any:
    """{vertex index: [facets]} of the pairs the test on the pieces of [0, T] cannot prune
    (:func:`survivors_of_pieces` on the secants and remainders of A_d(h)), after pricing the
    pieces (:func:`pieces_cost`)."""
    ends = nodes(T)
    within_budget(pieces_cost(N, ends), f"the {len(ends) - 1} pieces of the pruning test "
                  f"(degree {len(N) - 1}, n = {len(N[0])})")
    return survivors_of_pieces(G, b, vertices, chord_pieces(N, T))


def survivors_of_pieces(G: Any, b: Any, vertices: Any, pieces: Any) -> Any:
    """{vertex index: [facets]} of the pairs the chord test cannot prune on the pieces given
    as (X, Z, M) (the path of v on a piece within M |v| entrywise of the chord from X v to
    Z v): exactly the pairs (i, j) with :func:`_outside` for row j and vertex i's box at
    some end (:meth:`_Ends.boxes` of :func:`vertex_box`).  The boxes around blocks of
    vertices along :func:`morton_order` only skip work (the box (1) of a block holds those
    of its vertices): a block's boxes against every row, each vertex's against the rows its
    block does not clear there (:class:`_Packed`)."""
    rows = integer_rows(G, b)
    out: dict[int, set[Any]] = {i: set() for i in range(len(vertices))}
    if not rows or not vertices:
        return {i: [] for i in out}
    boxes = [vertex_box(v) for v in vertices]
    n = len(boxes[0][0])
    within_budget(80 * n * n * 2 * len(pieces), f"the {2 * len(pieces)} chord ends of the pruning test (n = {n})")
    ends = _Ends(pieces, boxes)
    box_count = len(vertices) + len(vertices) // max(1, isqrt(len(vertices))) + 1
    within_budget(20 * box_count * 3 * n * n * (1 + ends.count * ends.width * 8 // 4096),
                  f"the boxes of {len(vertices)} vertices at {ends.count} chord ends (n = {n})")
    packed_rows = [([max(x, 0) for x in g] + [min(x, 0) for x in g], K * beta) for g, beta in rows]
    width = _slot_bytes(packed_rows, (ends.coordinate_max >> SHIFT) + 1)
    require_budget(width * len(rows) * (2 * ends.n + 1) <= MAX_PACKED_BYTES,
            f"over the kernel's work budget: {len(rows)} rows packed in slots of {width} bytes")
    table = _Packed.table(packed_rows, width)
    everything = _Packed(table, list(range(len(rows))))
    order, size, total, slot_tests = morton_order(boxes), max(1, isqrt(len(vertices))), 0, 0
    for start in range(0, len(order), size):
        block = order[start:start + size]
        per_end = ends.boxes(group_box([boxes[i] for i in block]))
        near = everything.outside(_hull(per_end))
        if not near:
            continue
        near_rows = _Packed(table, near)
        hits = [(e, _Packed(table, found)) for e, found in enumerate(near_rows.outside(box) for box in per_end) if found]
        tests = len(block) * sum(len(rows_e.J) for _, rows_e in hits)
        slot_tests += tests
        charge(2 * tests, "the vertex-facet tests at the chord ends")  # measured: 1.3e8 tests in 5 s
        require_budget(slot_tests <= MAX_SLOT_TESTS, f"over the kernel's work budget: more than {MAX_SLOT_TESTS:.0e} "
                f"vertex-facet tests at the chord ends, past the blocks")
        for i in block:
            mine = ends.boxes(boxes[i])
            before = len(out[i])
            for e, rows_e in hits:
                out[i].update(rows_e.outside(mine[e]))
            total += len(out[i]) - before
            require(total <= budget.MAX_CONDITIONS,
                    f"more than {budget.MAX_CONDITIONS} pairs survive the pruning test: they exceed the kernel's bound")
    return {i: sorted(f) for i, f in out.items()}
