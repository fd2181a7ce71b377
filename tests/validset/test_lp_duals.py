"""Dual pieces of the LP route (exactinv/validset/lp_duals.py): the paper's certificate y(h) = sum (h - a)^k
y_k >= 0 along a piece where the facet is far from binding.  The valid set is identical with them and
without them, and to the vertex route's, end by end and flag by flag; the kernel checks every certificate;
a dual piece found by hand matches its worked values."""

import random
from fractions import Fraction

import flint
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

import exactinv as ei
import exactinv_check
from exactinv.core.scalars import INF
from exactinv.lp.solver import ExactLPSolver
from exactinv.validset import lp_route as engine_lp
from exactinv.validset.lp_duals import DualCertificate, dual_piece, dual_target

M = ei.methods
F = Fraction
FORCED = engine_lp.DualPolicy(F(0), 0, 1, 10**9)  # try a dual piece at the end of every basis piece


def _ends(V):
    return [(iv.lo, iv.hi, iv.lo_closed, iv.hi_closed) for iv in V]


@pytest.fixture
def forced(monkeypatch):
    monkeypatch.setattr(engine_lp, "DUAL_POLICY", FORCED)


def _with(policy, S, P, m):
    old = engine_lp.DUAL_POLICY
    engine_lp.DUAL_POLICY = policy
    try:
        return ei.valid_steplengths(S, P, m, route="lp")
    finally:
        engine_lp.DUAL_POLICY = old


# ------------------------------------------------------------------ worked by hand


def test_dual_piece_on_an_interval_by_hand():
    """x' = -x on [-1, 1], forward Euler, facet 0 (x <= 1) from a = 1/2 with the basis {0} (x_B = 1):
    D N^T g_0 = 1 - h = 1/2 - (h - 1/2), so y_0 = (1/2, 0) and y_1 solves G^T y = -1, y >= 0: (0, 1);
    y(h)^T b = h, q = 1 - h, whose root 1 ends the piece (phi_0(h) = 1 - h <= 1 there)."""
    G = flint.fmpq_mat([[1], [-1]])
    b = flint.fmpq_mat(2, 1, [1, 1])
    C = flint.fmpq_mat([[1, -1]])  # c_0(h) = (g_0 N_0, g_0 N_1) = (1, -1)
    D = flint.fmpq_poly([1])
    target = dual_target(C, D)
    y0 = ((0,), [flint.fmpq(1, 2)])  # the basis {0} at a = 1/2: B^-T d_0 = 1/2
    cert = dual_piece(G, b, F(1), D, target, y0, ExactLPSolver(G, (False, False)), F(1, 2), None)
    assert cert == DualCertificate(F(1, 2), F(1), (((0, F(1, 2)),), ((1, F(1)),)))
    assert cert.record() == {"dual": [[[0, "1/2"]], [[1, "1"]]]}
    capped = dual_piece(G, b, F(1), D, target, y0, ExactLPSolver(G, (False, False)), F(1, 2), F(3, 4))
    assert capped.end == F(3, 4)


def test_no_dual_piece_where_the_facet_binds_or_the_basis_is_not_optimal():
    G = flint.fmpq_mat([[1], [-1]])
    b = flint.fmpq_mat(2, 1, [1, 1])
    C = flint.fmpq_mat([[1, -1]])
    D = flint.fmpq_poly([1])
    solver = ExactLPSolver(G, (False, False))
    target = dual_target(C, D)
    assert dual_piece(G, b, F(1), D, target, ((0,), [flint.fmpq(1)]), solver, F(0), None) is None  # q(0) = 0
    # the basis {1} at a = 1/2: B^-T d_0 = -1/2 < 0, not optimal
    assert dual_piece(G, b, F(1), D, target, ((1,), [flint.fmpq(-1, 2)]), solver, F(1, 2), None) is None


def test_an_unbounded_direction_gives_no_dual_piece():
    """P = {x <= 1} (a half-line): y_1 would need G^T y = -1 with y >= 0 -- none exists (Farkas: the ray -1)."""
    G = flint.fmpq_mat([[1]])
    b = flint.fmpq_mat(1, 1, [1])
    cert = dual_piece(G, b, F(1), flint.fmpq_poly([1]), dual_target(flint.fmpq_mat([[1, -1]]), flint.fmpq_poly([1])),
                      ((0,), [flint.fmpq(1, 2)]), ExactLPSolver(G, (False,)), F(1, 2), None)
    assert cert is None


