"""Exact real numbers of a certificate: rationals, +-infinity, real algebraic numbers.

A real algebraic number is written ``{"poly": [c0, c1, ...], "interval": [lo, hi]}``:
the unique root of c0 + c1 x + ... in the open interval (lo, hi).  The kernel
accepts it only after proving that (lo, hi) holds exactly one root and that
neither end is a root: by Descartes' rule on (lo, hi) when it counts one sign
variation, else by Descartes isolation of the squarefree part.  Ordering and
equality are then decided exactly (bisection and gcds), never by tolerance.

Invariant of an algebraic Real: its root is a *simple* root of ``poly``, the
only root of ``poly`` in the open (lo, hi), and poly(lo), poly(hi) are nonzero
(so of opposite signs).  Bisections are charged to the certificate's account.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Sequence

from . import poly_arithmetic, polys, resultants, text
from .budget import MAX_ALGEBRAIC_DEGREE, MAX_REFINEMENTS, charge, remainder_step_cost
from .failure import CheckFailure, require
from .format import INFINITY, NEG_INFINITY
from .poly_arithmetic import evaluate, sign
from .rationals import rational


class Real:
    """A proved real: ``q`` (a Fraction), ``inf`` (+1/-1) or an isolated root."""

    __slots__ = ("inf", "q", "poly", "lo", "hi", "_ints", "_sign_lo", "_bits")

    def __init__(self, inf: int = 0, q: Fraction | None = None, poly: Sequence[int] | None = None,
                 lo: Fraction | None = None, hi: Fraction | None = None) -> None:
        self.inf, self.q, self.poly, self.lo, self.hi = inf, q, poly, lo, hi
        if poly is not None:
            self._ints = poly_arithmetic.integer_coefficients(poly)
            self._bits = max(abs(c).bit_length() for c in self._ints)
            self._sign_lo = polys.sign_at(self._ints, lo, self._bits)

    # -------------------------------------------------------- construction
    @classmethod
    def parse(cls, data: Any, what: Any="number", infinite: Any=True) -> Any:
        if isinstance(data, str) and data in (INFINITY, NEG_INFINITY):
            require(infinite, f"{what}: infinity is not allowed here")
            return cls(inf=1 if data == INFINITY else -1)
        if isinstance(data, dict):
            require(set(data) == {"poly", "interval"}, f"{what}: an algebraic number has exactly the keys poly, interval")
            require(isinstance(data["poly"], list) and len(data["poly"]) <= MAX_ALGEBRAIC_DEGREE + 1,
                    f"{what}: the polynomial must be a list of at most {MAX_ALGEBRAIC_DEGREE + 1} coefficients")
            poly = poly_arithmetic.trim([rational(c, what) for c in data["poly"]])
            require(isinstance(data["interval"], list) and len(data["interval"]) == 2, f"{what}: interval needs two ends")
            lo, hi = (rational(x, what) for x in data["interval"])
            return cls.claimed(poly, lo, hi, what)
        return cls(q=rational(data, what))

    @classmethod
    def rational(cls, q: Any) -> Any:
        return cls(q=Fraction(q))

    @classmethod
    def algebraic(cls, poly: Any, lo: Fraction, hi: Fraction, what: str = "number") -> Any:
        """The unique root of poly in the open (lo, hi) -- proved, or CheckFailure."""
        require(len(poly_arithmetic.trim(poly)) >= 2, f"{what}: the polynomial must have degree >= 1")
        require(lo < hi, f"{what}: empty isolating interval")
        p = polys.squarefree(poly)
        require(evaluate(p, lo) != 0 and evaluate(p, hi) != 0, f"{what}: an end of the interval is a root")
        require(polys.count_roots(p, lo, hi) == 1, f"{what}: the interval does not isolate exactly one root")
        return cls._made(p, lo, hi)

    @classmethod
    def claimed(cls, poly: Any, lo: Any, hi: Any, what: str = "number") -> Any:
        """A certificate's algebraic number, proved well defined cheaply first.

        Descartes' rule on (lo, hi) counting exactly one sign variation proves
        exactly one root there, and a simple one, in O(d^2) integer operations;
        only when it is inconclusive is the squarefree part isolated on (lo, hi)
        (:meth:`algebraic`), every step charged to the certificate's account."""
        require(len(poly_arithmetic.trim(poly)) >= 2, f"{what}: the polynomial must have degree >= 1")
        require(lo < hi, f"{what}: empty isolating interval")
        ints = poly_arithmetic.integer_coefficients(poly)
        require(polys.sign_at(ints, lo) != 0 and polys.sign_at(ints, hi) != 0, f"{what}: an end of the interval is a root")
        if polys.descartes_variations(ints, lo, hi) == 1:
            return cls._made(ints, lo, hi)
        return cls.algebraic(poly, lo, hi, what)

    @classmethod
    def _made(cls, p: Sequence[int], lo: Fraction, hi: Fraction) -> Real:
        if len(p) == 2:  # a linear polynomial: the root is rational
            return cls(q=-Fraction(p[0]) / p[1])
        return cls(poly=p, lo=lo, hi=hi)

    @classmethod
    def root_in(cls, p: Sequence[int | Fraction], lo: Fraction, hi: Fraction) -> Any:
        """From (lo, hi) data of polys.positive_roots (lo == hi: the rational root)."""
        return cls(q=lo) if lo == hi else cls._made(polys.squarefree(poly_arithmetic.strip_zero_roots(p)), lo, hi)

    # -------------------------------------------------------------- queries
    @property
    def is_rational(self) -> bool:
        return not self.inf and self.poly is None

    def is_zero(self) -> Any:
        return self.is_rational and self.q == 0

    def bounds(self) -> Any:
        """Rational (lower, upper) with lower <= self <= upper; None for infinities."""
        if self.inf:
            return None
        return (self.q, self.q) if self.poly is None else (self.lo, self.hi)

    def bisect(self) -> None:
        mid = (self.lo + self.hi) / 2  # type: ignore[operator]
        s = polys.sign_at(self._ints, mid, self._bits)  # charged by the largest coefficient
        if s == 0:
            self.q, self.poly = mid, None
        elif s == self._sign_lo:
            self.lo = mid
        else:
            self.hi = mid

    def refine_below(self, width: Any) -> None:
        """Bisect until the enclosure is narrower than width."""
        for _ in range(MAX_REFINEMENTS):
            if self.poly is None or self.hi - self.lo < width:  # type: ignore[operator]
                return
            self.bisect()

    def sign_of(self, f: Any) -> Any:
        """The exact sign of the polynomial f at this (finite) real."""
        require(not self.inf, "sign at infinity")
        f = poly_arithmetic.trim(f)
        if not f:
            return 0
        if self.poly is None:
            return sign(evaluate(f, self.q))
        g = poly_arithmetic.gcd(f, self.poly)
        if len(g) > 1 and sign(evaluate(g, self.lo)) * sign(evaluate(g, self.hi)) < 0:
            return 0  # g divides poly, whose root here is simple and alone in (lo, hi): g changes sign iff g(root) = 0
        fi = poly_arithmetic.integer_coefficients(f)
        for _ in range(MAX_REFINEMENTS):  # f(root) != 0: refine until Descartes proves no root of f in (lo, hi)
            if self.poly is None:
                return polys.sign_at(fi, self.q)
            s = polys.sign_at(fi, self.lo)
            if s != 0 and polys.descartes_variations(fi, self.lo, self.hi) == 0:
                return s
            self.bisect()
        raise CheckFailure("could not decide a sign at an algebraic number")

    def compare(self, other: Any) -> Any:
        """-1, 0 or 1: the exact order of self and other."""
        if self.inf or other.inf:
            return sign(self.inf - other.inf)
        if self.poly is None and other.poly is None:
            return sign(self.q - other.q)
        if self.poly is None:
            return -other.compare(self)
        if other.poly is None:  # self algebraic, other rational q: one sign of poly at q (the root is poly's only
            q = other.q  # sign change in (lo, hi)); a gcd with x - q cost a pseudo-remainder sequence at degree 272
            if q <= self.lo:
                return 1
            if q >= self.hi:
                return -1
            s = polys.sign_at(self._ints, q, self._bits)
            return 0 if s == 0 else (1 if s == self._sign_lo else -1)
        if self.hi <= other.lo:
            return -1
        if other.hi <= self.lo:
            return 1
        if self._same_polynomial(other):
            return self._compare_conjugate(other)
        if self._shares_root_with(other):
            return 0
        for _ in range(MAX_REFINEMENTS):  # different numbers: refine until the enclosures part
            if self.poly is None or other.poly is None:
                return self.compare(other)
            if self.hi <= other.lo:
                return -1
            if other.hi <= self.lo:
                return 1
            # refine the wider enclosure only: a number compared often (a running
            # minimum) then keeps the precision it needs, instead of gaining bits each time
            (self if self.hi - self.lo >= other.hi - other.lo else other).bisect()  # type: ignore[operator]
        raise CheckFailure("could not separate two real numbers")

    def _same_polynomial(self, other: Real) -> bool:
        """Both roots of one polynomial (up to a nonzero factor)?"""
        a, b = self._ints, other._ints
        return len(a) == len(b) and (a == b or a == [-c for c in b])

    def _compare_conjugate(self, other: Any) -> Any:
        """-1, 0 or 1 for two roots of the same polynomial p: equal iff one enclosure lies inside
        the other (a root of p in the other's (lo, hi) is the other's root, p has only that one
        there); else refine the wider until they are disjoint or nested -- this ends, since two
        equal roots lie strictly inside both intervals, and two different ones part.  No gcd,
        no root count."""
        for _ in range(MAX_REFINEMENTS):
            if self.poly is None or other.poly is None:
                return self.compare(other)
            if self.hi <= other.lo:
                return -1
            if other.hi <= self.lo:
                return 1
            if (other.lo <= self.lo and self.hi <= other.hi) or (self.lo <= other.lo and other.hi <= self.hi):
                return 0
            (self if self.hi - self.lo >= other.hi - other.lo else other).bisect()  # type: ignore[operator]
        raise CheckFailure("could not compare two roots of one polynomial")

    def _shares_root_with(self, other: Any) -> Any:
        """Are these two overlapping algebraic numbers equal?  Each is a root of
        g = gcd iff g changes sign on its own isolating interval (g divides the
        squarefree poly, so it has at most that one root there); if both are,
        they are equal iff g has a single root in the union of the intervals."""
        a, b = self._ints, other._ints
        small, large = (a, b) if len(a) <= len(b) else (b, a)
        # one polynomial dividing the other (a certificate's value is often a factor of the kernel's own d_j): that
        # divisor is the gcd, found by one exact division instead of a pseudo-remainder sequence
        g = small if divides(small, large) else poly_arithmetic.gcd(self.poly, other.poly)
        if len(g) <= 1:
            return False
        gi = poly_arithmetic.integer_coefficients(g)
        for x in (self, other):
            if polys.sign_at(gi, x.lo) * polys.sign_at(gi, x.hi) >= 0:
                return False
        lo, hi = min(self.lo, other.lo), max(self.hi, other.hi)
        return polys.count_roots(g, lo, hi) == 1

    def __str__(self) -> str:
        if self.inf:
            return INFINITY if self.inf > 0 else NEG_INFINITY
        if self.poly is None:
            return text.rational_text(self.q)
        return text.algebraic_text(self._ints, self.lo, self.hi)  # the engine's format (exactinv.core.digits)


