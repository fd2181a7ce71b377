"""Polynomials over Q, coefficient lists from x^0 up, and their real roots.

Everything the kernel knows about roots comes from Sturm sequences: exact
counts of distinct real roots in half-open intervals, with no tolerance and no
float.  Root isolation bisects until each interval holds one root.

The arithmetic (:mod:`exactinv_check.poly_arithmetic`) and the resultants
(:mod:`exactinv_check.resultants`) are re-exported here: the kernel reaches
every polynomial function as ``polys.<name>``.
"""

from fractions import Fraction
from math import gcd as _igcd, isqrt

from .poly_arithmetic import (  # noqa: F401 (the arithmetic, re-exported: its old home)
    MAX_DEGREE,
    _bounded,
    _content_free,
    _exact_quotient,
    _integer_derivative,
    _integer_gcd,
    _pseudo_remainder,
    add,
    degree,
    derivative,
    divmod_,
    evaluate,
    gcd,
    integer_coefficients,
    monic,
    mul,
    mul_integers,
    power,
    primitive,
    scale,
    sign,
    strip_zero_roots,
    sub,
    trim,
)
from .rationals import require
from .resultants import interpolate, quotient_polynomial, resultant  # noqa: F401 (re-exported: their old home)

MAX_BISECTIONS = 4000
STURM_BUDGET = 5 * 10**12  # degree^4 * bits^2 of a polynomial to isolate: up to about half a minute of gcd / Sturm work
# (measured: 1.5e12 ~ 8 s, 5e12 ~ 23 s on random polynomials); the tail polynomials of Pade(6,5) need 4e12


def sign_at(ints, x):
    """The sign of the integer polynomial ints at the rational x, in integer arithmetic
    (the homogenised value sum c_k n^k d^(D-k) with x = n/d, d > 0)."""
    n, d = x.numerator, x.denominator
    acc, power = 0, 1
    for c in ints:  # low to high: acc = sum_{k<=i} c_k n^k d^(i-k), rescaled as i grows
        acc = acc * d + c * power
        power *= n
    return (acc > 0) - (acc < 0)


def descartes_variations(ints, a, b):
    """Sign variations of (1+x)^D q(1/(1+x)), q(y) = p(a + (b - a) y): an upper bound,
    of the same parity, on the number of roots of p in the open (a, b) (Descartes'
    rule after the Moebius map (0, oo) -> (a, b)).  Integer arithmetic throughout."""
    D = len(ints) - 1
    w = b - a
    s = a.denominator * w.denominator
    u, v = a.numerator * w.denominator, w.numerator * a.denominator  # a + w y = (u + v y) / s
    q = [ints[-1]]
    for k in range(D - 1, -1, -1):  # Horner: q <- q (u + v y) + c_k s^(D-k)
        q = [u * q[0]] + [u * q[i] + v * q[i - 1] for i in range(1, len(q))] + [v * q[-1]]
        q[0] += ints[k] * s ** (D - k)
    q.reverse()  # x^D q(1/x)
    for i in range(D):  # Taylor shift x -> x + 1
        for k in range(D - 1, i - 1, -1):
            q[k] += q[k + 1]
    signs = [c > 0 for c in q if c]
    return sum(1 for x, y in zip(signs, signs[1:]) if x != y)


def no_root_in(p, T, depth=4):
    """True proves that p has no root in the open (0, T): Descartes' rule on (0, T),
    on halves where it is inconclusive, up to depth times.  False says nothing."""
    return no_root_between(p, Fraction(0), Fraction(T), depth)


def no_root_between(p, a, b, depth=4):
    """True proves that p has no root in the open (a, b), a < b: Descartes' rule on (a, b),
    on halves where it is inconclusive, up to depth times.  False says nothing."""
    ints = integer_coefficients(p)
    stack = [(Fraction(a), Fraction(b), depth)]
    while stack:
        a, b, left = stack.pop()
        if descartes_variations(ints, a, b) == 0:
            continue
        m = (a + b) / 2
        if left == 0 or sign_at(ints, m) == 0:
            return False
        stack += [(a, m, left - 1), (m, b, left - 1)]
    return True


def _affordable(ints):
    """Reject, before any pseudo-remainder sequence, an integer polynomial whose
    degree^4 * bits^2 (the cost of its gcd or Sturm sequence) is over the budget,
    whether a certificate wrote it or the kernel built it."""
    bits = max((abs(c).bit_length() for c in ints), default=0)
    require((len(ints) - 1) ** 4 * bits ** 2 <= STURM_BUDGET,
            f"over the kernel's work budget: root isolation of a polynomial of degree {len(ints) - 1} "
            f"with {bits}-bit coefficients (degree^4 bits^2 > {STURM_BUDGET:.0e})")
    return ints