def test_the_random_family_gets_dual_pieces_and_the_same_set(forced):
    """R^6 with 36 facets, Taylor-4: dual pieces replace runs of basis pieces; the set is the same as without
    them and as the vertex route's, and both certificates check."""
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
    from lp_route import family
    S, P = family(5, 20)
    V_on = ei.valid_steplengths(S, P, M.taylor(4), route="lp")
    V_off = _with(None, S, P, M.taylor(4))
    V_vertex = ei.valid_steplengths(S, P, M.taylor(4), route="vertex")
    assert V_on.lp.duals > 0 and V_off.lp.duals == 0
    assert V_on.lp.pieces < V_off.lp.pieces
    assert _ends(V_on) == _ends(V_off) == _ends(V_vertex)
    assert exactinv_check.check(V_on.certificate).ok
    L_on = ei.largest_threshold(S, P, M.taylor(4), route="lp")
    L_vertex = ei.largest_threshold(S, P, M.taylor(4), route="vertex")
    assert (L_on.value, L_on.attained) == (L_vertex.value, L_vertex.attained)


BOX3 = [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]]


@pytest.mark.parametrize("A, G, b, method", [
    ([[0, 1, 1], [1, -3, 0], [0, 0, 2]], BOX3, [2] * 6, M.pade(1, 1)),
    ([[-2, 3, 3], [1, 3, F(-1, 2)], [1, 2, F(-1, 2)]], BOX3 + [[-2, -2, 1], [-1, 1, -1]], [2] * 6 + [1, 4],
     M.backward_euler())], ids=["pade11", "backward-euler"])
def test_a_dual_piece_starting_a_hair_below_a_root_of_q_ends_before_it(A, G, b, method):
    """Found by hypothesis (session 6), dual pieces forced.  In the first, a dual piece of facet 1 started at
    a = 215027748241771/2^48, 1.1e-16 below the root 3 - sqrt 5 of its q; the root's 2^-44 enclosure reached
    below a, the engine took q > 0 up to the cap and wrote a piece the kernel rejected (q < 0 at 3.68).  Now the
    root's enclosure is refined until it passes a."""
    S, P, m = ei.LinearSystem(A), ei.Polyhedron(G, b), method
    V_on = _with(FORCED, S, P, m)
    report = exactinv_check.check(V_on.certificate)
    assert report.ok, report
    assert _ends(V_on) == _ends(ei.valid_steplengths(S, P, m, route="vertex"))


# ------------------------------------------------------------------ properties, dual pieces forced on

METHODS = [M.taylor(p) for p in range(1, 6)] + [M.backward_euler(), M.pade(1, 1), M.pade(2, 2), M.theta("1/3")]


@st.composite
def polytopes(draw, lines=False, unbounded=False):
    """Random P in R^n (n <= 3): the box [-2, 2]^n cut by random rows (bounded); with ``unbounded`` only
    rows with g . (1, .., 1) <= 0 and no box (a ray (1, .., 1)); with ``lines`` the last coordinate free
    (rank G < n).  A random rational A and a method."""
    n = draw(st.integers(1, 3)) + (1 if lines else 0)
    k = n - 1 if lines else n
    G, b = [], []
    if not unbounded:
        for i in range(k):
            for s in (1, -1):
                G.append([int(i == j) * s for j in range(n)])
                b.append(2)
    for _ in range(draw(st.integers(1 if unbounded else 0, 4))):
        row = [draw(st.integers(-3, 3)) for _ in range(k)] + ([0] if lines else [])
        assume(any(row))
        if unbounded and sum(row) > 0:
            row = [-g for g in row]
        assume(not unbounded or sum(row) < 0)
        G.append(row)
        b.append(draw(st.integers(1, 4)))
    q = st.fractions(min_value=-3, max_value=3, max_denominator=3)
    A = [[draw(q) for _ in range(n)] for _ in range(n)]
    if lines:  # the line e_n maps into itself (A e_n = a e_n), else the facets' line equalities decide all
        for i in range(n - 1):
            A[i][n - 1] = F(0)
    return ei.LinearSystem(A), ei.Polyhedron(G, b), draw(st.sampled_from(METHODS))


