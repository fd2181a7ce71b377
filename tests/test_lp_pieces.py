"""The kernel's lp record (exactinv_check/routes/lp_pieces.py): genuine LP-route certificates verify;
forged pieces -- a wrong basis, a piece that skips a breakpoint, a z_B that dips negative inside a
piece, a singular or infeasible basis, ends out of order, pieces stopping short of the valid set --
are rejected."""

import copy
import random
from fractions import Fraction

import pytest

import exactinv as ei
import exactinv_check
from exactinv_check import poly_arithmetic, polys
from exactinv_check.reals import Real, separate
from exactinv_check.routes import lp_pieces

M = ei.methods
F = Fraction


def _problem(seed=1, n=3, m=8, method=None):
    rng = random.Random(seed)
    G = [[rng.randint(-4, 4) for _ in range(n)] for _ in range(m)] + \
        [[int(i == j) * s for j in range(n)] for i in range(n) for s in (1, -1)]
    S = ei.LinearSystem([[F(-1 if i == j else 0) + F(rng.randint(-3, 3), 12) for j in range(n)] for i in range(n)])
    P = ei.Polyhedron(G, [1] * m + [2] * (2 * n))
    return S, P, method or M.taylor(4)


def _certificate(claim="valid", **kw):
    S, P, m = _problem(**kw)
    result = (ei.valid_steplengths if claim == "valid" else ei.largest_threshold)(S, P, m, route="lp")
    assert result.route == "lp"
    return result.certificate


def _rejected(cert, match):
    report = exactinv_check.check(cert)
    assert not report.ok, report
    assert match in str(report), report


def _lp(cert):
    return cert["claims"][0]["lp"]["facets"]


@pytest.mark.parametrize("claim", ["valid", "largest"])
@pytest.mark.parametrize("method", [M.taylor(4), M.taylor(1), M.pade(1, 1), M.backward_euler()])
def test_genuine_certificates_verify(claim, method):
    cert = _certificate(claim, method=method)
    assert "vertices" not in cert["claims"][0] and "lp" in cert["claims"][0]
    report = exactinv_check.check(cert)
    assert report.ok, report
    assert "LP route" in str(report)


def _facet_with_pieces(cert, count=2):
    for i, f in enumerate(_lp(cert)):
        if len(f["bases"]) >= count:
            return i, f
    pytest.skip("no facet with enough pieces")


def test_a_wrong_basis_is_rejected():
    """The basis of the next piece on the previous one: not optimal there (z_B < 0 on part of it)."""
    cert = _certificate()
    i, f = _facet_with_pieces(cert)
    f["bases"][0] = list(f["bases"][1])
    _rejected(cert, "negative inside its piece")


def test_a_piece_that_skips_a_breakpoint_is_rejected():
    """Two pieces merged into one with the first basis: past the breakpoint its z_B turns negative."""
    cert = _certificate()
    i, f = _facet_with_pieces(cert)
    del f["ends"][0]
    del f["bases"][1]
    _rejected(cert, "negative inside its piece")


def test_a_z_b_dipping_negative_inside_a_piece_is_rejected():
    """A piece's end moved a little past the true breakpoint (a rational just beyond it): z_B is
    negative on a sliver at the end of the piece; Descartes cannot prove it, the cells do."""
    cert = _certificate()
    i, f = _facet_with_pieces(cert)
    end, nxt = Real.parse(f["ends"][0]), Real.parse(f["ends"][1])
    if nxt.inf:
        shifted = end.bounds()[1] + F(1, 2**40)
    else:
        a1, b0 = separate(end, nxt)  # end <= a1 < b0 <= next
        shifted = a1 + (b0 - a1) / 2**20  # just past the true breakpoint, before the next end
    f["ends"][0] = str(shifted)
    _rejected(cert, "negative inside its piece")


