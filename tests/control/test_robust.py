"""robust_threshold (issue 25, part 2): one step for every A in conv{A_1, ..., A_k}.

Theorems as property tests: at a random rational point of the hull and a random
rational h <= tau, A_d(h) = r(hA) maps P into P, decided exactly by the engine's
discrete invariance LPs; switching sequences stay in P (exact iteration from
the vertices of P); the robust forward-Euler step is min_i of the vertices'
exact steps; tau lies in the exact upper bound, the intersection of the
vertices' valid sets; the kernel verifies the certificates and rejects forgeries.
"""

import copy
from fractions import Fraction

import flint
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

import exactinv as ei
from exactinv.core.real_algebraic import RealAlgebraic

POLY_METHODS = [ei.methods.taylor(1), ei.methods.taylor(2), ei.methods.taylor(4), ei.methods.rk4()]
RATIONAL_METHODS = [ei.methods.backward_euler(), ei.methods.trapezoid(), ei.methods.pade(1, 2), ei.methods.theta("3/4")]


def _matrix(M):
    return flint.fmpq_mat([[flint.fmpq(Fraction(v).numerator, Fraction(v).denominator) for v in r] for r in M])


@st.composite
def hulls(draw):
    """k vertices A_i = T^-1 M_i T with M_i diagonally dominant (M_ii + sum_j |M_ij| <= 0), each
    keeping P = {x : |Tx| <= 1} invariant (the box in y = Tx); T random invertible."""
    n = draw(st.integers(1, 3))
    k = draw(st.integers(2, 3))
    T = [[draw(st.integers(-2, 2)) for _ in range(n)] for _ in range(n)]
    Tq = _matrix(T)
    assume(Tq.det() != 0)
    Ti = Tq.inv()
    systems = []
    for _ in range(k):
        M = [[Fraction(draw(st.integers(-3, 3)), draw(st.integers(1, 2))) if i != j else 0 for j in range(n)]
             for i in range(n)]
        for i in range(n):
            M[i][i] = -sum(abs(v) for v in M[i]) - Fraction(draw(st.integers(0, 4)), 2)
        A = Ti * _matrix(M) * Tq
        systems.append(ei.LinearSystem([[A[i, j] for j in range(n)] for i in range(n)]))
    G = [list(r) for r in T] + [[-v for v in r] for r in T]
    return systems, ei.Polyhedron(G, [1] * (2 * n))


def _point_of_simplex(data, k):
    w = [data.draw(st.integers(0, 6)) for _ in range(k)]
    assume(sum(w) > 0)
    return [Fraction(x, sum(w)) for x in w]


def _combination(systems, lam):
    n = systems[0].n
    return ei.LinearSystem([[sum(l * S.A[i][j] for l, S in zip(lam, systems)) for j in range(n)] for i in range(n)])


def _step_below(tau, attained, data):
    """A random rational h in [0, tau] ([0, tau) when not attained)."""
    if tau == ei.INF:
        return Fraction(data.draw(st.integers(0, 40)), 4)
    top = tau.lower if isinstance(tau, RealAlgebraic) else tau
    u = Fraction(data.draw(st.integers(0, 16)), 16)
    h = top * u
    if not attained and h == tau:
        h = top * Fraction(15, 16)
    return h


@given(hulls(), st.sampled_from(POLY_METHODS + RATIONAL_METHODS), st.data())
def test_every_matrix_of_the_hull_keeps_P_for_every_step_up_to_tau(hull, method, data):
    systems, P = hull
    r = ei.robust_threshold(systems, P, method)
    assert ei.check(r.certificate).ok
    for _ in range(2):
        lam = _point_of_simplex(data, len(systems))
        h = _step_below(r.value, r.attained, data)
        S = _combination(systems, lam)
        assert ei.discrete_invariance(S, P, method, h).holds, (lam, h)


@given(hulls(), st.sampled_from(POLY_METHODS + RATIONAL_METHODS), st.data())
def test_switching_sequences_stay_in_P(hull, method, data):
    systems, P = hull
    r = ei.robust_threshold(systems, P, method)
    h = _step_below(r.value, r.attained, data)
    x = list(P.vertices[data.draw(st.integers(0, len(P.vertices) - 1))])
    for _ in range(4):
        S = _combination(systems, _point_of_simplex(data, len(systems)))
        Ad = method.matrix(S, h)
        x = [sum(a * xi for a, xi in zip(row, x)) for row in Ad]
        assert x in P


