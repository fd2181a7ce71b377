"""Certified decimal digits: the leading significant digits that every number
of a rational enclosure [lo, hi] shares (how exact values are printed).
"""

from __future__ import annotations

from fractions import Fraction

__all__ = ["significant_digits"]


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


def _decade(q: Fraction) -> int:
    """e with 10**e <= q < 10**(e+1), for q > 0."""
    e = (q.numerator.bit_length() - q.denominator.bit_length()) * 30103 // 100000  # within 1 of log10 q
    while Fraction(10) ** e > q:
        e -= 1
    while Fraction(10) ** (e + 1) <= q:
        e += 1
    return e


def _floor(q: Fraction) -> int:
    return q.numerator // q.denominator
