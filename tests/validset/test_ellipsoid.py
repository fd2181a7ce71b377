"""Valid steplengths, largest thresholds and forward Euler on ellipsoids:
closed forms worked by hand, a theorem (backward Euler and every A-stable
method: all h on an invariant ellipsoid), a cross-check with the polyhedral
engine in dimension 1, and the property that defines the valid set."""

from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.core.psd import psd_decision, quadratic_form

DISC = ei.Ellipsoid([[1, 0], [0, 1]])
rationals = st.builds(Fraction, st.integers(-6, 6), st.integers(1, 4))
positive = st.builds(Fraction, st.integers(1, 6), st.integers(1, 4))


def _rotation(a, b):
    return ei.LinearSystem([[-a, -b], [b, -a]])


def _sign_changes_at(p, tau):
    """tau is a root of p (low to high) -- p changes sign across its enclosure, or vanishes
    at a rational tau -- p >= 0 at samples of [0, tau] and p < 0 just after tau."""
    ev = lambda x: sum(c * x**k for k, c in enumerate(p))  # noqa: E731
    lo, hi = (tau, tau) if isinstance(tau, Fraction) else (tau.lower, tau.upper)
    root = ev(tau) == 0 if isinstance(tau, Fraction) else ev(lo) * ev(hi) < 0
    return root and ev(hi + Fraction(1, 10**6)) < 0 and all(ev(lo * k / 16) >= 0 for k in range(17))


# ------------------------------------------------------------- closed forms
@given(positive, rationals)
def test_forward_euler_on_the_unit_disc_is_2a_over_a2_plus_b2(a, b):
    """A = [[-a, -b], [b, -a]] = -aI + bJ: (I + hA)^T (I + hA) = ((1 - ha)^2 + h^2 b^2) I,
    <= I iff h (a^2 + b^2) <= 2a."""
    tau = 2 * a / (a * a + b * b)
    fe = ei.forward_euler_threshold(_rotation(a, b), DISC)
    assert fe.value == fe.by_eigenvalue == fe.by_valid_set == tau
    V = ei.valid_steplengths(_rotation(a, b), DISC, ei.methods.forward_euler())
    assert [(iv.lo, iv.hi, iv.hi_closed) for iv in V] == [(0, tau, True)]
    assert ei.check(fe.certificate).ok


@given(positive, rationals)
@settings(max_examples=10)
def test_taylor2_on_the_unit_disc_by_hand(a, b):
    """r(z) = 1 + z + z^2/2, z = h(-a + ib), rho^2 = a^2 + b^2:
    |r|^2 = 1 + 2 Re z + |z|^2 + Re z^2 + |z|^2 Re z + |z|^4/4, so
    1 - |r|^2 = h (2a - 2a^2 h + a rho^2 h^2 - rho^4 h^3 / 4); M(h) = (1 - |r|^2) I."""
    rho2 = a * a + b * b
    hand = [2 * a, -2 * a * a, a * rho2, -rho2 * rho2 / 4]
    t = ei.largest_threshold(_rotation(a, b), DISC, ei.methods.taylor(2))
    assert t.attained and _sign_changes_at(hand, t.value)
    assert ei.first_sign_change(hand) == t.value  # the first sign change of the hand-made cubic
    assert ei.check(t.certificate).ok


def test_taylor2_for_a_equal_1_b_equal_0_is_2():
    # 2 - 2h + h^2 - h^3/4 = -(h - 2)(h^2 - 2h + 4)/4: the only real root is 2
    assert ei.largest_threshold(_rotation(1, 0), DISC, ei.methods.taylor(2)).value == 2


@pytest.mark.parametrize("A, tau", [([[0, 0], [0, -1]], 2),      # K singular, ker K in ker B: W = e_2
                                    ([[0, 1], [-1, 0]], 0),      # K = 0, B = I: no positive step
                                    ([[0, 0], [0, 0]], ei.INF)])  # A = 0: A_d = I
def test_forward_euler_when_K_is_singular(A, tau):
    fe = ei.forward_euler_threshold(ei.LinearSystem(A), DISC)
    assert fe.value == tau and fe.by_eigenvalue == fe.by_valid_set


