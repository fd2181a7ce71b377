"""exactinv.core.psd: the exact PSD decision, against an independent criterion.

A symmetric matrix is PSD iff every principal minor is >= 0 (not just the
leading ones); the test computes all principal minors by exact Fraction
cofactor expansion, sharing nothing with the elimination under test.
"""

from fractions import Fraction
from itertools import combinations

import pytest
from hypothesis import given
from hypothesis import strategies as st

import exactinv as ei
from exactinv.core.psd import psd_decision, quadratic_form, symmetric_matrix


def _det(M):
    if not M:
        return Fraction(1)
    return sum((-1) ** j * M[0][j] * _det([r[:j] + r[j + 1:] for r in M[1:]]) for j in range(len(M)) if M[0][j])


def _psd_by_minors(M):
    n = len(M)
    return all(_det([[M[i][j] for j in S] for i in S]) >= 0 for k in range(1, n + 1) for S in combinations(range(n), k))


@st.composite
def symmetric(draw):
    """B^T B minus a random diagonal: PSD, singular PSD or indefinite, all common."""
    n = draw(st.integers(1, 4))
    rows = draw(st.integers(0, n))
    B = [[Fraction(draw(st.integers(-2, 2)), draw(st.integers(1, 2))) for _ in range(n)] for _ in range(rows)]
    shift = [Fraction(draw(st.integers(0, 1)), draw(st.integers(1, 4))) for _ in range(n)]
    return [[sum((B[k][i] * B[k][j] for k in range(rows)), Fraction(0)) - (shift[i] if i == j else 0)
             for j in range(n)] for i in range(n)]


def _check_proof(M, proof):
    n, p = len(M), proof.perm
    assert sorted(p) == list(range(n))
    assert all(d >= 0 for d in proof.D)
    for i in range(n):
        assert proof.L[i][i] == 1 and all(proof.L[i][j] == 0 for j in range(i + 1, n))
        for j in range(n):
            assert sum(proof.L[i][k] * proof.D[k] * proof.L[j][k] for k in range(n)) == M[p[i]][p[j]]


@given(symmetric())
def test_the_decision_agrees_with_all_principal_minors_and_carries_its_evidence(M):
    d = psd_decision(M)
    assert d.psd == _psd_by_minors(M)
    if d.psd:
        _check_proof(M, d.proof)
    else:
        assert quadratic_form(M, d.witness) == d.value < 0


def test_semidefinite_with_zero_pivots_and_a_zero_diagonal_beside_a_nonzero_entry():
    assert psd_decision([[0, 0], [0, 1]]).psd and not psd_decision([[0, 0], [0, 1]]).definite
    d = psd_decision([[0, 1], [1, 0]])  # zero diagonal, nonzero off-diagonal: indefinite
    assert not d.psd and quadratic_form([[0, 1], [1, 0]], d.witness) == -2
    d = psd_decision([[1, 1, 1], [1, 1, 1], [1, 1, 0]])  # the remainder after one pivot is [[0, 0], [0, -1]]
    assert not d.psd and quadratic_form([[1, 1, 1], [1, 1, 1], [1, 1, 0]], d.witness) < 0
    assert psd_decision([[0, 0], [0, 0]]).psd


@pytest.mark.parametrize("M, what", [([[1, 2], [3, 1]], "not symmetric"), ([[1, 0.5], [0.5, 1]], "float"),
                                     ([[1, 2, 3]], "square")])
def test_bad_matrices_are_named(M, what):
    with pytest.raises(ei.ExactinvError, match=what):
        symmetric_matrix(M, "M")