@given(hulls(), st.sampled_from(POLY_METHODS + RATIONAL_METHODS[:2]))
def test_forward_euler_and_the_exact_upper_bound(hull, method):
    systems, P = hull
    r = ei.robust_threshold(systems, P, method)
    vertex_steps = [ei.forward_euler_threshold(S, P).value for S in systems]
    assert r.forward_euler_step == min(vertex_steps)  # convexity in A: the exact largest robust step
    if method.name == "taylor(1)":
        assert r.value == r.forward_euler_step
    # tau is no larger than what the vertices allow: [0, tau] lies in the first interval of the upper bound
    first = r.upper_bound[0]
    assert first.lo == 0 and first.lo_closed
    assert not first.hi < r.value
    for V in r.vertex_valid_sets():
        assert ei.check(V.certificate).ok


def test_by_hand():
    """x' = -x and x' = -2x on [-1, 1]: gamma_i = 1/2, 1; Taylor(2) has rho = 1, so tau = 1;
    the vertex x' = -2x has the valid set {h : |1 - 2h + 2h^2| <= 1} = [0, 1], so tau is tight."""
    P = ei.Polyhedron.box([-1], [1])
    r = ei.robust_threshold([ei.LinearSystem([[-1]]), ei.LinearSystem([[-2]])], P, ei.methods.taylor(2))
    assert (r.value, r.attained, r.gamma, r.gammas) == (1, True, 1, (Fraction(1, 2), 1))
    assert r.forward_euler_step == 1
    assert str(r.upper_bound) == "[0, 1]"
    # backward Euler: rho = oo and b > 0 gives beta <= 0: tau = oo
    be = ei.robust_threshold([ei.LinearSystem([[-1]]), ei.LinearSystem([[-2]])], P, ei.methods.backward_euler())
    assert be.value == ei.INF and be.beta is not None and be.beta <= 0


def test_the_rational_bound_is_hull_wide_not_the_vertices_alpha():
    """On a P with b not > 0 the abscissa bound beta (row sums of the H_i) is what caps tau, and it
    bounds alpha(sum lambda_i H_i) for every lambda, which no max of the vertices' alpha(H_i) does in
    general.  The certificate records v = 1 and beta; the kernel recomputes beta."""
    P = ei.Polyhedron([[-1, 0], [0, -1], [1, 1]], [0, 0, 1])  # a triangle with a vertex at 0: b not > 0
    systems = [ei.LinearSystem([[-1, 1], [0, -2]]), ei.LinearSystem([[-2, 0], [1, -1]])]
    r = ei.robust_threshold(systems, P, ei.methods.trapezoid())
    assert r.v == (1, 1, 1)
    cert = r.certificate
    assert ei.check(cert).ok
    claim = cert["claims"][-1]
    assert claim["beta"] == str(r.beta)
    forged = copy.deepcopy(cert)
    forged["claims"][-1]["beta"] = str(r.beta - 1)
    assert not ei.check(forged).ok


def test_refusals():
    P = ei.Polyhedron.box([-1], [1])
    with pytest.raises(ei.NotInvariant, match="systems\\[1\\]"):
        ei.robust_threshold([ei.LinearSystem([[-1]]), ei.LinearSystem([[1]])], P, ei.methods.taylor(2))
    strip = ei.Polyhedron([[1, 0], [-1, 0]], [1, 1])  # a P with lines: E2' is not proved hull-wide
    systems = [ei.LinearSystem([[-1, 0], [0, 3]]), ei.LinearSystem([[-2, 0], [0, 1]])]
    with pytest.raises(ei.Undecided, match="lines"):
        ei.robust_threshold(systems, strip, ei.methods.backward_euler())
    assert ei.robust_threshold(systems, strip, ei.methods.taylor(2)).value == 1  # gamma = max(1/2, 1), rho = 1
    with pytest.raises(ei.ExactinvError, match="systems"):
        ei.robust_threshold([], P, ei.methods.taylor(2))
    with pytest.raises(ei.ExactinvError, match="systems\\[0\\]"):
        ei.robust_threshold([ei.LinearSystem([[-1, 0], [0, -1]])], P, ei.methods.taylor(2))