def affordable_gcd(p, q):
    """gcd(p, q) over Q (monic), priced first: the common denominator of each is built with a
    running bound on its size (at most the bits degree^4 bits^2 <= STURM_BUDGET allows), then
    each integer polynomial is priced by :func:`_affordable` -- so no certificate's coefficients
    can make the content or the pseudo-remainder sequence run for minutes."""
    for r in (trim(p), trim(q)):
        limit = isqrt(STURM_BUDGET // max(1, (len(r) - 1) ** 4))
        den = 1
        for c in r:
            den = den * c.denominator // _igcd(den, c.denominator)
            require(den.bit_length() <= limit, f"over the kernel's work budget: a polynomial of degree "
                    f"{len(r) - 1} whose coefficients' common denominator passes {limit} bits")
        _affordable(integer_coefficients(r))
    return gcd(p, q)


def squarefree(p):
    """The squarefree part p / gcd(p, p') as coprime integers, with p's leading sign."""
    a = integer_coefficients(_bounded(trim(p)))
    if len(a) <= 2:
        return a
    g = _integer_gcd(_affordable(a), _integer_derivative(a))
    return _exact_quotient(a, g) if len(g) > 1 else a


def sign_right_of(p, x):
    """The sign of p on (x, x + eps) for small eps > 0 (0 only for p = 0): the sign of
    the first nonzero derivative at x (at x = 0, of the lowest nonzero coefficient), in integers."""
    q = integer_coefficients(p)
    if x == 0:
        return next((sign(c) for c in q if c), 0)
    while q:
        s = sign_at(q, Fraction(x))
        if s:
            return s
        q = _integer_derivative(q)
    return 0


class Sturm:
    """The Sturm sequence of a polynomial: exact counts of its distinct real roots."""

    def __init__(self, p):
        a = _affordable(integer_coefficients(_bounded(p)))
        self.p = a
        seq = [a, _content_free(_integer_derivative(a))] if len(a) > 1 else [a]
        while len(seq) > 1 and seq[-1]:
            seq.append([-c for c in _pseudo_remainder(seq[-2], seq[-1])])
        self.ints = [s for s in seq if s]

    def _variations_at(self, x):
        if x is None:  # +oo
            signs = [s[-1] > 0 for s in self.ints]
        else:
            signs = [v > 0 for v in (sign_at(s, x) for s in self.ints) if v]
        return sum(1 for a, b in zip(signs, signs[1:]) if a != b)

    def count(self, a, b):
        """Distinct real roots in (a, b]; b = None means +oo."""
        return self._variations_at(a) - self._variations_at(b)


def count_roots(p, a, b):
    """Distinct real roots of p in (a, b] (b = None: +oo)."""
    if len(trim(p)) <= 1:
        return 0
    return Sturm(p).count(a, b)


def cauchy_bound(p):
    """A power of two B with every real root of p in (-B, B) (Cauchy's bound, rounded
    up to a power of two so that bisection points stay dyadic and short)."""
    p = trim(p)
    bound = 1 + max(abs(Fraction(c) / p[-1]) for c in p[:-1]) if len(p) > 1 else Fraction(1)
    return Fraction(2 ** max(int(bound).bit_length(), 1))


def positive_roots(p, upper=None):
    """The distinct real roots of p in (0, upper] (upper = None: all positive roots)
    as isolating data, in increasing order: a list of (lo, hi) with lo < hi (one root
    in the open (lo, hi), none at the ends) or (q, q) for an exact rational root q."""
    p = strip_zero_roots(p)
    if len(p) <= 1:
        return []
    sturm = Sturm(squarefree(p))
    q = sturm.ints[0]
    out = []
    top = cauchy_bound(p)  # every root is below the Cauchy bound
    if upper is not None and upper < top:
        top = upper
        if sign_at(q, upper) == 0:
            out.append((upper, upper))
    stack = [(Fraction(0), top)]  # open intervals
    steps = 0
    while stack:
        a, b = stack.pop()
        steps += 1
        require(steps <= MAX_BISECTIONS * len(p), "root isolation does not terminate")
        b_root = sign_at(q, b) == 0
        k = sturm.count(a, b) - b_root  # roots in the open (a, b)
        if k == 0:
            continue
        if k == 1 and not b_root and sign_at(q, a) != 0:
            out.append((a, b))
            continue
        m = (a + b) / 2
        if sign_at(q, m) == 0:
            out.append((m, m))
        stack.append((m, b))
        stack.append((a, m))
    out.sort(key=lambda iv: iv[0])
    return out
