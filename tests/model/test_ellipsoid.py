"""exactinv.model.ellipsoid: construction (exact Q > 0), membership, from_lyapunov."""

from fractions import Fraction

import pytest

import exactinv as ei
from exactinv.model.ellipsoid import lyapunov_matrix


def _leading_minors_positive(M):
    """Sylvester's criterion, by exact Fraction elimination written out here."""
    n = len(M)
    for k in range(1, n + 1):
        S = [list(map(Fraction, r[:k])) for r in M[:k]]
        det = Fraction(1)
        for c in range(k):
            p = next((r for r in range(c, k) if S[r][c] != 0), None)
            if p is None:
                return False
            S[c], S[p] = S[p], S[c]
            det *= S[c][c] * (-1 if p != c else 1)
            for r in range(c + 1, k):
                f = S[r][c] / S[c][c]
                S[r] = [a - f * b for a, b in zip(S[r], S[c])]
        if det <= 0:
            return False
    return True


def test_an_ellipsoid_is_exact_and_knows_its_points():
    E = ei.Ellipsoid([["2", 0], [0, "1/2"]])
    assert E.Q == ((2, 0), (0, Fraction(1, 2))) and E.n == 2
    assert [0, 1] in E and [Fraction(1, 2), 1] in E and [1, 0] not in E
    assert E == ei.Ellipsoid([[2, 0], [0, Fraction(1, 2)]])
    assert "Ellipsoid(Q=" in repr(E) and r"x^T" in E.to_latex()


@pytest.mark.parametrize("Q, match", [
    ([[1, 2], [2, 1]], "Q: must be positive definite"),         # indefinite: the witness is in the message
    ([[1, 0], [0, 0]], "Q: must be positive definite.*singular"),
    ([[1, 1], [0, 1]], "Q: not symmetric"),
    ([[1, 0], [0, 0.5]], r"Q\[1\]\[1\]: got the float"),
    ([[1, 0, 0], [0, 1, 0]], "Q: must be square"),
])
def test_bad_Q_is_named(Q, match):
    with pytest.raises(ei.ExactinvError, match=match):
        ei.Ellipsoid(Q)


def test_floats_need_the_explicit_opt_in_and_then_are_exact():
    E = ei.Ellipsoid([[1, 0], [0, 0.5]], allow_float=True)
    assert E.Q[1][1] == Fraction(1, 2)


def test_only_the_centre_zero():
    assert ei.Ellipsoid([[1]], center=[0]).Q == ((1,),)
    with pytest.raises(ei.ExactinvError, match="center"):
        ei.Ellipsoid([[1]], center=[1])


@pytest.mark.parametrize("A", [[[-1, 2], [0, -1]], [[0, 1], [-2, -3]], [[-1, 10, 0], [0, -1, 10], [0, 0, -1]]])
def test_from_lyapunov_is_proved_exactly(A):
    pytest.importorskip("cvxpy")
    E = ei.Ellipsoid.from_lyapunov(A)
    L = lyapunov_matrix(A, E.Q)
    assert _leading_minors_positive(E.Q)
    assert _leading_minors_positive([[-x for x in r] for r in L])  # A^T Q + Q A < 0, strictly
    assert ei.continuous_invariance(ei.LinearSystem(A), E).holds


def test_from_lyapunov_refuses_an_unstable_matrix():
    pytest.importorskip("cvxpy")
    with pytest.raises(ei.ExactinvError, match="A: the Lyapunov SDP"):
        ei.Ellipsoid.from_lyapunov([[1, 0], [0, -1]])
