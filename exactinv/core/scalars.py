"""Exact scalars, vectors and matrices: the one place where input is parsed.

Everything that enters exactinv is converted here, once, to
:class:`fractions.Fraction` (the public, immutable form) and, where the
engine computes, to python-flint's ``fmpq``/``fmpq_mat``.  Accepted scalars:

* ``int`` (not ``bool``), :class:`~fractions.Fraction`, :class:`~decimal.Decimal`;
* strings such as ``"3/4"``, ``"-2"``, ``"0.1"`` (exactly 1/10) or ``"1e-3"``;
* sympy rationals and python-flint ``fmpz``/``fmpq``;
* numpy integers, and numpy 0-d arrays holding any of the above.

Matrices and vectors may be lists of rows, numpy arrays (integer dtype, or
object dtype holding Fractions, ints, sympy rationals, ...), sympy matrices
(a vector may also be an n x 1 or 1 x n sympy matrix or numpy array) or FLINT
matrices.  Every one is copied entry by entry; nothing the caller passed is
kept or changed.

Python, numpy and sympy floats (and so numpy float arrays) are refused: a float
such as ``0.1`` is not the number 1/10, and exactinv does not guess which number
was meant.  Pass ``"0.1"``, or
convert deliberately with :func:`exact_from_float` (the exact binary value) or
:func:`nearest_rational` (the simplest nearby fraction), or pass
``allow_float=True`` to the parsing functions (which then take the float's
exact binary value, as :func:`exact_from_float` does -- for a numpy
``longdouble`` or a sympy ``Float`` at its own precision).
"""

from __future__ import annotations

import math
import numbers as _abc
from decimal import Decimal
from fractions import Fraction
from functools import total_ordering
from typing import Any, Iterable, Sequence

import flint

from ..errors import InvalidInput
from .flintq import Matrix, Vector
from .moved import moved_names

# The Fraction <-> FLINT conversions live in exactinv.core.flintq; their old spelling here warns.
__getattr__ = moved_names(__name__, dict.fromkeys(
    ["dyadic_of", "fmpq_column", "fmpq_matrix", "fmpq_of", "fraction_of", "matrix_of", "vector_of"], "exactinv.core.flintq"))

__all__ = [
    "INF",
    "Infinity",
    "Matrix",
    "Vector",
    "exact_from_float",
    "nearest_rational",
    "to_rational",
    "to_vector",
    "to_matrix",
]



@total_ordering
class Infinity:
    """Exact +infinity or -infinity (``INF`` and ``-INF``).

    Compares with ints, Fractions and :class:`~exactinv.RealAlgebraic` and
    with other infinities; ``float(INF)`` is ``math.inf``.
    """

    __slots__ = ("sign",)

    def __new__(cls, sign: int = 1):
        if sign not in (1, -1):
            raise InvalidInput(f"Infinity: sign must be 1 or -1, got {sign!r}")
        cached = _INFINITIES.get(sign)
        if cached is not None:
            return cached
        self = super().__new__(cls)
        object.__setattr__(self, "sign", sign)
        _INFINITIES[sign] = self
        return self

    def __setattr__(self, name, value):
        raise AttributeError("Infinity is immutable")

    def __neg__(self) -> "Infinity":
        return Infinity(-self.sign)

    def __pos__(self) -> "Infinity":
        return self

    def __float__(self) -> float:
        return math.inf * self.sign

    def __eq__(self, other: object) -> bool:
        if isinstance(other, Infinity):
            return other.sign == self.sign
        if isinstance(other, float) and math.isinf(other):
            return (other > 0) == (self.sign > 0)
        return False

    def __lt__(self, other: object) -> bool:
        if isinstance(other, Infinity):
            return self.sign < other.sign
        if _is_comparable(other):
            return self.sign < 0
        return NotImplemented

    def __hash__(self) -> int:
        return hash(math.inf * self.sign)

    def __repr__(self) -> str:
        return "INF" if self.sign > 0 else "-INF"

    def __str__(self) -> str:
        return "oo" if self.sign > 0 else "-oo"

    def __reduce__(self):
        return (Infinity, (self.sign,))

    def _repr_latex_(self) -> str:
        return r"$\infty$" if self.sign > 0 else r"$-\infty$"


_INFINITIES: dict[int, Infinity] = {}
INF = Infinity(1)


def _is_comparable(other: object) -> bool:
    if isinstance(other, (int, Fraction)) and not isinstance(other, bool):
        return True
    # RealAlgebraic lives in another module; duck-type it to avoid a cycle.
    return hasattr(other, "_is_real_algebraic")


def exact_from_float(x: float) -> Fraction:
    """The exact rational value of a finite binary float (0.1 -> 3602879701896397/36028797018963968).

    >>> exact_from_float(0.1)
    Fraction(3602879701896397, 36028797018963968)
    >>> exact_from_float(0.5)
    Fraction(1, 2)
    """
    if not isinstance(x, (float, int)) or isinstance(x, bool):
        x = float(x)
    if not math.isfinite(x):
        raise InvalidInput(f"exact_from_float: {x!r} is not a finite number")
    return Fraction(x)


