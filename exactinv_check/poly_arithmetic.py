"""Polynomials over Q as coefficient lists from x^0 up: exact arithmetic on an
integer core (content, pseudo-remainders, the gcd), every polynomial the
kernel builds from a certificate bounded by MAX_DEGREE.  Re-exported by
:mod:`exactinv_check.polys`.
"""

from __future__ import annotations

from fractions import Fraction
from math import gcd as _igcd
from typing import Any, Sequence

from .budget import (
    MAX_ALGEBRAIC_DEGREE,
    MAX_DEGREE,  # bound on every polynomial the kernel builds from a certificate
    active,
    charge,
    content_cost,
    fraction_products_cost,
    remainder_step_cost,
)
from .failure import require


def trim(p: Any) -> Any:
    p = list(p)
    while p and p[-1] == 0:
        p.pop()
    return p


def degree(p: Any) -> Any:
    return len(trim(p)) - 1


def evaluate(p: Sequence[int | Fraction], x: Any) -> Any:
    """p(x) over Q (Horner), charged to the certificate's account by the size of x."""
    if active():
        x = Fraction(x)
        charge(fraction_products_cost(len(p), len(p) * max(abs(x.numerator).bit_length(), x.denominator.bit_length())),
               "a value of a polynomial")
    acc = Fraction(0)
    for c in reversed(p):
        acc = acc * x + c
    return acc


def sign(x: int | Fraction) -> Any:
    return (x > 0) - (x < 0)