# ------------------------------------------------------------- a theorem
@st.composite
def invariant_ellipsoids(draw):
    """Every (A, Q) with A^T Q + Q A <= 0: A = (J - R) Q, J skew, R = C^T C >= 0
    (then A^T Q + Q A = -2 Q R Q)."""
    n = draw(st.integers(1, 3))
    B = [[draw(rationals) for _ in range(n)] for _ in range(n)]
    Q = [[sum(B[k][i] * B[k][j] for k in range(n)) + (i == j) for j in range(n)] for i in range(n)]
    upper = [[draw(rationals) for _ in range(n)] for _ in range(n)]
    J = [[upper[i][j] if i < j else -upper[j][i] if i > j else 0 for j in range(n)] for i in range(n)]
    C = [[draw(rationals) for _ in range(n)] for _ in range(draw(st.integers(0, n)))]
    R = [[sum(c[i] * c[j] for c in C) for j in range(n)] for i in range(n)]
    A = [[sum((J[i][k] - R[i][k]) * Q[k][j] for k in range(n)) for j in range(n)] for i in range(n)]
    return ei.LinearSystem(A), ei.Ellipsoid(Q)


A_STABLE = [ei.methods.backward_euler(), ei.methods.trapezoid(), ei.methods.theta("3/4"), ei.methods.pade(1, 2),
            ei.methods.pade(2, 2)]


@given(invariant_ellipsoids(), st.sampled_from(A_STABLE))
@settings(max_examples=15)
def test_a_stable_methods_keep_every_invariant_ellipsoid_for_every_h(case, method):
    """Backward Euler: with x = (I - hA) y, ||x||_Q^2 = ||y||^2 - h y^T (A^T Q + Q A) y + h^2 ||Ay||^2
    >= ||y||^2 = ||A_d x||^2, and I - hA is invertible (Re lambda(A) <= 0).  Every A-stable r:
    von Neumann's inequality in the Q-inner product (A is Q-dissipative), ||r(hA)||_Q <= 1.
    So the valid set is [0, oo): proved, not refuted."""
    S, E = case
    assert ei.continuous_invariance(S, E).holds
    V = ei.valid_steplengths(S, E, method)
    assert [(iv.lo, iv.hi, iv.lo_closed) for iv in V] == [(0, ei.INF, True)]
    assert ei.largest_threshold(S, E, method).value == ei.INF


def test_a_method_that_is_not_a_stable_has_a_finite_threshold_there():
    assert ei.largest_threshold(_rotation(1, 2), DISC, ei.methods.theta("1/4")).value == Fraction(4, 5)


# ------------------------------------------------------------- dimension 1: the polyhedral engine agrees
one_d_methods = st.sampled_from([ei.methods.taylor(p) for p in (1, 2, 3, 4)] + [
    ei.methods.polynomial([1, "1/2", "3/4", "1/4"]), ei.methods.theta("1/4"), ei.methods.pade(0, 2),
    ei.methods.pade(2, 1)])


@given(st.builds(Fraction, st.integers(-4, 4), st.integers(1, 3)), positive, one_d_methods)
@settings(max_examples=15)
def test_in_dimension_one_the_ellipsoid_is_an_interval(a, q, method):
    """E = {q x^2 <= 1} is the interval [-1/sqrt(q), 1/sqrt(q)]; for q = 1 it is the box [-1, 1]."""
    S = ei.LinearSystem([[a]])
    V = ei.valid_steplengths(S, ei.Ellipsoid([[q]]), method)
    P = ei.valid_steplengths(S, ei.Polyhedron.box([-1], [1]), method)
    assert [(iv.lo, iv.hi, iv.lo_closed, iv.hi_closed) for iv in V] == \
           [(iv.lo, iv.hi, iv.lo_closed, iv.hi_closed) for iv in P]


def test_a_valid_set_with_a_gap():
    S, E = ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]])
    V = ei.valid_steplengths(S, E, ei.methods.polynomial([1, "1/2", "3/4", "1/4"]))
    assert len(V) == 2 and V.intervals[0].hi == 1 and V.intervals[1].lo == 2
    assert "3/2" not in V and "1/2" in V and "5/2" in V
    assert ei.check(V.certificate).ok


# ------------------------------------------------------------- the defining property
def _Ad(A, method, h):
    return method.matrix(A, h)


def _M(E, Ad):
    n = E.n
    QA = [[sum(E.Q[i][k] * Ad[k][j] for k in range(n)) for j in range(n)] for i in range(n)]
    AQA = [[sum(Ad[k][i] * QA[k][j] for k in range(n)) for j in range(n)] for i in range(n)]
    return [[E.Q[i][j] - AQA[i][j] for j in range(n)] for i in range(n)]


