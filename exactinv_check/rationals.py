"""Exact rationals, vectors and matrices read from a certificate -- strictly.

Every number in a certificate is a string: an integer or a fraction
("-3/4"), a finite decimal ("0.125"), or "oo" / "-oo" where the format
allows an infinity.  Anything else -- a JSON float, a bool, an exponent, an
over-long string -- is rejected, so parsing can neither hang nor guess.
"""

from __future__ import annotations

import re
from fractions import Fraction
from math import gcd
from typing import Any

from .budget import MAX_DIGITS, MAX_DIMENSION
from .failure import CheckFailure, require

SHOWN_DIGITS = 60  # longer numbers are described by their size in messages
_ZERO = Fraction(0)

# an integer or a fraction without leading zeros ("0", "-3/4", not "01/2" nor "1/02"),
# or a finite decimal ("0.125", "-12.5"; the fraction part may end in zeros)
_NUMBER = re.compile(r"[+-]?(?:0|[1-9][0-9]*)(?:/[1-9][0-9]*|\.[0-9]+)?")


def describe(x: Any) -> Any:
    """x for a message: in full if short, else by its size ("a 6001-digit integer"),
    so that a huge exact number never reaches str() (Python limits int -> str)."""
    if isinstance(x, (int, Fraction)) and not isinstance(x, bool):
        q = Fraction(x)
        digits = max(abs(q.numerator).bit_length(), q.denominator.bit_length()) * 30103 // 100000 + 1
        if digits > SHOWN_DIGITS:
            kind = "integer" if q.denominator == 1 else "rational"
            return f"a {digits}-digit {'negative ' if q < 0 else ''}{kind}"
    return str(x)


