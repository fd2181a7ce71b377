"""Primitives on Q[x] shared by root isolation and the valid-set computation.

Exact sign evaluation, Descartes' rule of signs (on (0, oo) and on an interval
(a, b) after a Moebius map), Sturm counting and the sign just right of a
point.  Every function works on FLINT polynomials; :func:`as_polynomial`
converts input once, at the boundary.

>>> sign_variations([1, -2, 0, 3])
2
>>> no_root_between([-2, 0, 1], 0, 1)      # x^2 - 2 has no root in (0, 1)
True
>>> sign_right_of([0, -1, 1], 0)           # x^2 - x is negative just right of 0
-1
"""

from __future__ import annotations

from fractions import Fraction
from math import comb
from typing import Any, Iterable

import flint

from ..errors import InvalidInput
from .flintq import fmpq_of
from .scalars import to_rational

__all__ = [
    "as_polynomial",
    "integer_part",
    "shift",
    "sign_at",
    "poly_text",
    "sign_variations",
    "no_root_between",
    "no_positive_root_below",
    "positive_below",
    "count_real_roots",
    "sign_right_of",
    "positive_right_of_zero",
    "poly_latex",
]

ONE_PLUS_X = flint.fmpq_poly([1, 1])


def as_polynomial(f: Any, name: str = "f") -> flint.fmpq_poly:
    """An exact polynomial from an fmpq_poly/fmpz_poly, a sympy Poly, or a
    sequence of coefficients from the constant term up.

    >>> as_polynomial([Fraction(1, 2), 0, 1])   # coefficients from x^0 up
    x^2 + 1/2
    """
    if isinstance(f, flint.fmpq_poly):
        return f
    if isinstance(f, flint.fmpz_poly):
        return flint.fmpq_poly(f)
    if hasattr(f, "all_coeffs") and hasattr(f, "gens"):  # sympy Poly (high to low)
        coeffs = list(reversed(f.all_coeffs()))
    elif isinstance(f, (str, bytes)) or not isinstance(f, Iterable):
        raise InvalidInput(f"{name}: expected a polynomial or a list of coefficients (constant term first)")
    else:
        coeffs = list(f)
    return flint.fmpq_poly([fmpq_of(to_rational(c, f"{name}[{k}]")) for k, c in enumerate(coeffs)])


def integer_part(f: flint.fmpq_poly) -> flint.fmpz_poly:
    """The primitive integer polynomial with the same roots and sign as f.

    >>> integer_part(flint.fmpq_poly([1, -3, 2], 6))   # (2x^2 - 3x + 1)/6
    2*x^2 + (-3)*x + 1
    """
    num = f.numer()
    return num // num.content() if not num.is_zero() else num


def shift(f: flint.fmpq_poly, start: Fraction) -> flint.fmpq_poly:
    """f(start + x).

    >>> shift(flint.fmpq_poly([0, 0, 1]), Fraction(1))   # (1 + x)^2
    x^2 + 2*x + 1
    """
    if start == 0:
        return f
    return f(flint.fmpq_poly([fmpq_of(start), 1]))


def sign_at(p: flint.fmpz_poly | flint.fmpq_poly, x: Fraction) -> int:
    """The exact sign of p(x) at a rational x.

    >>> p = flint.fmpq_poly([-2, 0, 1])   # x^2 - 2
    >>> sign_at(p, Fraction(7, 5)), sign_at(p, Fraction(3, 2)), sign_at(p * 0, Fraction(1))
    (-1, 1, 0)
    """
    v = p(fmpq_of(x))
    return (v > 0) - (v < 0)


def sign_variations(coeffs: Iterable[Any]) -> int:
    """Number of sign changes in a coefficient sequence, zeros ignored.
    By Descartes' rule it bounds the number of positive roots (with
    multiplicity) and has the same parity.

    >>> sign_variations([1, 0, -2, 3, 0, 4]), sign_variations([1, 2, 3])
    (2, 0)
    """
    signs = [c > 0 for c in coeffs if c != 0]
    return sum(1 for a, b in zip(signs, signs[1:]) if a != b)