def test_a_singular_or_infeasible_basis_is_rejected():
    cert = _certificate()
    f = _lp(cert)[0]
    f["bases"][0] = [f["bases"][0][0]] * len(f["bases"][0])
    _rejected(cert, "repeats a row")
    cert = _certificate()
    f = _lp(cert)[0]
    n = len(f["bases"][0])
    m = len(cert["problem"]["G"])
    # the n rows 0..n-1 of G: a vertex of the arrangement, mostly not of P (or singular)
    for rows in ([0, 1, 2][:n], [1, 2, 3][:n], [2, 3, 4][:n]):
        forged = copy.deepcopy(cert)
        _lp(forged)[0]["bases"][0] = rows
        report = exactinv_check.check(forged)
        assert not report.ok
        assert any(word in str(report) for word in ("violates row", "singular", "negative inside")), report
    assert m > n


def test_ends_out_of_order_or_infinite_too_early_are_rejected():
    cert = _certificate()
    i, f = _facet_with_pieces(cert)
    f["ends"][1] = "0"  # the second piece ends before it starts
    _rejected(cert, "not increasing")
    cert = _certificate()
    i, f = _facet_with_pieces(cert)
    f["ends"][1] = f["ends"][0]  # a second piece of length 0: a point piece, whose neighbour then skips a breakpoint
    assert not exactinv_check.check(cert).ok
    cert = _certificate()
    i, f = _facet_with_pieces(cert)
    f["ends"][0] = "oo"
    report = exactinv_check.check(cert)
    assert not report.ok


def test_pieces_stopping_short_of_the_valid_set_are_rejected():
    """Every facet cut after its first piece: the horizon E is then below the valid set's end."""
    cert = _certificate()
    for f in _lp(cert):
        del f["ends"][1:]
        del f["bases"][1:]
    report = exactinv_check.check(cert)
    assert not report.ok
    assert any(w in str(report) for w in ("beyond it", "negative inside", "valid set")), report


def test_the_record_shape_is_checked():
    cert = _certificate()
    cert["claims"][0]["lp"]["facets"].pop()
    _rejected(cert, "one entry per facet")
    cert = _certificate()
    cert["claims"][0]["vertices"] = [["0", "0", "0"]]
    _rejected(cert, "neither a box nor generators")
    cert = _certificate()
    _lp(cert)[0]["bases"][0] = [0, 1]
    _rejected(cert, "a list of 3 rows")


def test_the_work_is_priced_first(monkeypatch):
    monkeypatch.setattr(lp_pieces, "MAX_PIECES", 2)
    _rejected(_certificate(), "more than 2 pieces")


def test_a_claimed_valid_set_that_differs_is_rejected():
    cert = _certificate()
    claim = cert["claims"][0]
    claim["intervals"][-1]["hi_closed"] = not claim["intervals"][-1]["hi_closed"]
    assert not exactinv_check.check(cert).ok


def test_a_breakpoint_moved_a_hair_early_is_rejected():
    """The end of the first piece moved to a rational 2^-60 below the true breakpoint: the next
    piece's basis is then claimed on a sliver where one of its components is still negative."""
    cert = _certificate()
    i, f = _facet_with_pieces(cert)
    end = Real.parse(f["ends"][0])
    f["ends"][0] = str(end.bounds()[0] - F(1, 2**60))
    _rejected(cert, "negative inside its piece")


def test_the_pieces_together_are_priced_first(monkeypatch):
    monkeypatch.setattr(lp_pieces, "LP_WORK_BUDGET", 10**3)
    _rejected(_certificate(), "the LP route's")


# ------------------------------------------------------------------ the cheap paths, against the direct ones

from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from exactinv_check.failure import CheckFailure  # noqa: E402
from exactinv_check.linalg import integer_determinant, integer_solve  # noqa: E402

_small = st.integers(-6, 6)


def _adjugate(B):
    n = len(B)
    return integer_solve(B, [[int(i == j) for j in range(n)] for i in range(n)])


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 5).flatmap(lambda n: st.tuples(
    st.lists(st.lists(_small, min_size=n, max_size=n), min_size=n, max_size=n),
    st.lists(_small, min_size=n, max_size=n), st.integers(0, n - 1))))
