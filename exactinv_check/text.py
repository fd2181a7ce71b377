"""Numbers as the kernel prints them: the engine's one format (exactinv.core.digits
and exactinv.core.polys.poly_text), copied here because the kernel imports nothing
from exactinv.  tests/test_number_format.py checks that both print alike.

* a rational: as it is when short; with its leading 17 significant digits when
  long; by its size beyond SHOWN_DIGITS digits (Python limits int -> str);
* a real algebraic number: its certified digits, its polynomial and an
  isolating interval, ``1.7496858314598103  (the root of x^4 - 6x^2 + 12x - 12
  in [1.749685831459, 1.74968583146])``;
* infinity: ``oo``.

Printing decides nothing: the digits are read off an enclosure refined by exact
bisection, and a shorter decimal enclosure is shown only where Descartes' rule
proves it isolates the same root.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Sequence

from .budget import MAX_PRINT_BISECTIONS
from .polys import no_root_between, sign_at
from .rationals import SHOWN_DIGITS

__all__ = ["significant_digits", "decimal_text", "rational_text", "root_text", "poly_text", "algebraic_text"]

TIDY_DIGITS = 12  # decimals of the printed isolating interval (as the engine's RealAlgebraic.tidy)
PRINTABLE_DIGITS = 4000  # decimal_text's digits at most (its denominator's bits bound the decimals)
PRINTABLE_BITS = 13000  # integers printed digit by digit have at most this many bits (about 3900 digits): Python's
# int -> str stops at 4300 digits (ValueError), and a radius's d_j over a common denominator of three 1999-digit
# denominators has 6000-digit coefficients; longer numbers are described by their size (red team rt-gate)


def significant_digits(lo: Fraction, hi: Fraction, digits: int = 17) -> Any:
    """The common leading ``digits`` significant digits of every number in [lo, hi]
    (truncated towards zero; lo and hi of one sign), or None if the enclosure is too
    wide to certify them."""
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
    mant = str(ma)
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
    """q as an exact decimal when its denominator divides a power of ten, else as a fraction."""
    q = Fraction(q)
    if q.numerator.bit_length() * 3 // 10 + q.denominator.bit_length() > PRINTABLE_DIGITS:  # k <= bits of d
        return rational_text(q)
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


def rational_text(q: Any) -> str:
    """A rational: as it is when short, with its leading digits when long, by its size when huge."""
    q = Fraction(q)
    size = max(_length(q.numerator), _length(q.denominator))
    if size > SHOWN_DIGITS:
        digits = significant_digits(q, q, 17)
        kind = "integer" if q.denominator == 1 else "rational"
        return f"a {size}-digit {'negative ' if q < 0 else ''}{kind}  (= {digits}...)"
    text = str(q)
    if len(text) <= 12 or q.denominator == 1:
        return text
    digits = significant_digits(q, q, 17)
    return f"{text}  (= {digits}{'' if Fraction(digits) == q else '...'})"


def root_text(digits: str, poly: str, lower: Fraction, upper: Fraction) -> str:
    """A real algebraic number: certified ``digits``, its polynomial (text), an isolating interval."""
    return f"{digits}  (the root of {poly} in [{decimal_text(lower)}, {decimal_text(upper)}])"


def poly_text(coeffs: Sequence[int], var: str = "x") -> str:
    """Plain text of a polynomial (rational coefficients from the constant term up), highest degree first."""
    cs = [Fraction(c) for c in coeffs]
    bits = max((max(c.numerator.bit_length(), c.denominator.bit_length()) for c in cs), default=0)
    if bits > PRINTABLE_BITS:  # too long to print digit by digit (and to read)
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


def algebraic_text(ints: Sequence[int], lo: Any, hi: Any) -> str:
    """The root of the integer polynomial ``ints`` (low to high) isolated by (lo, hi), in the
    one format: 17 certified digits from exact bisection of a copy of the enclosure, the
    polynomial with a positive leading coefficient, and the interval the cell
    [k, k + 1] / 10**TIDY_DIGITS of the decimal grid that holds the root (as the engine's
    RealAlgebraic.tidy) where Descartes' rule proves the added slivers root-free."""
    s_lo = sign_at(ints, lo)
    scale = 10**TIDY_DIGITS
    digits = None
    for _ in range(MAX_PRINT_BISECTIONS):
        digits = significant_digits(lo, hi, 17)
        if digits is not None and _floor(lo * scale) == -_floor(-hi * scale) - 1:
            break
        mid = (lo + hi) / 2
        s = sign_at(ints, mid)
        if s == 0:
            return rational_text(mid)
        lo, hi = (mid, hi) if s == s_lo else (lo, mid)
    else:
        digits = significant_digits(lo, hi, 17)
    cell = Fraction(_floor(lo * scale), scale)
    top = cell + Fraction(1, scale)
    if cell <= lo and hi <= top and sign_at(ints, cell) != 0 and sign_at(ints, top) != 0 and \
            (cell == lo or no_root_between(ints, cell, lo)) and (top == hi or no_root_between(ints, hi, top)):
        lo, hi = cell, top
    shown = poly_text(ints if ints[-1] > 0 else [-c for c in ints])
    if digits is None:  # digits not certified within the bisections: the enclosure alone
        return f"the root of {shown} in [{decimal_text(lo)}, {decimal_text(hi)}]"
    return root_text(digits, shown, lo, hi)


def _decade(q: Fraction) -> int:
    """e with 10**e <= q < 10**(e+1), for q > 0 (from bit lengths: no int -> str)."""
    e = (q.numerator.bit_length() - q.denominator.bit_length()) * 30103 // 100000
    while Fraction(10) ** e > q:
        e -= 1
    while Fraction(10) ** (e + 1) <= q:
        e += 1
    return e


def _length(k: int) -> int:
    return 1 if k == 0 else _decade(Fraction(abs(k))) + 1


def _floor(q: Fraction) -> int:
    return q.numerator // q.denominator
