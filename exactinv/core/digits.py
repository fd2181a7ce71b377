"""How exact numbers print -- the one format of reports (polyhedra and
ellipsoids alike) and, copied, of the trusted kernel (``exactinv_check.text``):

* certified decimal digits: the leading significant digits that every number
  of a rational enclosure [lo, hi] shares (:func:`significant_digits`);
* a rational: as it is, with its leading digits when it is long, by its size
  when it is huge (:func:`rational_text`);
* a real algebraic number: its certified digits, its polynomial and an
  isolating interval (:func:`root_text`);
* a double a user may step with: the shortest truncation that reads back as
  it (:func:`float_text`).
"""

from __future__ import annotations

from fractions import Fraction

__all__ = ["significant_digits", "decimal_text", "rational_text", "root_text", "float_text", "SHOWN_DIGITS"]

SHOWN_DIGITS = 60
"""A rational with more digits than this is described by its size (Python limits int -> str)."""


def significant_digits(lo: Fraction, hi: Fraction, digits: int = 17) -> str | None:
    """The common leading ``digits`` significant digits of every number in
    [lo, hi] (truncated towards zero; lo and hi of one sign), or None if the
    enclosure is too wide to certify them.  ``lo == hi`` gives the digits of
    that rational (exact only if nothing was cut off).

    >>> significant_digits(Fraction(251274520497858851, 10**24), Fraction(251274520497858852, 10**24))
    '2.5127452049785885e-7'
    >>> significant_digits(Fraction(1749685831459810, 10**15), Fraction(1749685831459811, 10**15), 10)
    '1.749685831'
    """
    if lo == 0 and hi == 0:
        return "0"
    if lo < 0 < hi or lo == 0 or hi == 0:
        return None
    neg = hi < 0
    a, b = (-hi, -lo) if neg else (lo, hi)
    e = _decade(a)
    if _decade(b) != e:
        return None
    unit = Fraction(10) ** (e - digits + 1)
    ma, mb = _floor(a / unit), _floor(b / unit)
    if ma != mb:
        return None
    mant = str(ma)  # exactly `digits` digits
    if -4 <= e < 16:
        if e >= digits - 1:
            text = mant + "0" * (e - digits + 1)
        elif e >= 0:
            text = mant[:e + 1] + "." + mant[e + 1:]
        else:
            text = "0." + "0" * (-e - 1) + mant
    else:
        text = mant[0] + ("." + mant[1:] if digits > 1 else "") + f"e{e}"
    return ("-" if neg else "") + text


def decimal_text(q: Fraction) -> str:
    """q as an exact decimal when its denominator divides a power of ten, else as a fraction.

    >>> decimal_text(Fraction(1749685831459, 10**12)), decimal_text(Fraction(-3, 8)), decimal_text(Fraction(1, 3))
    ('1.749685831459', '-0.375', '1/3')
    """
    d, twos, fives = q.denominator, 0, 0
    while d % 2 == 0:
        d, twos = d // 2, twos + 1
    while d % 5 == 0:
        d, fives = d // 5, fives + 1
    k = max(twos, fives)
    if d != 1 or k == 0:
        return rational_text(q)
    digits = str(abs(q.numerator * 10**k // q.denominator)).rjust(k + 1, "0")
    text = (digits[:-k] + "." + digits[-k:]).rstrip("0").rstrip(".")
    return ("-" if q < 0 else "") + text


def rational_text(q: Fraction | int) -> str:
    """A rational for a report: as it is when short; with its leading 17 significant
    digits when it is long ("..." when they are cut off); by its size when it has
    more than ``SHOWN_DIGITS`` digits.

    >>> rational_text(Fraction(2, 5)), rational_text(Fraction(1, 3 * 10**20))
    ('2/5', '1/300000000000000000000  (= 3.3333333333333333e-21...)')
    >>> rational_text(Fraction(1, 2**80))
    '1/1208925819614629174706176  (= 8.2718061255302767e-25...)'
    >>> rational_text(Fraction(10**70 + 1, 3))
    'a 71-digit rational  (= 3.3333333333333333e69...)'
    """
    q = Fraction(q)
    size = max(_length(q.numerator), _length(q.denominator))
    if size > SHOWN_DIGITS:
        if q == 0:  # pragma: no cover (0 is short)
            return "0"
        digits = significant_digits(q, q, 17)
        kind = "integer" if q.denominator == 1 else "rational"
        return f"a {size}-digit {'negative ' if q < 0 else ''}{kind}  (= {digits}...)"
    text = str(q)
    if len(text) <= 12 or q.denominator == 1:
        return text
    digits = significant_digits(q, q, 17)
    return f"{text}  (= {digits}{'' if Fraction(digits) == q else '...'})"


def root_text(digits: str, poly: str, lower: Fraction, upper: Fraction) -> str:
    """A real algebraic number for a report: its certified ``digits``, its polynomial
    (plain text, e.g. from :func:`exactinv.core.polys.poly_text`) and an isolating
    interval with decimal ends where they are decimals.

    >>> root_text("1.7496858314598103", "x^4 - 6x^2 + 12x - 12", Fraction(1749685831459, 10**12),
    ...           Fraction(174968583146, 10**11))
    '1.7496858314598103  (the root of x^4 - 6x^2 + 12x - 12 in [1.749685831459, 1.74968583146])'
    """
    return f"{digits}  (the root of {poly} in [{decimal_text(lower)}, {decimal_text(upper)}])"


def float_text(d: float) -> str:
    """The shortest decimal that reads back as the double ``d >= 0`` (``float(text) == d``)
    and is itself at most ``d``: ``d``'s exact binary value truncated to as few
    significant digits as round-trip, in :func:`significant_digits`' notation.  So a
    printed safe step is safe both as a float literal and as a real number.

    >>> float_text(6271923527134733 / 2**52)    # repr() would round up to ...407
    '1.3926467817026406'
    >>> float_text(0.5), float_text(1e-300 / 3) == repr(1e-300 / 3) or float(float_text(1e-300 / 3)) == 1e-300 / 3
    ('0.5', True)
    """
    if not d > 0 or d == float("inf"):
        return repr(d)
    q = Fraction(d)
    for digits in range(1, 800):  # a double's exact expansion has at most 767 significant digits
        text = significant_digits(q, q, digits)
        if float(text) == d:  # what a user's float parse gives: correctly rounded
            return text
    return repr(d)  # pragma: no cover (the exact expansion always reads back)


def _decade(q: Fraction) -> int:
    """e with 10**e <= q < 10**(e+1), for q > 0 (from bit lengths: no int -> str)."""
    e = (q.numerator.bit_length() - q.denominator.bit_length()) * 30103 // 100000
    while Fraction(10) ** e > q:
        e -= 1
    while Fraction(10) ** (e + 1) <= q:
        e += 1
    return e


def _length(k: int) -> int:
    """The number of decimal digits of the integer k (no int -> str)."""
    return 1 if k == 0 else _decade(Fraction(abs(k))) + 1


def _floor(q: Fraction) -> int:
    return q.numerator // q.denominator
