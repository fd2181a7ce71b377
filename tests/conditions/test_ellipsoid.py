"""exactinv.conditions.ellipsoid: q_k(h) = e_k(M(h)/h), checked against the
sum of the k x k principal minors of M(h) = H^T Q H - G^T Q G computed here."""

from fractions import Fraction
from itertools import combinations

import flint
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.conditions.ellipsoid import psd_polynomials

rationals = st.builds(Fraction, st.integers(-4, 4), st.integers(1, 3))


def _det(M):
    if not M:
        return Fraction(1)
    return sum((-1) ** j * M[0][j] * _det([r[:j] + r[j + 1:] for r in M[1:]]) for j in range(len(M)) if M[0][j])


def _e(M, k):
    return sum(_det([[M[i][j] for j in S] for i in S]) for S in combinations(range(len(M)), k))


def _matpoly(coeffs, X):
    n = len(X)
    out = [[Fraction(0)] * n for _ in range(n)]
    for c in reversed(coeffs):
        out = [[sum(out[i][k] * X[k][j] for k in range(n)) + (c if i == j else 0) for j in range(n)] for i in range(n)]
    return out


def _mul(X, Y):
    return [[sum(X[i][k] * Y[k][j] for k in range(len(Y))) for j in range(len(Y[0]))] for i in range(len(X))]


def _T(X):
    return [list(r) for r in zip(*X)]


@given(st.integers(1, 3).flatmap(lambda n: st.tuples(
    st.lists(st.lists(rationals, min_size=n, max_size=n), min_size=n, max_size=n),
    st.lists(st.lists(rationals, min_size=n, max_size=n), min_size=n, max_size=n))),
    st.sampled_from([ei.methods.taylor(2), ei.methods.taylor(3), ei.methods.pade(1, 1), ei.methods.pade(1, 2),
                     ei.methods.theta("1/4")]),
    st.builds(Fraction, st.integers(1, 9), st.integers(1, 4)))
@settings(max_examples=15)
def test_q_k_is_the_sum_of_principal_minors_of_M_over_h_to_the_k(AB, method, h):
    A, B = AB
    n = len(A)
    Q = [[sum(B[k][i] * B[k][j] for k in range(n)) + (i == j) for j in range(n)] for i in range(n)]
    E = ei.Ellipsoid(Q)
    qs, D = psd_polynomials(ei.LinearSystem(A), E.Q_flint, method)
    hA = [[h * a for a in r] for r in A]
    G, H = _matpoly(method.numerator, hA), _matpoly(method.denominator, hA)
    M = [[a - b for a, b in zip(r, s)] for r, s in zip(_mul(_mul(_T(H), Q), H), _mul(_mul(_T(G), Q), G))]
    hq = flint.fmpq(h.numerator, h.denominator)
    for k, q in enumerate(qs, start=1):
        assert Fraction(str(q(hq))) == _e(M, k) / h**k
    assert Fraction(str(D(hq))) == _det(H)
