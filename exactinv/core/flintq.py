"""Conversions between exact Fractions and python-flint's fmpz/fmpq/fmpq_mat/arb.

The engine computes with FLINT; results are reported as Fractions.  Both
directions are exact (FLINT keeps its rationals canonical, so no gcd is
recomputed on the way back).  Re-exported by :mod:`exactinv.core.scalars`.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Sequence

import flint

__all__ = ["Vector", "Matrix", "fmpq_of", "fraction_of", "fmpq_matrix", "fmpq_column", "matrix_of", "vector_of",
           "dyadic_of", "exact_text"]

Vector = tuple[Fraction, ...]
Matrix = tuple[tuple[Fraction, ...], ...]


def fmpq_of(x: Fraction) -> flint.fmpq:
    """A Fraction as a FLINT rational.

    >>> fmpq_of(Fraction(-2, 6))
    -1/3
    """
    return flint.fmpq(x.numerator, x.denominator)


def fraction_of(x: flint.fmpq | flint.fmpz | int) -> Fraction:
    """A FLINT rational or integer (or an int) as a Fraction.

    >>> fraction_of(flint.fmpq(6, 4)), fraction_of(flint.fmpz(7))
    (Fraction(3, 2), Fraction(7, 1))
    """
    if isinstance(x, (flint.fmpz, int)):
        return Fraction(int(x))
    return _coprime(int(x.p), int(x.q))


def _coprime(p: int, q: int) -> Fraction:
    # flint keeps fmpq canonical (coprime, q > 0): skip Fraction's gcd.
    try:
        return Fraction(p, q, _normalize=False)
    except TypeError:  # Python >= 3.12
        return Fraction._from_coprime_ints(p, q)


def fmpq_matrix(rows: Sequence[Sequence[Fraction]]) -> flint.fmpq_mat:
    """The fmpq matrix of exact rows.

    >>> fmpq_matrix([[Fraction(1, 2), 0], [0, 1]]).det()
    1/2
    """
    m = len(rows)
    n = len(rows[0]) if m else 0
    return flint.fmpq_mat(m, n, [fmpq_of(x) for row in rows for x in row])


def fmpq_column(entries: Sequence[Fraction]) -> flint.fmpq_mat:
    """The column fmpq matrix of exact entries.

    >>> fmpq_column([Fraction(1, 2), Fraction(-3)]).entries()
    [1/2, -3]
    """
    return flint.fmpq_mat(len(entries), 1, [fmpq_of(x) for x in entries])


def matrix_of(M: flint.fmpq_mat) -> Matrix:
    """The rows of an fmpq matrix, as Fractions.

    >>> matrix_of(flint.fmpq_mat([[1, 2], [3, 4]]) / 2)
    ((Fraction(1, 2), Fraction(1, 1)), (Fraction(3, 2), Fraction(2, 1)))
    """
    return tuple(tuple(fraction_of(M[i, j]) for j in range(M.ncols())) for i in range(M.nrows()))


def vector_of(M: flint.fmpq_mat) -> Vector:
    """The entries of a column (or row) matrix, as Fractions.

    >>> vector_of(flint.fmpq_mat(2, 1, [flint.fmpq(1, 3), 2]))
    (Fraction(1, 3), Fraction(2, 1))
    """
    return tuple(fraction_of(x) for x in M.entries())


def dyadic_of(a: flint.arb) -> Fraction:
    """The midpoint of an Arb ball as an exact dyadic Fraction.

    >>> dyadic_of(flint.arb(3) / 4)
    Fraction(3, 4)
    """
    man, exp = a.mid().man_exp()
    man, exp = int(man), int(exp)
    return Fraction(man * 2**exp) if exp >= 0 else Fraction(man, 2**-exp)


def exact_text(x: Fraction | int | flint.fmpz | flint.fmpq) -> str:
    """The exact decimal text "p" or "p/q" of a rational of any size (str(Fraction) and str(int)
    stop at Python's 4300-digit limit; FLINT's decimal conversion has none).

    >>> exact_text(Fraction(-3, 4)), exact_text(7), len(exact_text(Fraction(10**5000, 3)))
    ('-3/4', '7', 5003)
    """
    if isinstance(x, (flint.fmpz, flint.fmpq)):
        return str(x)
    if isinstance(x, int):
        return str(flint.fmpz(x))
    return str(flint.fmpz(x.numerator)) if x.denominator == 1 else f"{flint.fmpz(x.numerator)}/{flint.fmpz(x.denominator)}"
