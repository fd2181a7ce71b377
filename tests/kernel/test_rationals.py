"""exactinv_check.rationals: strict parsing of exact numbers, vectors and matrices; exact linear algebra."""

from fractions import Fraction as F

import pytest
from hypothesis import given
from hypothesis import strategies as st

from exactinv_check.budget import MAX_DIGITS, MAX_DIMENSION
from exactinv_check.failure import CheckFailure
from exactinv_check.rationals import determinant, matrix, rank_and_nullspace, rational, solve, vector

small = st.fractions(min_value=-20, max_value=20, max_denominator=10)


# ------------------------------------------------------------------ soundness
@given(st.fractions(max_denominator=10**6))
def test_a_number_string_reads_back_exactly(q):
    assert rational(str(q)) == q and rational(f"{q.numerator}/{q.denominator}") == q


def test_a_finite_decimal_is_its_exact_value():  # docs/certificate-format.md: "0.125" is exactly 1/8
    assert (rational("0.125"), rational("-12.50"), rational("3")) == (F(1, 8), F(-25, 2), F(3))


@pytest.mark.parametrize("bad", [1.5, 0.0, True, None, "1.", ".5", "1e3", "01/2", "1/02", "1/0", " 1", "0x10", "nan", "inf",
                                 "1/-2", "--1", [], {}])
def test_anything_but_an_exact_rational_is_refused(bad):
    with pytest.raises(CheckFailure):
        rational(bad)


def test_shapes_are_checked():
    assert vector(["1", "-3/4"], "v", length=2) == [F(1), F(-3, 4)]
    with pytest.raises(CheckFailure, match="expected 3 entries"):
        vector(["1", "2"], "v", length=3)
    with pytest.raises(CheckFailure):
        matrix([["1", "2"], ["3"]], "M")


@given(st.integers(1, 4).flatmap(lambda n: st.lists(st.lists(small, min_size=n, max_size=n), min_size=n, max_size=n)))
def test_determinant_solve_and_nullspace_agree(M):
    n = len(M)
    d = determinant(M)
    rank, null = rank_and_nullspace(M, n)
    assert (d != 0) == (rank == n) and len(null) == n - rank
    for v in null:
        assert any(v) and all(sum(a * x for a, x in zip(row, v)) == 0 for row in M)
    if d != 0:
        X = solve(M, [[F(int(i == j)) for j in range(n)] for i in range(n)])  # the inverse
        assert all(sum(M[i][k] * X[k][j] for k in range(n)) == (i == j) for i in range(n) for j in range(n))


# ------------------------------------------------------------------ resources
def test_a_number_longer_than_max_digits_is_refused_before_parsing():
    assert rational("9" * MAX_DIGITS) == int("9" * MAX_DIGITS)
    with pytest.raises(CheckFailure, match=f"longer than {MAX_DIGITS}"):
        rational("9" * (MAX_DIGITS + 1))
    with pytest.raises(CheckFailure, match="too large"):
        rational(1 << (4 * MAX_DIGITS + 1))


def test_a_vector_longer_than_the_dimension_bound_squared_is_refused_before_its_entries():
    with pytest.raises(CheckFailure, match="too long"):
        vector([None] * (MAX_DIMENSION * MAX_DIMENSION + 1), "v")  # refused by length: no entry is read