def no_root_between(p: Any, a: Fraction, b: Fraction) -> bool:
    """True if Descartes' rule proves that p has no root in the open interval
    (a, b): the Moebius-transformed (1+x)^d p((a + b x)/(1 + x)) has no sign
    variation.  (False means: not proved.)  Exact; a Taylor shift in FLINT.

    >>> p = flint.fmpq_poly([-2, 0, 1])   # roots +-sqrt(2)
    >>> no_root_between(p, Fraction(0), Fraction(1)), no_root_between(p, Fraction(1), Fraction(2))
    (True, False)
    """
    pq = as_polynomial(p)
    shifted = pq(flint.fmpq_poly([fmpq_of(a), fmpq_of(b - a)]))  # p(a + (b - a) y), y in (0, 1)
    transformed = flint.fmpq_poly(list(reversed(shifted.coeffs())))(ONE_PLUS_X)
    return sign_variations(transformed.coeffs()) == 0


def no_positive_root_below(p: flint.fmpq_poly, T: Fraction) -> bool:
    """Descartes' rule on (0, T): True proves that p has no root in (0, T).

    >>> p = flint.fmpq_poly([-2, 0, 1])
    >>> no_positive_root_below(p, Fraction(1)), no_positive_root_below(p, Fraction(2))
    (True, False)
    """
    return no_root_between(p, Fraction(0), T)


def positive_below(polys: list[flint.fmpq_poly], T: Fraction | None) -> list[bool]:
    """For each p: True proves p > 0 on the open (0, T) (T None: on (0, oo)) -- exactly when
    p is positive just right of 0 and Descartes' rule on (0, T) sees no sign variation
    (after padding to the largest degree d, a factor (1 + y)^j with no positive root).
    All at once: with T = P/Q, the coefficients of Q^d (1 + y)^d p(T y/(1 + y)) are
    sum_k a_k P^k Q^(d-k) C(d-k, m-k) (a = the numerator's coefficients, a positive
    multiple of p's), one FLINT integer matrix product; p is proved positive iff they are
    all >= 0 and one is > 0.  False says nothing.

    >>> ps = [flint.fmpq_poly([-2, 0, 1]), flint.fmpq_poly([2, -3, 1]), flint.fmpq_poly([0, 1, 5])]
    >>> positive_below(ps, Fraction(1)), positive_below(ps, None)   # x^2 - 2, (x - 1)(x - 2), x + 5x^2
    ([False, True, True], [False, False, True])
    """
    if not polys:
        return []
    d = max(max(p.degree(), 0) for p in polys)
    rows = [p.numer().coeffs() for p in polys]
    M = flint.fmpz_mat(len(rows), d + 1, [x for r in rows for x in r + [0] * (d + 1 - len(r))])
    if T is not None:
        P, Q = T.numerator, T.denominator
        M = M * flint.fmpz_mat(d + 1, d + 1, [P**k * Q ** (d - k) * comb(d - k, m - k) if m >= k else 0
                                              for k in range(d + 1) for m in range(d + 1)])
    entries, zero = M.entries(), flint.fmpz(0)
    return [min(entries[i:i + d + 1]) >= zero and max(entries[i:i + d + 1]) > zero
            for i in range(0, len(entries), d + 1)]


def count_real_roots(p: Any, lower: Fraction | None = None, upper: Fraction | None = None) -> int:
    """Number of distinct real roots of p in the open interval (lower, upper)
    (None = unbounded), by Sturm's theorem in exact arithmetic.  The ends must
    not be roots.

    >>> p = flint.fmpq_poly([0, -2, 0, 1])   # x^3 - 2x: roots 0, +-sqrt(2)
    >>> count_real_roots(p), count_real_roots(p, Fraction(0)), count_real_roots(p, Fraction(-1), Fraction(1))
    (3, 1, 1)
    """
    pq = as_polynomial(p)
    seq = [pq, pq.derivative()]
    while not seq[-1].is_zero():
        seq.append(-(seq[-2] % seq[-1]))
    seq.pop()

    def variations(x):
        return sign_variations([s(fmpq_of(x)) for s in seq])

    def at_infinity(sign):
        vals = []
        for s in seq:
            lead = s.coeffs()[-1] if s.degree() >= 0 else 0
            vals.append(lead * (sign ** s.degree()))
        return sign_variations(vals)

    left = at_infinity(-1) if lower is None else variations(lower)
    right = at_infinity(1) if upper is None else variations(upper)
    return left - right