def test_a_row_exchange_gives_the_adjugate_and_determinant_of_bareiss(data):
    """adj and det after replacing one row (n^2 update) equal Bareiss' on the new matrix; a
    singular result is rejected, never returned."""
    B, g, p = data
    d, adj = _adjugate(B)
    if d == 0:
        return
    n = len(B)
    rows = [(list(r), 0) for r in B] + [(list(g), 0)]
    new = [list(r) for r in B]
    new[p] = list(g)
    if integer_determinant(new) == 0:
        with pytest.raises(CheckFailure, match="singular"):
            lp_pieces._exchange(rows, (tuple(range(n)), d, adj), p, n)
        return
    order, d2, adj2 = lp_pieces._exchange(rows, (tuple(range(n)), d, adj), p, n)
    assert order == tuple(n if k == p else k for k in range(n))
    assert (d2, adj2) == _adjugate(new)


@settings(max_examples=60, deadline=None)
@given(st.integers(1, 4).flatmap(lambda n: st.tuples(
    st.lists(st.tuples(st.lists(_small, min_size=n, max_size=n), st.integers(-20, 20)), min_size=1, max_size=9),
    st.lists(st.integers(-10**30, 10**30), min_size=n, max_size=n), st.integers(1, 10**25))))
def test_the_packed_slack_test_agrees_with_the_row_by_row_one(data):
    """All rows at once by Kronecker substitution: True exactly when every g_k x <= beta_k d."""
    rows, x, d = data
    bases = lp_pieces._Bases([g for g, _ in rows], [beta for _, beta in rows])
    truth = all(sum(a * v for a, v in zip(g, x)) <= beta * d for g, beta in bases.rows)
    assert bases.packed_slacks(x, d) == truth


def test_a_slack_of_exactly_zero_passes_and_minus_one_fails_the_packed_test():
    bases = lp_pieces._Bases([[1, 0], [0, 1], [-1, -1]], [1, 1, 5])
    assert bases.packed_slacks([1, 1], 1)        # rows 0, 1 tight: v = 0
    assert not bases.packed_slacks([2, 1], 1)    # row 0: 2 > 1
    assert not bases.packed_slacks([-3, -3], 1)  # row 2: 6 > 5


@settings(max_examples=80, deadline=None)
@given(st.lists(st.lists(st.integers(-30, 30), min_size=3, max_size=3), min_size=1, max_size=5),
       st.lists(st.integers(-3, 3), min_size=1, max_size=3).filter(lambda D: D[0] != 0),
       st.fractions(0, 4, max_denominator=16), st.one_of(st.none(), st.fractions(0, 3, max_denominator=16)))
def test_the_batched_descartes_test_is_sound_and_matches_the_single_one(Y, D, a, width):
    """Every row the batch accepts is >= 0 on (a, b) (sampled exactly), and it accepts every row whose
    product with D the single-polynomial test (Descartes, or the Taylor shift for b = oo) proves > 0."""
    b = None if width is None or width == 0 else a + width
    flags = lp_pieces._batch_positive(Y, D, a, b)
    for y, ok in zip(Y, flags):
        p = poly_arithmetic.trim(poly_arithmetic.mul_integers(y, D))
        if not p:
            assert ok
            continue
        if ok:
            top = b if b is not None else a + 10
            for k in range(1, 40):
                assert polys.sign_at(p, a + (top - a) * F(k, 40)) >= 0
        assert ok or not lp_pieces._positive_around(poly_arithmetic.integer_coefficients(p), a, b)


def test_negative_beyond_a_rational_and_an_algebraic_horizon():
    two = Real.rational(2)
    assert lp_pieces._negative_beyond([F(2), F(-1)], two)          # 2 - h < 0 beyond 2
    assert not lp_pieces._negative_beyond([F(3), F(-1)], two)      # 3 - h > 0 on (2, 3)
    assert not lp_pieces._negative_beyond([F(1), F(1)], two)       # positive leading coefficient
    sqrt2 = Real.claimed([F(-2), F(0), F(1)], F(1), F(2))
    assert lp_pieces._negative_beyond([F(2), F(0), F(-1)], sqrt2)  # 2 - h^2 < 0 beyond sqrt 2
    assert not lp_pieces._negative_beyond([F(3), F(0), F(-1)], sqrt2)