def test_forged_robust_certificates_are_rejected():
    systems = [ei.LinearSystem([[-1, 1], [-1, -1]]), ei.LinearSystem([[-2, 1], [0, -1]])]
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    cert = ei.robust_threshold(systems, P, ei.methods.taylor(3)).certificate
    assert ei.check(cert).ok

    def forged(edit):
        c = copy.deepcopy(cert)
        edit(c)
        return not ei.check(c).ok

    bump = lambda s: str(Fraction(s) + Fraction(1, 3))  # noqa: E731
    claim = -1
    assert forged(lambda c: c["claims"][claim].update(gamma=bump(c["claims"][claim]["gamma"])))
    assert forged(lambda c: c["claims"][claim].update(forward_euler="2"))
    assert forged(lambda c: c["claims"][claim].update(value=bump(c["claims"][claim]["value"])))
    assert forged(lambda c: c["claims"][claim]["vertices"].pop())
    assert forged(lambda c: c["claims"][claim]["vertices"][0]["H"]["sparse"][0][-1].__setitem__(1, "5"))
    assert forged(lambda c: c["claims"][claim]["vertices"][1].update(value="1/3"))  # the smaller gamma, unproved
    assert forged(lambda c: c["problem"]["hull"][1][0].__setitem__(0, "-1/2"))     # another hull
    assert forged(lambda c: c["problem"]["hull"].append([["1", "0"], ["0", "1"]]))
    assert forged(lambda c: c["claims"].pop(0))                                     # no verified radius
    assert forged(lambda c: c["claims"][claim].update(rho="2"))


def test_gamma_unbounded_below():
    """P = {0} (both coordinates pinned by pairs of inequalities with b = 0): every row LP of
    gamma* is unbounded, so gamma*(A) = -oo for every A, and P is invariant under every linear map.
    Then the forward-Euler step and a polynomial method with sigma_k >= 0 (Taylor 3) give tau = oo
    exactly, and each vertex's H is written with H >= 0 entrywise (H + max(gamma, 0) I >= 0, the
    kernel's condition for a rational method).  Backward Euler is capped only by the pole z_p = 1
    over beta, a hull-wide bound of the spectral abscissa: every A of the hull with h < tau has
    I - hA nonsingular."""
    P = ei.Polyhedron([[1, 0], [-1, 0], [0, 1], [0, -1]], [0, 0, 0, 0])
    systems = [ei.LinearSystem([[1, 2], [3, -4]]), ei.LinearSystem([[0, 1], [-1, 0]])]
    taylor = ei.robust_threshold(systems, P, ei.methods.taylor(3))
    assert taylor.gammas == (-ei.INF, -ei.INF) and taylor.gamma == -ei.INF
    assert (taylor.value, taylor.attained, taylor.forward_euler_step) == (ei.INF, True, ei.INF)
    assert ei.check(taylor.certificate).ok
    be = ei.robust_threshold(systems, P, ei.methods.backward_euler())
    cert = be.certificate
    assert ei.check(cert).ok
    for vertex in cert["claims"][-1]["vertices"]:
        assert all(Fraction(x) >= 0 for row in vertex["H"]["sparse"] for _, x in row)  # v3: rows of nonzeros
    assert be.beta > 0 and be.value == Fraction(1) / be.beta and not be.attained
    for lam in ([1, 0], [0, 1], [Fraction(1, 2)] * 2, [Fraction(1, 3), Fraction(2, 3)]):
        A = _combination(systems, lam).A
        for h in (be.value * Fraction(k, 8) for k in range(8)):
            assert _matrix([[int(i == j) - h * A[i][j] for j in range(2)] for i in range(2)]).det() != 0
    forged = copy.deepcopy(cert)
    row = forged["claims"][-1]["vertices"][0]["H"]["sparse"][0]
    row[:] = [[0, "-1"]] + [entry for entry in row if entry[0] != 0]  # h_00 = -1
    assert not ei.check(forged).ok