def integer_coefficients(p: Sequence[int | Fraction]) -> Any:
    """Coprime integers proportional to p by a positive factor (so signs agree).

    Charged to the certificate's account by the sizes of its numbers before they are built (budget.content_cost):
    coefficients 1/d_k with distinct 3300-bit d_k make a common denominator of degree x 3300 bits shared by every
    integer, and the content's gcds of such numbers ran minutes uncharged (red team rt-budget2: a 200 KB algebraic
    number of degree 200 kept the kernel over 60 s of CPU before any charge)."""
    p = trim(p)
    metered = active()
    den = 1
    for c in p:
        if not isinstance(c, int) and c.denominator != 1:
            if metered:
                charge(content_cost(1, den.bit_length(), c.denominator.bit_length()), "a common denominator")
            den = den * c.denominator // _igcd(den, c.denominator)
    if metered and den != 1:
        charge(content_cost(len(p), den.bit_length(), max(abs(Fraction(c).numerator).bit_length() for c in p)),
               "the integer coefficients of a polynomial (their content)")
    return content_free([c * den if isinstance(c, int) else c.numerator * (den // c.denominator) for c in p])


def add(p: Sequence[Fraction], q: Sequence[Fraction]) -> Any:
    n = max(len(p), len(q))
    return trim([(p[i] if i < len(p) else 0) + (q[i] if i < len(q) else 0) for i in range(n)])


def sub(p: Sequence[Fraction], q: Sequence[Fraction]) -> Any:
    return add(p, [-c for c in q])


def scale(p: Sequence[Fraction], c: Fraction) -> Any:
    return trim([c * a for a in p])


def mul(p: Sequence[Fraction], q: Any) -> Any:
    """p q over Q, charged to the certificate's account by the sizes of the numbers (Fraction products)."""
    if not p or not q:
        return []
    if active():
        charge(fraction_products_cost(len(p) * len(q), _bits(p) + _bits(q)), "a polynomial product")
    out = [Fraction(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        if a:
            for j, b in enumerate(q):
                out[i + j] += a * b
    return trim(out)


def _bits(p: Sequence[Fraction]) -> int:
    """The largest numerator or denominator of p's coefficients, in bits."""
    return max(max(abs(Fraction(c).numerator).bit_length(), Fraction(c).denominator.bit_length()) for c in p)


def mul_integers(p: Any, q: Sequence[int]) -> list[int]:
    """The product of two polynomials with integer coefficients, in integers (not trimmed)."""
    out = [0] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        if a:
            for j, c in enumerate(q):
                out[i + j] += a * c
    return out


def power(p: Sequence[Fraction], k: int) -> list[Fraction]:
    out = [Fraction(1)]
    for _ in range(k):
        out = mul(out, p)
    return out


def derivative(p: Any) -> Any:
    return trim([k * p[k] for k in range(1, len(p))])


def divmod_(p: Any, d: Any) -> Any:
    p, d = trim(p), trim(d)
    require(d, "division by the zero polynomial")
    q = [Fraction(0)] * max(len(p) - len(d) + 1, 1)
    r = list(p)
    lead = d[-1]
    while r and len(r) >= len(d):
        shift = len(r) - len(d)
        c = Fraction(r[-1]) / lead
        q[shift] = c
        for k, dk in enumerate(d):
            r[k + shift] -= c * dk
        r = trim(r)
    return trim(q), r


def primitive(p: Any) -> Any:
    """p scaled by a POSITIVE rational to coprime integer coefficients (sign kept)."""
    return [Fraction(c) for c in integer_coefficients(p)]


def monic(p: Sequence[int | Fraction]) -> Any:
    p = trim(p)
    return [Fraction(c, 1) / p[-1] for c in p] if p else p


# --------------------------------------------- integer core (Python ints, no Fractions)
def content_free(a: Sequence[int]) -> Any:
    """a divided by the positive gcd of its coefficients (signs kept)."""
    g = 0
    for c in a:
        g = _igcd(g, c)
    return [c // g for c in a] if g > 1 else a


def pseudo_remainder(a: Sequence[int], b: Sequence[int]) -> list[int]:
    """r with s^k a = q b + r for s = |lc(b)| > 0: the remainder up to a POSITIVE factor,
    so signs (Sturm) and divisibility (gcd) are those of the rational remainder."""
    s, sgn = abs(b[-1]), (1 if b[-1] > 0 else -1)
    r = list(a)
    s_bits = s.bit_length()
    while len(r) >= len(b) and r:
        shift, c = len(r) - len(b), r[-1] * sgn
        charge(remainder_step_cost(len(r), s_bits, c.bit_length()), "a pseudo-remainder sequence")
        r = [s * x for x in r]
        for k, bk in enumerate(b):
            r[k + shift] -= c * bk
        while r and r[-1] == 0:
            r.pop()
        r = content_free(r)
    return r


def integer_gcd(a: Sequence[int], b: Sequence[int]) -> Any:
    """gcd of two integer polynomials: primitive, positive leading coefficient."""
    while b:
        a, b = b, pseudo_remainder(a, b)
    a = content_free(a)
    return [-c for c in a] if a and a[-1] < 0 else a


def exact_quotient(a: Sequence[int], b: Sequence[int]) -> list[int]:
    """a / b for integer polynomials where b divides a over Z (checked)."""
    a, q = list(a), [0] * (len(a) - len(b) + 1)
    for shift in range(len(a) - len(b), -1, -1):
        c, rest = divmod(a[shift + len(b) - 1], b[-1])
        require(rest == 0, "internal: inexact polynomial division")
        q[shift] = c
        for k, bk in enumerate(b):
            a[k + shift] -= c * bk
    require(not any(a), "internal: inexact polynomial division")
    return q


def integer_derivative(a: Sequence[int]) -> list[int]:
    """The derivative of an integer polynomial (coefficients from x^0 up)."""
    return [k * a[k] for k in range(1, len(a))]


def gcd(p: Any, q: Any) -> Any:
    """The monic gcd over Q."""
    g = integer_gcd(integer_coefficients(bounded(p, MAX_ALGEBRAIC_DEGREE)),
                    integer_coefficients(bounded(q, MAX_ALGEBRAIC_DEGREE)))
    return [Fraction(c, g[-1]) for c in g] if g else []


def bounded(p: Sequence[int | Fraction], limit: int = MAX_DEGREE) -> Any:
    """p itself, after checking its degree is at most ``limit`` (else the claim is rejected): MAX_DEGREE, or
    MAX_ALGEBRAIC_DEGREE for the computations charged by the sizes of their numbers as they run (gcds by
    pseudo-remainders, squarefree parts, Descartes isolation)."""
    require(len(p) - 1 <= limit, f"a polynomial of degree {len(p) - 1} exceeds the kernel's bound {limit}")
    return p


def strip_zero_roots(p: Sequence[int | Fraction]) -> Any:
    p = trim(p)
    while p and p[0] == 0:
        p = p[1:]
    return p