def nearest_rational(x: float, max_denominator: int = 10**6) -> Fraction:
    """The rational with denominator <= ``max_denominator`` closest to the float ``x``
    (0.1 -> 1/10).  A deliberate, explicit rounding step.

    >>> nearest_rational(0.1), nearest_rational(3.14159265, 100)
    (Fraction(1, 10), Fraction(311, 99))
    """
    return exact_from_float(x).limit_denominator(max_denominator)


def to_rational(value: Any, name: str = "value", *, allow_float: bool = False) -> Fraction:
    """Parse one exact scalar; ``name`` is used in error messages.

    >>> to_rational("3/4"), to_rational(2), to_rational(flint.fmpq(-1, 3))
    (Fraction(3, 4), Fraction(2, 1), Fraction(-1, 3))
    >>> to_rational(0.1, allow_float=True) == Fraction(0.1)   # the float's exact value, on request
    True
    """
    if isinstance(value, Fraction):
        return value
    if getattr(value, "ndim", None) == 0 and hasattr(value, "item"):  # a numpy 0-d array
        value = value.item()
    if isinstance(value, bool) or type(value).__name__ == "bool_":  # numpy's bool too
        raise InvalidInput(f"{name}: got the bool {value!r}; pass a number")
    if isinstance(value, int):
        return Fraction(value)
    if isinstance(value, str):
        return _rational_from_text(value, name)
    if isinstance(value, Decimal):
        if not value.is_finite():
            raise InvalidInput(f"{name}: {value!r} is not a finite rational number")
        return Fraction(value)
    if isinstance(value, flint.fmpq) or getattr(value, "is_Rational", False):  # flint, sympy Integer / Rational
        return Fraction(int(value.p), int(value.q))
    if isinstance(value, (flint.fmpz, _abc.Integral)):  # numpy integers, gmpy2 mpz
        return Fraction(int(value))
    if isinstance(value, float) or isinstance(value, _abc.Real) and not isinstance(value, _abc.Rational):
        return _rational_from_float(value, name, allow_float)
    if isinstance(value, _abc.Rational):  # e.g. gmpy2 mpq
        return Fraction(int(value.numerator), int(value.denominator))
    if getattr(value, "is_number", False) and getattr(value, "is_Rational", None) is False:
        raise InvalidInput(f"{name}: {value} is not a rational number")
    raise InvalidInput(f"{name}: cannot read {value!r} (type {type(value).__name__}) as a rational number")


def _rational_from_text(value: str, name: str) -> Fraction:
    text = value.strip()
    if text.lower().lstrip("+-") in ("nan", "inf", "infinity"):
        raise InvalidInput(f"{name}: {value!r} is not a finite rational number")
    try:
        return Fraction(text)
    except (ValueError, ZeroDivisionError):
        raise InvalidInput(
            f"{name}: cannot read {value!r} as a rational number (write e.g. '3/4', '-2' or '0.1')"
        ) from None


def _rational_from_float(value: Any, name: str, allow_float: bool) -> Fraction:
    if getattr(value, "is_Float", False):  # a sympy Float: its own precision, not a double's
        if not value.is_finite:
            raise InvalidInput(f"{name}: {value!r} is not a finite number")
        if allow_float:
            import sympy

            exact = sympy.Rational(value)
            return Fraction(int(exact.p), int(exact.q))
        as_float = float(value)
    else:
        as_float = float(value)
        if not math.isfinite(as_float):
            raise InvalidInput(f"{name}: {value!r} is not a finite number")
        if allow_float:
            if hasattr(value, "as_integer_ratio"):  # float, numpy float16 .. longdouble: exact
                return Fraction(*value.as_integer_ratio())
            return exact_from_float(as_float)
    kind = "" if type(value) is float else f" ({type(value).__module__.split('.')[0]} {type(value).__name__})"
    raise InvalidInput(
        f"{name}: got the float {value!r}{kind}; floats are not exact. Pass a string "
        f"such as '{_suggest(as_float)}', a Fraction, or convert explicitly with "
        f"exactinv.exact_from_float / exactinv.nearest_rational (or allow_float=True)"
    )


def _suggest(x: float) -> str:
    return repr(x) if len(repr(x)) < 20 else str(nearest_rational(x))


def _rows(value: Any, name: str, allow_float: bool = False) -> list:
    if hasattr(value, "tolist") and not isinstance(value, str):  # numpy, sympy, flint matrices
        if isinstance(value, (flint.fmpq_mat, flint.fmpz_mat)):
            return [[value[i, j] for j in range(value.ncols())] for i in range(value.nrows())]
        kind = getattr(getattr(value, "dtype", None), "kind", None)
        if kind in ("f", "c") and not allow_float:
            raise InvalidInput(
                f"{name}: got a numpy array of dtype {value.dtype}; floats are not exact. Pass an integer "
                f"array, an object array of Fractions or strings (np.array([...], dtype=object)), or convert "
                f"explicitly with exactinv.exact_from_float / exactinv.nearest_rational (or allow_float=True)")
        value = value.tolist()
    if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
        raise InvalidInput(f"{name}: expected a list of rows, got {type(value).__name__}")
    return list(value)


