from fractions import Fraction

import flint
import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

import exactinv as ei
from exactinv.certificates import certificate
from exactinv.core.flintq import fmpq_matrix
from exactinv_check import check


def _dominant(draw, n):
    A = [[Fraction(draw(st.integers(-5, 5)), draw(st.integers(1, 3))) for _ in range(n)] for _ in range(n)]
    for i in range(n):
        off = sum(abs(A[i][j]) for j in range(n) if j != i)
        A[i][i] = -off - Fraction(draw(st.integers(0, 6)), draw(st.integers(1, 4)))
    return A


@st.composite
def dominant_systems(draw, max_n=4):
    n = draw(st.integers(1, max_n))
    return _dominant(draw, n)


def _box(n):
    return ei.Polyhedron.box([-1] * n, [1] * n)


@given(dominant_systems())
def test_box_gamma_closed_form(A):
    """[-1,1]^n, row-diagonally-dominant A with a_ii <= 0:  gamma* = max_i (sum_{j!=i}|a_ij| - a_ii)/2."""
    n = len(A)
    expected = max((sum(abs(A[i][j]) for j in range(n) if j != i) - A[i][i]) / 2 for i in range(n))
    g = ei.optimal_gamma(ei.LinearSystem(A), _box(n))
    assert g.value == expected
    assert check(g.certificate).ok


@given(dominant_systems(max_n=3), st.data())
def test_positive_gamma_ignores_redundant_rows(A, data):
    n = len(A)
    P = _box(n)
    g = ei.optimal_gamma(ei.LinearSystem(A), P)
    assume(g.value > 0)
    # redundant rows: nonnegative combinations of existing rows, loosened
    extra_G, extra_b = [], []
    for _ in range(data.draw(st.integers(1, 3))):
        w = [data.draw(st.integers(0, 2)) for _ in range(P.m)]
        assume(any(w))
        row = [sum(w[k] * P.G[k][i] for k in range(P.m)) for i in range(n)]
        assume(any(row))
        extra_G.append(row)
        extra_b.append(sum(w[k] * P.b[k] for k in range(P.m)) + data.draw(st.integers(0, 3)))
    Q = ei.Polyhedron(list(P.G) + extra_G, list(P.b) + extra_b)
    assert ei.optimal_gamma(ei.LinearSystem(A), Q).value == g.value


def test_nonpositive_gamma_depends_on_representation():
    """docs/design.md: P = {x >= 1}, x' = x has gamma* = -1, but -1/6 once x >= -5 is added."""
    S = ei.LinearSystem([[1]])
    assert ei.optimal_gamma(S, ei.Polyhedron([[-1]], [-1])).value == -1
    assert ei.optimal_gamma(S, ei.Polyhedron([[-1], [-1]], [-1, 5])).value == Fraction(-1, 6)


@given(dominant_systems(max_n=3), st.data())
def test_gamma_invariant_under_change_of_coordinates(A, data):
    n = len(A)
    T = [[data.draw(st.integers(-2, 2)) for _ in range(n)] for _ in range(n)]
    Tq = flint.fmpq_mat(T)
    assume(Tq.det() != 0)
    Aq = Tq.inv() * fmpq_matrix(A) * Tq
    P = _box(n)
    GT = fmpq_matrix(P.G) * Tq
    S2 = ei.LinearSystem([[Aq[i, j] for j in range(n)] for i in range(n)])
    P2 = ei.Polyhedron([[GT[i, j] for j in range(n)] for i in range(P.m)], P.b)
    assert ei.optimal_gamma(S2, P2).value == ei.optimal_gamma(ei.LinearSystem(A), P).value


def test_lower_dimensional_gamma_can_be_minus_infinity():
    segment = ei.Polyhedron([[1, 0], [-1, 0]], [0, 0])  # the line x1 = 0, as a polyhedron
    g = ei.optimal_gamma(ei.LinearSystem([[-1, 0], [0, -2]]), segment)
    assert g.value == -ei.INF and g.forward_euler_step == ei.INF
    assert check(g.certificate).ok


def test_segment_in_the_plane():
    P = ei.Polyhedron([[1, 0], [-1, 0], [0, 1], [0, -1]], [0, 0, 1, 1])
    g = ei.optimal_gamma(ei.LinearSystem([[-1, 0], [0, -1]]), P)
    assert g.value == Fraction(1, 2)  # (1 - dt) x stays in [-1, 1] iff dt <= 2


@given(st.integers(2, 4), st.data())
def test_non_invariant_witness(n, data):
    A = [[data.draw(st.integers(-3, 3)) for _ in range(n)] for _ in range(n)]
    A[0][0] = 1  # x1' = x1 + ... leaves the box through x1 = 1 somewhere
    S, P = ei.LinearSystem(A), _box(n)
    result = ei.continuous_invariance(S, P)
    assume(not result.holds)
    w = result.witness
    x = w.x
    assert P.contains(x)
    g = P.G[w.facet]
    assert sum(gi * xi for gi, xi in zip(g, x)) == P.b[w.facet]
    rate = sum(g[i] * sum(A[i][k] * x[k] for k in range(n)) for i in range(n))
    assert rate > 0 and rate == w.value
    assert ei.optimal_gamma(S, P).value == ei.INF
    assert check(result.certificate_json).ok


def test_continuous_invariance_holds_with_H():
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    P = _box(2)
    result = ei.continuous_invariance(S, P)
    assert result.holds and bool(result)
    H = fmpq_matrix(result.certificate)
    assert H * P.G_flint == P.G_flint * S.A_flint


def test_discrete_invariance():
    P = _box(2)
    rotation = ei.discrete_invariance([[0, 1], [-1, 0]], P)
    assert rotation.holds
    assert check(certificate(ei.LinearSystem([[0, 0], [0, 0]]), P, None, [rotation])).ok
    shear = ei.discrete_invariance([[1, 1], [0, 1]], P)
    assert not shear.holds
    x = shear.witness.x
    assert P.contains(x) and not P.contains([x[0] + x[1], x[1]])


def test_discrete_invariance_with_method_and_step():
    S, P = ei.LinearSystem([[-1]]), _box(1)
    fe = ei.methods.forward_euler()
    assert ei.discrete_invariance(S, P, fe, 2).holds
    assert not ei.discrete_invariance(S, P, fe, "2001/1000").holds
    with pytest.raises(ei.InvalidInput, match="dt"):
        ei.discrete_invariance(S, P, fe, 0.5)
    with pytest.raises(ei.InvalidInput, match="method= and dt="):
        ei.discrete_invariance(S, P)


def test_unbounded_discrete_witness():
    cone = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
    result = ei.discrete_invariance([[1, -1], [0, 1]], cone)
    assert not result.holds and cone.contains(result.witness.x)


@pytest.mark.parametrize("call", [
    lambda: ei.optimal_gamma([[1]], ei.Polyhedron([[1]], [1])),
    lambda: ei.optimal_gamma(ei.LinearSystem([[1]]), [[1]]),
    lambda: ei.optimal_gamma(ei.LinearSystem([[1, 0], [0, 1]]), ei.Polyhedron([[1]], [1])),
    lambda: ei.continuous_invariance(ei.LinearSystem([[1]]), "P"),
    lambda: ei.discrete_invariance([[1, 0], [0, 1]], ei.Polyhedron([[1]], [1])),
    lambda: ei.discrete_invariance([[1, 2]], ei.Polyhedron([[1]], [1])),
])
def test_bad_input(call):
    with pytest.raises(ei.InvalidInput):
        call()