@pytest.mark.parametrize("shape", [{}, {"lines": True}, {"unbounded": True}], ids=["bounded", "lines", "rays"])
@settings(max_examples=30, deadline=None)
@given(data=st.data())
def test_with_dual_pieces_forced_the_lp_route_equals_the_vertex_route(shape, data):
    S, P, m = data.draw(polytopes(**shape))
    try:
        V_on = _with(FORCED, S, P, m)
    except ei.ExactinvError:
        if shape.get("unbounded"):
            return  # declined (an irrational touching point of ray conditions): the vertex route's case
        raise
    V_vertex = ei.valid_steplengths(S, P, m, route="vertex")
    assert _ends(V_on) == _ends(V_vertex)
    assert exactinv_check.check(V_on.certificate).ok


@pytest.mark.parametrize("seed", range(3))
def test_forced_on_off_and_default_policies_agree_on_the_random_family(seed):
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
    from lp_route import family
    S, P = family(4, 14, seed)
    method = random.Random(seed).choice([M.taylor(3), M.pade(1, 1), M.taylor(6)])
    sets = [_ends(_with(policy, S, P, method)) for policy in (FORCED, None, engine_lp.DualPolicy())]
    assert sets[0] == sets[1] == sets[2]
    assert isinstance(INF, type(INF))


def test_explain_counts_dual_pieces_apart_from_ray_pieces():
    """The selftest's octagon under Taylor-2 (every facet gets a dual piece from its breakpoint 1, where
    A_d(1) = 0): explain names the dual pieces and no ray piece."""
    from exactinv.interfaces.explain import explain
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    octagon = ei.Polyhedron([[1, 0], [-1, 0], [0, 1], [0, -1], [1, 1], [1, -1], [-1, 1], [-1, -1]],
                            [1, 1, 1, 1, "3/2", "3/2", "3/2", "3/2"])
    V = _with(FORCED, S, octagon, M.taylor(2))
    assert V.lp.duals == 8 and V.lp.rays == 0 and _ends(V) == [(0, F(3, 2), True, True)]
    text = explain(V.certificate)
    assert "8 dual pieces" in text and "ray piece" not in text


# ------------------------------------------------------------------ chained and carried dual pieces (branch lp-dualcost)


def _family(n, m, seed=1):
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
    from lp_route import family
    return family(n, m, seed)


def _taylor_directions(A, g, coeffs, a, K):
    """d_0, ..., d_K at a of N(h)^T g = sum_j c_j h^j (A^T)^j g (a polynomial method, D = 1), in plain Fractions,
    apart from the engine: d_k = sum_j c_j C(j, k) a^(j - k) (A^T)^j g."""
    from math import comb
    n = len(g)
    powers = [list(g)]
    for _ in range(len(coeffs) - 1):
        v = powers[-1]
        powers.append([sum(A[r][c] * v[r] for r in range(n)) for c in range(n)])  # A^T v
    return [[sum(coeffs[j] * comb(j, k) * a ** (j - k) * powers[j][c] for j in range(k, len(coeffs)))
             for c in range(n)] for k in range(K + 1)]