def test_a_sliver_of_the_end_polynomial_times_a_power_of_h():
    """p = h q with q the end's own polynomial: recognised without a gcd, but only when the enclosure
    lies in h >= 0 (else h could vanish inside it)."""
    r = Real.claimed([F(-2), F(0), F(1)], F(1), F(2))   # sqrt 2, enclosure (1, 2)
    p = [0, 2, 0, -1]                                     # h (2 - h^2): > 0 on (1, sqrt 2)
    assert lp_pieces._sliver(p, p, r, r.lo)
    q = [0, -2, 0, 1]                                     # h (h^2 - 2): < 0 there
    assert not lp_pieces._sliver(q, q, r, r.lo)


# ------------------------------------------------------------------ ray pieces (unbounded P)


def _ray_certificate(method=None, claim="valid"):
    """The orthant of R^2 with M = [[-4, -1], [10, 0]] (tests/validset/test_lp_route.py works it by hand):
    Taylor(2) gives facet 0 two ray pieces (0, 1/2) with e2, (1/2, 1) with e1, then a basis; Taylor(3) a ray
    piece (0, 1), a point piece [1, 1] and a ray piece (1, oo)."""
    S = ei.LinearSystem([[-4, -1], [10, 0]])
    P = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
    result = (ei.valid_steplengths if claim == "valid" else ei.largest_threshold)(S, P, method or M.taylor(2), route="lp")
    cert = result.certificate
    assert exactinv_check.check(cert).ok
    return cert


def _half_strip_certificate():
    """P = {x1 >= 0, |x2| <= 1}, x' = -x, forward Euler: facet 0 is a basis on [0, 1], a ray piece (1, oo)."""
    S = ei.LinearSystem([[-1, 0], [0, -1]])
    P = ei.Polyhedron([[-1, 0], [0, 1], [0, -1]], [0, 1, 1])
    cert = ei.valid_steplengths(S, P, M.forward_euler(), route="lp").certificate
    assert exactinv_check.check(cert).ok
    f = _lp(cert)[0]
    assert f["ends"] == ["1", "oo"] and f["bases"][1] == {"ray": ["1", "0"]}
    return cert


def test_a_ray_outside_the_recession_cone_is_rejected():
    cert = _half_strip_certificate()
    _lp(cert)[0]["bases"][1] = {"ray": ["1", "1"]}  # G d = (-1, 1, -1): leaves x2 <= 1
    _rejected(cert, "not a ray of P")
    cert = _half_strip_certificate()
    _lp(cert)[0]["bases"][1] = {"ray": ["0", "0"]}
    _rejected(cert, "zero vector")


def test_a_ray_not_positive_on_its_whole_piece_is_rejected():
    """(g_0 N(h) d) D = h - 1 for d = (1, 0): the ray piece moved to start at 1/2 covers (1/2, 1), where the
    LP is bounded; a ray piece from 0 likewise.  Both rejected (the basis piece before it is cut short)."""
    cert = _half_strip_certificate()
    _lp(cert)[0]["ends"][0] = "1/2"
    _rejected(cert, "inside its piece")
    cert = _half_strip_certificate()
    f = _lp(cert)[0]
    f["ends"], f["bases"] = ["oo"], [{"ray": ["1", "0"]}]
    _rejected(cert, "inside its piece")


def test_a_ray_piece_claiming_validity_is_rejected():
    """The valid set claimed past the ray piece's start: the ray condition -(h - 1) >= 0 is recomputed and
    the claim [0, 2] differs from [0, 1]; and a basis piece in place of the ray piece (the LP called bounded
    where it is not): z_B dips negative."""
    cert = _half_strip_certificate()
    cert["claims"][0]["intervals"][0]["hi"] = "2"
    assert not exactinv_check.check(cert).ok
    for basis in ([0, 2], [0, 1]):  # another vertex, or the vertex kept past its breakpoint
        cert = _half_strip_certificate()
        _lp(cert)[0]["bases"][1] = basis
        del cert["claims"][0]["lp"]["point"]  # no ray piece is left
        _rejected(cert, "negative inside its piece")