def sign_right_of(f: Any, t: Fraction) -> int:
    """The sign of f on (t, t + eps) for small eps > 0: the sign of the first
    nonzero Taylor coefficient of f at t (0 only for the zero polynomial).

    >>> p = flint.fmpq_poly([1, -2, 1])   # (x - 1)^2
    >>> sign_right_of(p, Fraction(1)), sign_right_of(-p, Fraction(0)), sign_right_of(p * 0, Fraction(0))
    (1, -1, 0)
    """
    g = shift(as_polynomial(f), Fraction(t))
    for c in g.coeffs():
        if c != 0:
            return 1 if c > 0 else -1
    return 0


def positive_right_of_zero(p: Any) -> bool:
    """p >= 0 just right of 0 (True for the zero polynomial).

    >>> positive_right_of_zero([0, 1]), positive_right_of_zero([0, -1, 5]), positive_right_of_zero([0])
    (True, False, True)
    """
    return sign_right_of(p, Fraction(0)) >= 0


def interpolate(points: Iterable[Any], values: Iterable[Any]) -> flint.fmpq_poly:
    """The polynomial of degree < len(points) through (points, values), exactly (Lagrange).

    >>> interpolate([0, 1, 2], [1, 2, 5])
    x^2 + 1
    """
    points, values = list(points), list(values)
    x = flint.fmpq_poly([0, 1])
    total = flint.fmpq_poly([0])
    for i, (xi, yi) in enumerate(zip(points, values)):
        term = flint.fmpq_poly([fmpq_of(yi) if isinstance(yi, Fraction) else yi])
        for j, xj in enumerate(points):
            if j != i:
                term = term * (x - fmpq_of(Fraction(xj))) / fmpq_of(Fraction(xi) - Fraction(xj))
        total += term
    return total


PRINTABLE_BITS = 13000  # coefficients printed digit by digit have at most this many bits (as the kernel's text.py)


def poly_text(coeffs: Any, var: str = "x") -> str:
    """Plain text of a polynomial (an fmpz/fmpq poly or rational coefficients
    from the constant term up), highest degree first.

    >>> poly_text([-12, 12, -6, 0, 1])
    'x^4 - 6x^2 + 12x - 12'
    >>> poly_text(["1", "-1", "1/2", "-1/6"], "t")
    '-t^3/6 + t^2/2 - t + 1'
    >>> poly_text([1, 0, 10**5000])
    'a polynomial of degree 2 with coefficients of up to 16610 bits'
    """
    if hasattr(coeffs, "coeffs"):
        coeffs = coeffs.coeffs()
    cs = [to_rational(c, "coefficient") if not isinstance(c, (flint.fmpz, flint.fmpq)) else Fraction(int(c.p), int(c.q))
          if isinstance(c, flint.fmpq) else Fraction(int(c)) for c in coeffs]
    bits = max((max(c.numerator.bit_length(), c.denominator.bit_length()) for c in cs), default=0)
    if bits > PRINTABLE_BITS:  # Python's int -> str stops at 4300 digits; nobody reads such a polynomial
        return f"a polynomial of degree {len(cs) - 1} with coefficients of up to {bits} bits"
    terms = []
    for k in range(len(cs) - 1, -1, -1):
        c = cs[k]
        if c == 0:
            continue
        mag = abs(c)
        mono = "" if k == 0 else (var if k == 1 else f"{var}^{k}")
        if k == 0:
            body = str(mag)
        else:
            body = ("" if mag.numerator == 1 else str(mag.numerator)) + mono + \
                ("" if mag.denominator == 1 else f"/{mag.denominator}")
        terms.append((" - " if c < 0 else " + ") + body)
    text = "".join(terms) or " + 0"
    return ("-" + text[3:]) if text.startswith(" - ") else text[3:]


def poly_latex(p: Any) -> str:
    """LaTeX of an integer polynomial in x, highest degree first.

    >>> print(poly_latex(flint.fmpz_poly([-2, 0, 1])))
    x^{2}-2
    """
    terms = []
    coeffs = [int(c) for c in p.coeffs()]
    for k in range(len(coeffs) - 1, -1, -1):
        c = coeffs[k]
        if c == 0:
            continue
        mag = abs(c)
        mono = "" if k == 0 else ("x" if k == 1 else f"x^{{{k}}}")
        body = str(mag) if (mag != 1 or k == 0) else ""
        terms.append(("-" if c < 0 else "+") + body + mono)
    text = "".join(terms) or "0"
    return text[1:] if text.startswith("+") else text