def to_vector(
    value: Any, name: str = "vector", *, length: int | None = None, allow_float: bool = False
) -> Vector:
    """Parse a vector of exact scalars, optionally checking its length.

    >>> to_vector(['1/3', 2], 'b', length=2)
    (Fraction(1, 3), Fraction(2, 1))
    """
    if isinstance(value, (flint.fmpq_mat, flint.fmpz_mat)):
        value = [value[i, j] for i in range(value.nrows()) for j in range(value.ncols())]
    shape = getattr(value, "shape", None)
    if isinstance(shape, tuple) and len(shape) == 2 and 1 in shape and hasattr(value, "tolist"):
        value = [x for row in _rows(value, name, allow_float) for x in row]  # an n x 1 or 1 x n matrix / array
    items = _rows(value, name, allow_float)
    out = []
    for i, entry in enumerate(items):
        if not isinstance(entry, (str, bytes)) and isinstance(entry, Iterable):
            raise InvalidInput(f"{name}: entry {i} is a sequence; expected a vector of numbers")
        out.append(to_rational(entry, f"{name}[{i}]", allow_float=allow_float))
    if not out:
        raise InvalidInput(f"{name}: the vector is empty")
    if length is not None and len(out) != length:
        raise InvalidInput(f"{name}: expected length {length}, got length {len(out)}")
    return tuple(out)


def to_matrix(
    value: Any,
    name: str = "matrix",
    *,
    shape: tuple[int | None, int | None] = (None, None),
    square: bool = False,
    allow_float: bool = False,
) -> Matrix:
    """Parse a matrix given as a sequence of rows; checks raggedness, emptiness
    and (optionally) the shape and squareness, naming the offending position.

    >>> to_matrix([[1, '1/2'], [0, 3]], 'A', square=True)
    ((Fraction(1, 1), Fraction(1, 2)), (Fraction(0, 1), Fraction(3, 1)))
    """
    rows = _rows(value, name, allow_float)
    if not rows:
        raise InvalidInput(f"{name}: the matrix is empty")
    out = []
    width = None
    for i, row in enumerate(rows):
        if isinstance(row, (str, bytes)) or not isinstance(row, Iterable):
            raise InvalidInput(f"{name}: row {i} is {row!r}, not a sequence; expected a list of rows")
        entries = list(row)
        if width is None:
            width = len(entries)
            if width == 0:
                raise InvalidInput(f"{name}: row 0 is empty")
        elif len(entries) != width:
            raise InvalidInput(f"{name}: ragged matrix, row 0 has {width} entries but row {i} has {len(entries)}")
        out.append(tuple(to_rational(e, f"{name}[{i}][{j}]", allow_float=allow_float) for j, e in enumerate(entries)))
    rows_expected, cols_expected = shape
    if square and len(out) != width:
        raise InvalidInput(f"{name}: must be square, got shape {len(out)}x{width}")
    if rows_expected is not None and len(out) != rows_expected:
        raise InvalidInput(f"{name}: expected {rows_expected} rows, got {len(out)} (shape {len(out)}x{width})")
    if cols_expected is not None and width != cols_expected:
        raise InvalidInput(f"{name}: expected {cols_expected} columns, got {width} (shape {len(out)}x{width})")
    return tuple(out)


# ---------------------------------------------------------------- flint bridge
def format_rational(x: Fraction | Infinity) -> str:
    """The exact string form used in JSON and on the command line ("-3/4").

    >>> format_rational(Fraction(-3, 4)), format_rational(Fraction(2)), format_rational(INF)
    ('-3/4', '2', 'oo')
    """
    return str(x)


def frac_latex(q: Fraction) -> str:
    """A Fraction as a compact LaTeX ``\\tfrac``.

    >>> print(frac_latex(Fraction(-3, 4)), frac_latex(Fraction(5)))
    -\\tfrac{3}{4} 5
    """
    if q.denominator == 1:
        return str(q.numerator)
    sign = "-" if q < 0 else ""
    return f"{sign}\\tfrac{{{abs(q.numerator)}}}{{{q.denominator}}}"


def vector_text(v: Sequence[Fraction]) -> str:
    """A vector of exact values as "[a, b, ...]".

    >>> vector_text([Fraction(1, 3), Fraction(-2)])
    '[1/3, -2]'
    """
    return "[" + ", ".join(str(x) for x in v) + "]"


def matrix_text(M: Sequence[Sequence[Fraction]]) -> str:
    """A matrix of exact values as "[[a, b], ...]".

    >>> matrix_text([[Fraction(1, 2), Fraction(0)], [Fraction(-1), Fraction(3)]])
    '[[1/2, 0], [-1, 3]]'
    """
    return "[" + ", ".join(vector_text(r) for r in M) + "]"