def test_a_piece_skipping_a_breakpoint_is_rejected_with_rays():
    """Taylor(2): the ray e2 kept past 1/2 (to 1), e1's piece dropped; or e1's piece run to oo."""
    cert = _ray_certificate()
    f = _lp(cert)[0]
    assert f["bases"][:2] == [{"ray": ["0", "1"]}, {"ray": ["1", "0"]}] and f["ends"][:2] == ["1/2", "1"]
    del f["ends"][0], f["bases"][1]
    _rejected(cert, "inside its piece")
    cert = _ray_certificate()
    f = _lp(cert)[0]
    f["ends"][1:], f["bases"][2:] = ["oo"], []
    _rejected(cert, "inside its piece")


def test_ray_pieces_meeting_where_neither_decides_are_rejected():
    """Taylor(3): the point piece [1, 1] deleted -- the two ray pieces of e2 meet at 1, where its
    (g N d) D touches 0 and h = 1 is valid: rejected.  The pieces cut after the first ray piece: its end 1
    is left undecided.  Two ray pieces meeting at an irrational end: rejected (a rational end is required)."""
    cert = _ray_certificate(M.taylor(3))
    f = _lp(cert)[0]
    assert f["ends"] == ["1", "1", "oo"] and isinstance(f["bases"][1], list)
    del f["ends"][1], f["bases"][1]
    _rejected(cert, "covered by neither")
    cert = _ray_certificate(M.taylor(3))
    f = _lp(cert)[0]
    del f["ends"][1:], f["bases"][1:]
    _rejected(cert, "nothing covers")
    cert = _ray_certificate()
    f = _lp(cert)[0]
    f["ends"][0] = {"poly": ["-1", "0", "5"], "interval": ["2/5", "1/2"]}  # 1/sqrt 5, in (1/3, 1/2)
    _rejected(cert, "covered by neither")


def test_a_point_piece_with_a_negative_dual_is_rejected():
    """Taylor(3)'s point piece [1, 1] with another basis, or moved to 1/2 (inside the ray piece)."""
    cert = _ray_certificate(M.taylor(3))
    f = _lp(cert)[0]
    f["ends"][0:2] = ["1/2", "1/2"]
    assert not exactinv_check.check(cert).ok
    cert = _ray_certificate(M.taylor(3))
    f = _lp(cert)[0]
    f["ends"].insert(0, "1/2")
    f["bases"].insert(0, f["bases"][1])  # a point piece [1/2, 1/2] with the basis of h = 1
    f["ends"][1] = "1/2"
    assert not exactinv_check.check(cert).ok


def test_the_point_of_p_is_required_with_ray_pieces_and_checked():
    cert = _half_strip_certificate()
    lp = cert["claims"][0]["lp"]
    lp["point"] = ["-1", "0"]
    _rejected(cert, "lp point violates row 0")
    del lp["point"]
    _rejected(cert, "a point of P is given exactly when")
    cert = _certificate()
    cert["claims"][0]["lp"]["point"] = ["0", "0", "0"]
    _rejected(cert, "a point of P is given exactly when")
    cert = _half_strip_certificate()
    _lp(cert)[0]["bases"][1] = {"ray": ["1", "0"], "basis": [0, 1]}
    _rejected(cert, "a ray piece is")


def test_a_binding_ray_condition_is_checked():
    """The largest threshold of the half-strip under forward Euler is 1, bound by the ray piece's ray
    condition (kind "ray", the piece's flat index); naming the basis piece's index as a ray is rejected."""
    S = ei.LinearSystem([[-1, 0], [0, -1]])
    P = ei.Polyhedron([[-1, 0], [0, 1], [0, -1]], [0, 1, 1])
    cert = ei.largest_threshold(S, P, M.forward_euler(), route="lp").certificate
    claim = cert["claims"][0]
    assert exactinv_check.check(cert).ok and claim["value"] == "1"
    assert claim["binding"]["kind"] == "ray" and claim["binding"]["generator"] == 1
    claim["binding"]["generator"] = 0
    assert not exactinv_check.check(cert).ok
