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
       A_d(t + s) v = X + s Y + R(s),  X = D_0 v,  Y = D_1 v,
       |R(s)| <= M |v| entrywise,  M = sum_{k>=2} d^k |D_k|,
   so on the piece A_d(h) v lies within rho_v = max_i (M |v|)_i (in every
   coordinate) of the chord from X to Z = X + d Y.  A linear function is
   largest on the chord at an end: both ends, widened by rho_v, inside the
   open half-space g_j x < b_j on every piece prove the condition positive
   on [0, T].  The kernel decides this itself for every pair, in
   integers: coordinates are rounded outwards to a grid of step 1/K, so it
   may keep more pairs than needed, never fewer.  To stay cheap it tests
   boxes around blocks of consecutive vertices along ``order`` (any
   permutation; a good one keeps near vertices together) first over all
   pieces at once, then piece by piece, then around chunks of each block,
   and only then vertex by vertex (at both chord ends); each box against many facets at once
   (:class:`_Packed`: one integer, one facet per fixed-width slot).  The
   kept pairs are exactly those of the vertex-by-vertex test: a box around
   boxes clears a facet only if each of them does.
3. Every surviving pair, all of vertex k's pairs, every ray and line pair are
   built; with 1 and 2 their valid set (or first interval) is that of all pairs.