def _check_dual_piece(S, P, method, facet, piece):
    """The paper's certificate along [a, e], re-proved here in plain Fractions: every y_k >= 0, G^T y_k = d_k
    exactly for every k (d_k = 0 beyond the last y_k), and q(h) = b_i - y(h)^T b >= 0 on [a, e]."""
    from exactinv.core.roots import negative_segments
    cert = piece.dual
    a = cert.start
    G, b = [list(map(F, r)) for r in P.G], [F(v) for v in P.b]
    coeffs = [F(c) for c in method.numerator]
    W = len(coeffs)
    assert len(cert.ys) <= W
    d = _taylor_directions([list(map(F, r)) for r in S.A], G[facet], coeffs, a, W - 1)
    betas = []
    for k in range(W):
        y = cert.ys[k] if k < len(cert.ys) else ()
        assert all(v > 0 and isinstance(v, F) for _, v in y) and [r for r, _ in y] == sorted({r for r, _ in y})
        assert [sum(v * G[r][c] for r, v in y) for c in range(len(G[0]))] == d[k]
        betas.append(sum(v * b[r] for r, v in y))
    q = flint.fmpq_poly([flint.fmpq(b[facet].numerator, b[facet].denominator)]) - flint.fmpq_poly(
        [flint.fmpq(v.numerator, v.denominator) for v in betas])  # q(a + s), s = h - a
    assert q(0) > 0
    span = None if cert.end == INF else cert.end - a
    for lo, _ in negative_segments(q):
        assert span is not None and not lo < span  # q >= 0 on [0, span]


def test_chained_and_carried_dual_pieces_are_the_papers_certificate_exactly(monkeypatch):
    """R^5 with 20 facets, Taylor-4, dual pieces tried after one basis piece: dual pieces follow dual pieces
    directly (y_0 from the float LP's basis at the previous end), some with y_1, y_2, ... carried over from the
    previous piece's y(h) (no LP); every dual piece re-proved apart from the engine, the set the same as
    without dual pieces and as the vertex route's, the certificate accepted by the kernel."""
    from exactinv.validset import lp_duals
    carried = []
    original = lp_duals.DualCertificate.taylor_at
    monkeypatch.setattr(lp_duals.DualCertificate, "taylor_at",
                        lambda self, a, first=0: carried.append(a) or original(self, a, first))
    S, P = _family(5, 20)
    method = M.taylor(4)
    V = _with(engine_lp.DualPolicy(after=1), S, P, method)
    chained = 0
    for f in V.lp.facets:
        for before, piece in zip(f.pieces, f.pieces[1:]):
            chained += before.dual is not None and piece.dual is not None
        for piece in f.pieces:
            if piece.dual is not None:
                _check_dual_piece(S, P, method, f.facet, piece)
    assert chained > 0 and carried
    assert _ends(V) == _ends(_with(None, S, P, method)) == _ends(ei.valid_steplengths(S, P, method, route="vertex"))
    assert exactinv_check.check(V.certificate).ok


@settings(max_examples=30, deadline=None)
@given(data=st.data())
def test_a_dual_pieces_y_written_at_a_later_start_is_the_same_polynomial(data):
    """DualCertificate.taylor_at: z_k = sum_j C(j, k) (a - start)^(j - k) y_j are >= 0, sum_k (h - a)^k z_k is
    the same y(h) at every h (so G^T z_k are the Taylor coefficients at a of the same target), and b^T z_k
    from the y_j's own b^T y_j (lp_duals._carried_betas) is exact."""
    from exactinv.validset.lp_duals import _carried_betas
    m = data.draw(st.integers(1, 6))
    value = st.fractions(min_value=F(1, 7), max_value=5, max_denominator=7)
    K = data.draw(st.integers(1, 5))
    ys = []
    for _ in range(K):
        rows = sorted(data.draw(st.sets(st.integers(0, m - 1), max_size=m)))
        ys.append(tuple((r, data.draw(value)) for r in rows))
    start = data.draw(st.fractions(min_value=0, max_value=3, max_denominator=5))
    a = start + data.draw(st.fractions(min_value=0, max_value=2, max_denominator=9))
    cert = DualCertificate(start, INF, tuple(ys))
    z = cert.taylor_at(a)
    assert all(v > 0 for y in z for _, v in y)
    assert cert.taylor_at(a, 1) == z[1:] and cert.taylor_at(a, K) == []
    for h in (a, a + F(1, 3), a + 2, start + 7):
        old = [sum(F(str(v)) * (h - start) ** k for k, y in enumerate(ys) for r2, v in y if r2 == r) for r in range(m)]
        new = [sum(F(str(v)) * (h - a) ** k for k, y in enumerate(z) for r2, v in y if r2 == r) for r in range(m)]
        assert old == new
    b = [flint.fmpq(r + 1, 3) for r in range(m)]
    betas = _carried_betas(cert, a, b)
    assert betas == [sum((v * b[r] for r, v in y), flint.fmpq(0)) for y in z]