def _upper(x):
    return x if isinstance(x, Fraction) else x.upper


def _lower(x):
    return x if isinstance(x, Fraction) else x.lower


def _inside(lo, hi, t):
    """A rational strictly between lo and hi (hi may be INF), at relative position t in (0, 1)."""
    a = _upper(lo)
    b = a + 3 if hi == ei.INF else _lower(hi)
    return a + (b - a) * t if a < b else None


@st.composite
def problems(draw):
    n = draw(st.integers(1, 3))
    A = [[draw(rationals) for _ in range(n)] for _ in range(n)]
    B = [[draw(rationals) for _ in range(n)] for _ in range(n)]
    Q = [[sum(B[k][i] * B[k][j] for k in range(n)) + (i == j) for j in range(n)] for i in range(n)]
    method = draw(st.sampled_from([ei.methods.taylor(p) for p in (1, 2, 3)] + [
        ei.methods.theta("1/4"), ei.methods.backward_euler(), ei.methods.pade(1, 1), ei.methods.pade(2, 1),
        ei.methods.polynomial([1, "1/2", "3/4", "1/4"])]))
    return ei.LinearSystem(A), ei.Ellipsoid(Q), method


@given(problems(), st.fractions(Fraction(1, 8), Fraction(7, 8)))
@settings(max_examples=20)
def test_inside_every_interval_psd_and_inside_every_gap_a_witness(case, t):
    S, E, method = case
    V = ei.valid_steplengths(S, E, method)
    ends = [Fraction(0)]
    for iv in V:
        h = _inside(iv.lo, iv.hi, t)
        if h is not None:
            d = psd_decision(_M(E, _Ad(S, method, h)))
            assert d.psd, (h, V)
            L, D, p = d.proof.L, d.proof.D, d.proof.perm  # the LDL^T checked here, entry by entry
            M = _M(E, _Ad(S, method, h))
            assert min(D) >= 0 and all(sum(L[i][k] * D[k] * L[j][k] for k in range(E.n)) == M[p[i]][p[j]]
                                       for i in range(E.n) for j in range(E.n))
        ends.append(iv.hi)
    gaps = list(zip([iv.hi for iv in V][:-1], [iv.lo for iv in V][1:]))
    if V.intervals[-1].hi != ei.INF:
        gaps.append((V.intervals[-1].hi, ei.INF))
    for lo, hi in gaps:
        h = _inside(lo, hi, t)
        if h is None or any(h == s for s in V.singular):
            continue
        v = psd_decision(_M(E, _Ad(S, method, h))).witness
        assert v is not None and quadratic_form(_M(E, _Ad(S, method, h)), v) < 0, (h, V)
    assert ei.check(V.certificate).ok
    assert ei.check(ei.largest_threshold(S, E, method).certificate).ok


def test_bad_input_is_named():
    with pytest.raises(ei.ExactinvError, match="method"):
        ei.valid_steplengths(_rotation(1, 1), DISC, "taylor")
    with pytest.raises(ei.ExactinvError, match="system/ellipsoid"):
        ei.largest_threshold(ei.LinearSystem([[1]]), DISC, ei.methods.taylor(1))


def test_result_fields_land_where_they_belong():
    """Regression (a merge added ``pruning`` to the polyhedral result types, which shifted positional
    arguments): on the unit disc with A = -I and Taylor-2, q_1 = 2 c(h), q_2 = c(h)^2 with
    c = (1 - h/2)(2 - h + h^2/2); q_1 changes sign at h = 2 and binds, q_2 only touches 0."""
    from exactinv import Ellipsoid, LinearSystem, methods
    from exactinv import largest_threshold as ellipsoid_largest_threshold
    from exactinv import valid_steplengths as ellipsoid_valid_steplengths
    S, E = LinearSystem([[-1, 0], [0, -1]]), Ellipsoid([[1, 0], [0, 1]])
    L = ellipsoid_largest_threshold(S, E, methods.taylor(2))
    assert (L.value, L.coefficient, L.pruning) == (2, 1, None)
    V = ellipsoid_valid_steplengths(S, E, methods.taylor(2))
    assert V.pruning is None and len(V.polynomials) == 2
    assert V.polynomials[0] == (4, -4, 2, Fraction(-1, 2))
