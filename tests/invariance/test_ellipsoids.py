"""exactinv.invariance.ellipsoids: exact invariance of ellipsoids, with
the witness checked by the test's own arithmetic and the certificate by the kernel."""

from fractions import Fraction

import pytest
from hypothesis import given
from hypothesis import strategies as st

import exactinv as ei
from exactinv.core.psd import quadratic_form

DISC = ei.Ellipsoid([[1, 0], [0, 1]])


def _matmul(X, Y):
    return [[sum(X[i][k] * Y[k][j] for k in range(len(Y))) for j in range(len(Y[0]))] for i in range(len(X))]


def _transpose(X):
    return [list(r) for r in zip(*X)]


def test_the_rotation_with_damping_keeps_the_unit_disc():
    S = ei.LinearSystem([[-1, -2], [2, -1]])  # A + A^T = -2I
    r = ei.continuous_invariance(S, DISC)
    assert r.holds and r.witness is None and all(d == 2 for d in r.proof.D)
    assert ei.check(r.certificate).ok


def test_a_shear_leaves_the_disc_and_the_witness_says_where():
    A = [[-1, 3], [0, -1]]  # A + A^T = [[-2, 3], [3, -2]] has the eigenvalue 1 > 0
    r = ei.continuous_invariance(ei.LinearSystem(A), DISC)
    assert not r.holds
    v = r.witness.v
    L = [[a + b for a, b in zip(ra, rb)] for ra, rb in zip(_transpose(A), A)]
    assert quadratic_form(L, v) == r.witness.value > 0 and r.witness.norm == quadratic_form(DISC.Q, v)
    assert ei.check(r.certificate).ok


@st.composite
def maps_and_ellipsoids(draw):
    n = draw(st.integers(1, 3))
    entry = st.builds(Fraction, st.integers(-3, 3), st.integers(1, 3))
    Ad = [[draw(entry) for _ in range(n)] for _ in range(n)]
    B = [[draw(entry) for _ in range(n)] for _ in range(n)]
    Q = [[sum(B[k][i] * B[k][j] for k in range(n)) + (1 if i == j else 0) for j in range(n)] for i in range(n)]
    return Ad, ei.Ellipsoid(Q)


@given(maps_and_ellipsoids())
def test_discrete_invariance_on_random_maps(case):
    """holds: ||A_d x||_Q <= ||x||_Q at the test's own random points; fails: the
    witness's image is outside E (computed here)."""
    Ad, E = case
    r = ei.discrete_invariance(Ad, E)
    M = [[q - p for q, p in zip(rq, rp)] for rq, rp in zip(E.Q, _matmul(_matmul(_transpose(Ad), E.Q), Ad))]
    if r.holds:
        for k in range(-3, 4):
            x = [Fraction(k + i, 3) for i in range(E.n)]
            assert quadratic_form(M, x) >= 0
    else:
        v = r.witness.v
        image = [sum(a * x for a, x in zip(row, v)) for row in Ad]
        assert quadratic_form(E.Q, image) > quadratic_form(E.Q, v) > 0
        assert quadratic_form(E.Q, image) - quadratic_form(E.Q, v) == r.witness.value


def test_discrete_invariance_from_a_method_names_dt_in_the_certificate():
    S = ei.LinearSystem([[-1, -2], [2, -1]])
    yes = ei.discrete_invariance(S, DISC, ei.methods.forward_euler(), "2/5")   # the threshold itself
    no = ei.discrete_invariance(S, DISC, ei.methods.forward_euler(), "41/100")
    assert yes.holds and not no.holds
    for r in (yes, no):
        claim = r.certificate["claims"][0]
        assert claim["dt"] in ("2/5", "41/100") and ei.check(r.certificate).ok


@pytest.mark.parametrize("call, match", [
    (lambda: ei.continuous_invariance(ei.LinearSystem([[1]]), DISC), "system/ellipsoid"),
    (lambda: ei.discrete_invariance([[1, 0, 0]] * 3, DISC), "Ad"),
    (lambda: ei.discrete_invariance(ei.LinearSystem([[1, 0], [0, 1]]), DISC), "method= and dt="),
    (lambda: ei.discrete_invariance(ei.LinearSystem([[1, 0], [0, 1]]), DISC, ei.methods.taylor(1), -1), "dt"),
    (lambda: ei.discrete_invariance([[0.5, 0], [0, 1]], DISC), "float"),
])
def test_bad_input_is_named(call, match):
    with pytest.raises(ei.ExactinvError, match=match):
        call()