The horizon is short (numerator and denominator of at most 64 bits): the pieces' exact powers t^i then stay
small; a longer one is rejected before any piece is built.
"""

from fractions import Fraction
from math import comb, gcd, isqrt

from . import conditions
from .rationals import integer, rational, require

K = 1 << 40  # the integer grid
HORIZON_BITS = 64  # the horizon's numerator and denominator: the pieces' powers t^i stay short (work budget)
MAX_PACKED_BYTES = 1 << 27  # the packed rows' table: every slot as wide as the widest row needs


def _ceil(x):
    return -((-x.numerator) // x.denominator)


def _floor(x):
    return x.numerator // x.denominator


def parse(record, vertex_count):
    """(T, k, order) from a pruning record, shape-checked."""
    require(isinstance(record, dict) and set(record) == {"horizon", "vertex", "order"},
            "pruning has the keys horizon, vertex, order")
    T = rational(record["horizon"], "pruning horizon")
    require(T >= 0, "the pruning horizon is negative")
    require(max(T.numerator.bit_length(), T.denominator.bit_length()) <= HORIZON_BITS,
            f"over the kernel's work budget: the pruning horizon needs a numerator and denominator of at most "
            f"{HORIZON_BITS} bits (a short upper bound of the set's end)")
    k = integer(record["vertex"], "pruning vertex", 0, vertex_count)
    order = record["order"]
    require(isinstance(order, list) and len(order) == vertex_count
            and all(type(i) is int for i in order) and sorted(order) == list(range(vertex_count)),
            "pruning order is not a permutation of the vertices")
    return T, k, order


def nodes(T):
    """The ends of the pieces of [0, T]."""
    if T == 0:
        return [Fraction(0), Fraction(0)]
    xs = {Fraction(0), Fraction(1)} | {Fraction(a, 16) for a in range(1, 16)}
    xs |= {Fraction(1, 2**i) for i in range(1, 13)} | {1 - Fraction(1, 2**i) for i in range(1, 13)}
    return [T * x for x in sorted(xs)]


def _piece(N, t, d):
    """(D_0, d D_1, M) for the piece [t, t + d]: A_d(t + s) = sum_k s^k D_k with
    D_k = sum_{i>=k} C(i, k) t^(i-k) N_i, and M = sum_{k>=2} d^k |D_k| entrywise."""
    n = len(N[0])
    D = [[[sum(comb(i, k) * t ** (i - k) * N[i][r][c] for i in range(k, len(N))) for c in range(n)] for r in range(n)]
         for k in range(len(N))]
    zero = [[Fraction(0)] * n for _ in range(n)]
    Y = [[d * x for x in row] for row in D[1]] if len(D) > 1 else zero
    M = [[sum(d**k * abs(D[k][r][c]) for k in range(2, len(D))) for c in range(n)] for r in range(n)]
    return D[0], Y, M


def _integer_rows(G, b):
    """Each row of (G | b) times a positive integer: (g+ g- ||g||_1 concatenated, K b)."""
    rows = []
    for g, beta in zip(G, b):
        d = 1
        for x in list(g) + [beta]:
            d = d * x.denominator // gcd(d, x.denominator)
        gi = [int(x * d) for x in g]
        rows.append(([max(x, 0) for x in gi] + [min(x, 0) for x in gi] + [sum(map(abs, gi))], int(beta * d) * K))
    return rows


def _integer_matrix(Q):
    """(Q_int, d) with Q = Q_int / d, d > 0."""
    d = 1
    for row in Q:
        for x in row:
            d = d * x.denominator // gcd(d, x.denominator)
    return [[int(x * d) for x in row] for row in Q], d


def chord_pieces(N, T):
    """(X, Z, M) per piece of [0, T]: the chord ends X = A_d(t), Z = A_d(t + d) and the remainder M."""
    ends = nodes(T)
    out = []
    for t, u in zip(ends, ends[1:]):
        X, Y, M = _piece(N, t, u - t)
        out.append((X, [[x + y for x, y in zip(rx, ry)] for rx, ry in zip(X, Y)], M))
    return out


def _boxes(vertices, pieces):
    """boxes[i][a] = (end X, end Z), each hi + lo + [B]: the integer box around one chord end
    of vertex i on piece a (scaled by K, rounded outwards, so at most one grid step wide),
    widened by B / K >= rho; integer arithmetic only.  The chord's box is their union; a
    linear function is largest on the chord at one of its ends, so a half-space holding
    both widened end boxes holds the whole path on the piece."""
    maps = []
    for X, Z, M in pieces:
        (Xi, dX), (Zi, dZ), (Mi, dM) = (_integer_matrix(Q) for Q in (X, Z, M))
        maps.append(([[K * x for x in row] for row in Xi], dX, [[K * x for x in row] for row in Zi], dZ,
                     [[K * x for x in row] for row in Mi], dM))
    out = []
    for v in vertices:
        q = 1
        for x in v:
            q = q * x.denominator // gcd(q, x.denominator)
        p = [int(x * q) for x in v]
        ap = [abs(x) for x in p]
        mine = []
        for KX, dX, KZ, dZ, KM, dM in maps:
            dx, dz = dX * q, dZ * q
            hx, lx, hz, lz = [], [], [], []
            for row_x, row_z in zip(KX, KZ):  # K (X v) = (K dX q X v) / (dX q), likewise Z
                fx, rx = divmod(sum(map(int.__mul__, row_x, p)), dx)
                fz, rz = divmod(sum(map(int.__mul__, row_z, p)), dz)
                lx.append(fx)
                hx.append(fx + (rx > 0))  # ceilings
                lz.append(fz)
                hz.append(fz + (rz > 0))
            rho = [-(-max(sum(map(int.__mul__, row, ap)) for row in KM) // (dM * q))]  # K dM q rho / (dM q)
            mine.append((hx + lx + rho, hz + lz + rho))
        out.append(mine)
    return out


def _union(boxes):
    """The box around boxes given as (hi lo B concatenated): coordinate-wise max of hi and B, min of lo."""
    n = (len(boxes[0]) - 1) // 2
    cols = list(zip(*boxes))
    return [max(c) for c in cols[:n]] + [min(c) for c in cols[n:2 * n]] + [max(cols[-1])]


def _outside(row, box):
    """True unless the box [lo, hi] / K widened by B / K lies in g x < b (then the pairs are pruned):
    max over the box of g x is g+ hi + g- lo, and |g (A_d - I) ...| adds at most ||g||_1 B / K."""
    return row[1] <= sum(map(int.__mul__, row[0], box))


def _slot_bytes(rows, boxes):
    """Bytes per slot of a :class:`_Packed` test: |g . box - K b| < 2^(8 W - 2) for every
    row and every box given (or union of them: the same entries), and every |row entry| and
    |K b| as well."""
    coefficient = max(abs(x) for row in rows for x in row[0])
    entry = max(abs(x) for box in boxes for x in box)
    threshold = max(abs(row[1]) for row in rows)
    bound = len(rows[0][0]) * coefficient * entry + threshold + coefficient
    return (bound.bit_length() + 2 + 7) // 8


class _Packed:
    """The test :func:`_outside` of one box against many rows at once, in one integer.

    Slot t of width S = 8 W bits holds row J_t.  With the columns
    C_c = sum_t |a_{J_t c}| 2^(S t) (a column of the rows has one sign s_c: g+ and
    ||g||_1 are >= 0, g- <= 0) and E = sum_t (2^(S-1) - K b_{J_t}) 2^(S t),

        X = E + sum_c s_c box_c C_c = sum_t (2^(S-1) + v_t) 2^(S t),
        v_t = a_{J_t} . box - K b_{J_t},

    an identity of integers.  |v_t| < 2^(S-2) (:func:`_slot_bytes`), so each
    2^(S-1) + v_t is a digit in [0, 2^S) of X in base 2^S, and its top bit is set
    iff v_t >= 0, i.e. iff :func:`_outside` holds for row J_t: those slots are read
    off X masked to the top bits (bytes 0x80 of its little-endian bytes)."""

    def __init__(self, table, J):
        width, signs, cells = table
        self.J, self.width, self.size, self.signs = J, width, width * len(J), signs
        self.columns = [int.from_bytes(b"".join([column[j] for j in J]), "little") for column in cells[:-1]]
        self.base = int.from_bytes(b"".join([cells[-1][j] for j in J]), "little")
        self.mask = int.from_bytes((bytes(width - 1) + b"\x80") * len(J), "little")

    @staticmethod
    def table(rows, width):
        """(width, signs s_c, cells): each |a_jc| and 2^(S-1) - K b_j as W little-endian bytes,
        column by column, once; a :class:`_Packed` joins the cells of its rows."""
        columns = len(rows[0][0])
        n = (columns - 1) // 2
        half = 1 << (8 * width - 1)
        cells = [[abs(row[0][c]).to_bytes(width, "little") for row in rows] for c in range(columns)]
        cells.append([(half - row[1]).to_bytes(width, "little") for row in rows])
        return width, [1] * n + [-1] * n + [1], cells

    def outside(self, box):
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


def survivors(G, b, vertices, N, T, order):
    """{vertex index: [facets]} of the pairs the test on the pieces of [0, T] cannot prune
    (:func:`survivors_of_pieces` on the chords and Taylor remainders of A_d(h))."""
    return survivors_of_pieces(G, b, vertices, chord_pieces(N, T), order)


def survivors_of_pieces(G, b, vertices, pieces, order):
    """{vertex index: [facets]} of the pairs the chord test cannot prune on the pieces given
    as (X, Z, M) (the path of v on a piece within max_i (M |v|)_i of the chord from X v to
    Z v): exactly the pairs (i, j) with :func:`_outside` for row j and one of the two
    widened chord-end boxes of vertex i on some piece (a box around boxes is outside
    whenever one of them is, so the blocks of vertices along ``order`` and their chunks
    only skip work), each test done by :class:`_Packed`."""
    rows = _integer_rows(G, b)
    boxes = _boxes(vertices, pieces)
    out = {i: set() for i in range(len(vertices))}
    if not rows:
        return {i: [] for i in out}
    every_box = [box for per_vertex in boxes for ends in per_vertex for box in ends]
    width = _slot_bytes(rows, every_box)
    require(width * len(rows) * (len(rows[0][0]) + 1) <= MAX_PACKED_BYTES,
            f"over the kernel's work budget: {len(rows)} rows packed in slots of {width} bytes")
    table = _Packed.table(rows, width)
    everything = _Packed(table, list(range(len(rows))))
    size, total = max(1, isqrt(len(vertices))), [0]
    for start in range(0, len(order), size):
        block = order[start:start + size]
        chunks = [block[k:k + isqrt(size)] for k in range(0, len(block), isqrt(size))]
        per_chunk = [[_union([end for i in chunk for end in boxes[i][a]]) for a in range(len(boxes[block[0]]))]
                     for chunk in chunks]
        per_piece = [_union(list(boxes_a)) for boxes_a in zip(*per_chunk)]
        near = everything.outside(_union(per_piece))
        if near:
            near_rows = _Packed(table, near)
            for a, box in enumerate(per_piece):
                _descend(table, near_rows.outside(box), [(chunk, c[a]) for chunk, c in zip(chunks, per_chunk)],
                         boxes, a, out, total)
    return {i: sorted(f) for i, f in out.items()}


def _descend(table, hits, chunks, boxes, a, out, total):
    """Piece a of one block: the rows ``hits`` its box does not clear, tested on each
    chunk's box, then on the boxes of the chunk's vertices (``total[0]`` counts the
    distinct pairs found: past the kernel's bound on conditions, reject at once)."""
    if not hits:
        return
    hit_rows = _Packed(table, hits)
    for chunk, box in chunks:
        close = hit_rows.outside(box)
        if close:
            close_rows = _Packed(table, close)
            for i in chunk:
                x, z = boxes[i][a]
                before = len(out[i])
                out[i].update(close_rows.outside(x))
                out[i].update(close_rows.outside(z))
                total[0] += len(out[i]) - before
                require(total[0] <= conditions.MAX_CONDITIONS,
                        f"more than {conditions.MAX_CONDITIONS} pairs survive the pruning test: they exceed the kernel's bound")