def integer_matrix(M: Any) -> Any:
    """(L, L M) with L > 0 the least common denominator of M's entries: L M is integral,
    and L M >= 0 iff M >= 0 (a positive factor changes no sign)."""
    L = 1
    for row in M:
        for x in row:
            L = L * x.denominator // gcd(L, x.denominator)
    return L, [[x.numerator * (L // x.denominator) for x in row] for row in M]


def integer_rows(G: Any, b: Any) -> Any:
    """Each row of (G | b) times its least positive common denominator: (g, beta) in integers,
    the same half-space g x <= beta."""
    rows = []
    for g, beta in zip(G, b):
        _, (scaled,) = integer_matrix([list(g) + [beta]])
        rows.append((scaled[:-1], scaled[-1]))
    return rows


def rational(s: Any, what: str = "number") -> Any:
    """A Fraction from an exact number string (never from a float or bool)."""
    if isinstance(s, bool) or not isinstance(s, (str, int)):
        raise CheckFailure(f"{what}: expected an exact number string, got {s!r}")
    if isinstance(s, int):
        require(abs(s).bit_length() <= 4 * MAX_DIGITS, f"{what}: integer too large")
        return Fraction(s)
    if s == "0":  # most entries of a large certificate's H
        return _ZERO
    require(len(s) <= MAX_DIGITS, f"{what}: number string longer than {MAX_DIGITS} characters")
    require(_NUMBER.fullmatch(s) is not None, f"{what}: {s!r} is not an exact rational")
    try:
        return Fraction(s)
    except ZeroDivisionError:
        raise CheckFailure(f"{what}: {s!r} has a zero denominator") from None


def integer(x: Any, what: Any, low: Any = None, high: Any = None) -> Any:
    """A JSON integer (not a bool) in [low, high)."""
    require(isinstance(x, int) and not isinstance(x, bool), f"{what}: expected an integer, got {x!r}")
    require((low is None or x >= low) and (high is None or x < high), f"{what}: {x} is out of range")
    return x


def boolean(x: Any, what: str) -> Any:
    """A JSON boolean (not the string "false", not 0/1)."""
    require(isinstance(x, bool), f"{what}: expected true or false, got {x!r}")
    return x


def vector(v: Any, what: Any, length: Any = None) -> Any:
    """A list of rationals, of the given length when one is given."""
    require(isinstance(v, list), f"{what}: expected a list")
    require(len(v) <= MAX_DIMENSION * MAX_DIMENSION, f"{what}: too long")
    require(length is None or len(v) == length, f"{what}: expected {length} entries, got {len(v)}")
    return [rational(x, what) for x in v]


def matrix(M: Any, what: Any, rows: Any = None, cols: Any = None) -> Any:
    """A list of equal-length rows of rationals (shape checked when given)."""
    require(isinstance(M, list), f"{what}: expected a list of rows")
    require(rows is None or len(M) == rows, f"{what}: expected {rows} rows, got {len(M)}")
    out = [vector(r, what) for r in M]
    width = cols if cols is not None else (len(out[0]) if out else 0)
    require(all(len(r) == width for r in out), f"{what}: rows of unequal or wrong length")
    return out


def dot(u: Any, v: Any) -> Any:
    require(len(u) == len(v), "vector lengths differ")
    return sum(a * b for a, b in zip(u, v))


def matvec(X: Any, v: Any) -> Any:
    return [dot(row, v) for row in X]


def matmul(X: Any, Y: Any) -> Any:
    cols = list(zip(*Y)) if Y else []
    return [[dot(row, col) for col in cols] for row in X]


def transpose(X: Any) -> Any:
    return [list(r) for r in zip(*X)]


def identity(n: Any) -> Any:
    return [[Fraction(int(i == j)) for j in range(n)] for i in range(n)]


def rank_and_nullspace(M: Any, n: Any) -> tuple[int, list[list[Any]]]:
    """(rank, a basis of {x : Mx = 0}) of a list of rows of length n, by Gauss-Jordan."""
    rows = [list(r) for r in M]
    pivots = []
    r = 0
    for col in range(n):
        pivot = next((i for i in range(r, len(rows)) if rows[i][col] != 0), None)
        if pivot is None:
            continue
        rows[r], rows[pivot] = rows[pivot], rows[r]
        inv = 1 / rows[r][col]
        rows[r] = [v * inv for v in rows[r]]
        for i in range(len(rows)):
            if i != r and rows[i][col] != 0:
                f = rows[i][col]
                rows[i] = [a - f * c for a, c in zip(rows[i], rows[r])]
        pivots.append(col)
        r += 1
    free = [c for c in range(n) if c not in pivots]
    basis = []
    for f in free:
        x = [Fraction(0)] * n
        x[f] = Fraction(1)
        for i, c in enumerate(pivots):
            x[c] = -rows[i][f]
        basis.append(x)
    return r, basis


def solve(M: Any, B: Any) -> Any:
    """X with M X = B (Gauss-Jordan over Q, M square); None if M is singular."""
    n = len(M)
    aug = [list(M[i]) + list(B[i]) for i in range(n)]
    for col in range(n):
        pivot = next((r for r in range(col, n) if aug[r][col] != 0), None)
        if pivot is None:
            return None
        aug[col], aug[pivot] = aug[pivot], aug[col]
        inv = 1 / aug[col][col]
        aug[col] = [v * inv for v in aug[col]]
        for r in range(n):
            if r != col and aug[r][col] != 0:
                f = aug[r][col]
                aug[r] = [a - f * c for a, c in zip(aug[r], aug[col])]
    return [row[n:] for row in aug]


def determinant(M: Any) -> Any:
    n = len(M)
    a = [list(r) for r in M]
    det = Fraction(1)
    for col in range(n):
        pivot = next((r for r in range(col, n) if a[r][col] != 0), None)
        if pivot is None:
            return Fraction(0)
        if pivot != col:
            a[col], a[pivot] = a[pivot], a[col]
            det = -det
        det *= a[col][col]
        for r in range(col + 1, n):
            f = a[r][col] / a[col][col]
            if f:
                a[r] = [x - f * y for x, y in zip(a[r], a[col])]
    return det