@settings(max_examples=60, deadline=None)
@given(data=st.data())
def test_a_dual_pieces_end_is_proved_and_within_a_64th_of_qs_first_root(data):
    """lp_duals.piece_end, floats first (Newton on a decreasing q, else numpy's roots) and proved by Descartes,
    else the certified isolation: q >= 0 on [a, end], and the end is the cap, or at most q's first root beyond
    a and within 1/64 of the piece below it (checked by exact root isolation)."""
    from exactinv.core.roots import negative_segments, real_roots
    from exactinv.validset.lp_duals import piece_end
    c = st.fractions(min_value=-4, max_value=4, max_denominator=9)
    coeffs = [data.draw(st.fractions(min_value=F(1, 9), max_value=4, max_denominator=9))]
    coeffs += [data.draw(c) for _ in range(data.draw(st.integers(0, 5)))]
    if data.draw(st.booleans()):  # the common case: decreasing on [0, oo)
        coeffs = [coeffs[0]] + [-abs(v) for v in coeffs[1:]]
    q = flint.fmpq_poly([flint.fmpq(v.numerator, v.denominator) for v in coeffs])
    a = data.draw(st.fractions(min_value=0, max_value=3, max_denominator=8))
    cap = data.draw(st.one_of(st.none(), st.fractions(min_value=F(1, 8), max_value=5, max_denominator=8).map(a.__add__)))
    end = piece_end(q, a, cap)
    roots = [r for r, _ in real_roots(q) if r > 0] if q.degree() > 0 else []
    first = min(roots) if roots else None
    if end is None:
        assert first is not None and first < F(1, 2**150)
        return
    if end == INF:
        assert cap is None and not negative_segments(q)
        return
    assert end > a and (cap is None or end <= cap)
    span = end - a
    assert all(not lo < span for lo, _ in negative_segments(q))
    if first is not None:
        assert not first < span  # at most the first root
    if end != cap:
        assert first is not None and span >= first * F(63, 64) * (1 - F(1, 10**6))


def test_dual_certificates_are_immutable_and_compare_by_value():
    c = DualCertificate(F(1), F(2), (((0, flint.fmpq(1, 2)),), ((3, flint.fmpq(2)),)))
    assert c == DualCertificate(F(1), F(2), (((0, F(1, 2)),), ((3, F(2)),)))
    assert c != DualCertificate(F(1), F(2), (((0, F(1, 2)),),))
    assert hash(c) == hash(DualCertificate(F(1), F(2), (((0, F(1, 2)),), ((3, F(2)),))))
    assert c.record() == {"dual": [[[0, "1/2"]], [[3, "2"]]]}
    assert repr(c) == ("DualCertificate(start=Fraction(1, 1), end=Fraction(2, 1), "
                       "ys=(((0, Fraction(1, 2)),), ((3, Fraction(2, 1)),)))")
    with pytest.raises(AttributeError):
        c.end = F(3)
    import copy
    import pickle
    assert pickle.loads(pickle.dumps(c)) == c and copy.deepcopy(c) == c and copy.copy(c) == c


@pytest.mark.parametrize("scale", [F(10**400), F(1, 10**400), F(1)])
def test_a_dual_pieces_end_with_coefficients_beyond_double_range(scale):
    """The float root is only a hint (exactinv.core.float_hint: inf or 0, never an exception): q(a + s) =
    scale (1 - s) (1 + s), decreasing, huge or tiny -- the end is still q's root 1 beyond a, proved exactly;
    q = scale (1 + s^2 - s) (no real root) never ends."""
    from exactinv.validset.lp_duals import piece_end
    c = flint.fmpq(scale.numerator, scale.denominator)
    assert piece_end(flint.fmpq_poly([c, 0, -c]), F(1, 3), None) == F(4, 3)
    assert piece_end(flint.fmpq_poly([c, -c, c]), F(1, 3), None) == INF
    assert piece_end(flint.fmpq_poly([c, -c, c]), F(1, 3), F(5)) == F(5)