def separate(a: Real, b: Real) -> tuple[Fraction, Fraction]:
    """Rationals a1 < b0 with a <= a1 < b0 <= b, for reals a < b (refining them)."""
    for _ in range(MAX_REFINEMENTS):
        (a0, a1), (b0, b1) = a.bounds(), b.bounds()
        if a1 < b0:
            return a1, b0
        if a.poly is not None and (b.poly is None or a1 - a0 >= b1 - b0):
            a.bisect()
        else:
            b.bisect()
    raise CheckFailure("two reals could not be separated")


def scaled(a: Any, c: Any) -> Any:
    """c a for an algebraic a and a rational c > 0, with no new isolation: if a is the simple root
    of p alone in (lo, hi), c a is the simple root of p(x / c) alone in (c lo, c hi) (x -> c x is an
    increasing bijection), so the Real invariant carries over."""
    require(c > 0, "scaling by a positive rational only")
    d = len(a._ints) - 1
    n, m = c.numerator, c.denominator  # p(x m / n) n^d = sum p_k m^k n^(d-k) x^k
    return Real._made([p * m ** k * n ** (d - k) for k, p in enumerate(a._ints)], a.lo * c, a.hi * c)


def quotient(a: Any, b: Any) -> Any:
    """a / b as a Real, for a finite Real a and a rational or algebraic b > 0."""
    require(not a.inf and not b.inf and b.compare(Real.rational(0)) > 0, "quotient needs finite a and b > 0")
    if b.poly is None:
        if a.poly is None:
            return Real.rational(a.q / b.q)
        return scaled(a, 1 / b.q)
    if a.poly is None:
        if a.q == 0:
            return Real.rational(0)
        while b.poly is not None and b.lo <= 0:
            b.bisect()
        if b.poly is None:
            return quotient(a, b)
        # b root of p  =>  a/b root of x^d p(a/x)
        rev = list(reversed(b.poly))
        poly = polys.squarefree([c / a.q ** k for k, c in enumerate(rev)])
        lo, hi = sorted((a.q / b.hi, a.q / b.lo))
        return Real.algebraic(poly, lo, hi, "quotient")
    for x in (a, b):
        while x.poly is not None and x.lo <= 0:
            x.bisect()
    if a.poly is None or b.poly is None:
        return quotient(a, b)
    t = polys.squarefree(resultants.quotient_polynomial(a.poly, b.poly))
    for _ in range(MAX_REFINEMENTS):  # refine a and b until their quotient's enclosure isolates one root of t
        if a.poly is None or b.poly is None:
            return quotient(a, b)
        lo, hi = a.lo / b.hi, a.hi / b.lo
        if evaluate(t, lo) != 0 and evaluate(t, hi) != 0 and polys.count_roots(t, lo, hi) == 1:
            return Real._made(t, lo, hi)
        a.bisect()
        b.bisect()
    raise CheckFailure("could not isolate a quotient of two algebraic numbers")


def divides(b: Sequence[int], a: Sequence[int]) -> bool:
    """Does the primitive integer polynomial b divide the primitive integer polynomial a over Q?  By Gauss's
    lemma the quotient is then integral, so integer long division with every leading quotient exact decides it;
    each step is charged by the sizes of its numbers.  Both with degree >= 1."""
    if len(b) > len(a):
        return False
    a = list(a)
    lead_bits = abs(b[-1]).bit_length()
    for shift in range(len(a) - len(b), -1, -1):
        c, rest = divmod(a[shift + len(b) - 1], b[-1])
        if rest:
            return False
        charge(remainder_step_cost(len(b), lead_bits + abs(c).bit_length(), max(abs(a[shift + len(b) - 1]).bit_length(),
                                                                                  1)), "an exact polynomial division")
        if c:
            for k, bk in enumerate(b):
                a[k + shift] -= c * bk
    return not any(a)
