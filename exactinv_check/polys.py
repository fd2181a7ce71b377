"""Polynomials over Q, coefficient lists from x^0 up, and their real roots.

Real roots are isolated by Descartes' rule of signs with bisection (the
Vincent-Collins-Akritas method) on squarefree integer polynomials: after the
Moebius map (0, oo) -> (a, b), zero sign variations prove no root in the open
(a, b), one proves exactly one (and a simple one), and bisection at rational
midpoints (each tested for being a root) makes every interval of a squarefree
polynomial end with 0 or 1.  Each node costs O(d^2) integer additions -- no
pseudo-remainder sequence, so it is far cheaper than Sturm sequences at high
degree -- and is charged to the certificate's account as it runs
(:mod:`exactinv_check.budget`).  The squarefree part is proved by a gcd modulo
a prime when it is the polynomial itself (the usual case), else computed by a
priced pseudo-remainder sequence.  Sturm sequences remain for the callers that
need exact counts on many intervals of one polynomial.  No tolerance, no float.

One concept: real roots.  The arithmetic of Q[x] is :mod:`exactinv_check.poly_arithmetic` and the
resultants and interpolation are :mod:`exactinv_check.resultants`; every caller imports a name from the
module that defines it (none is re-exported here).
"""

from __future__ import annotations

from fractions import Fraction
from math import gcd as _igcd
from math import isqrt
from typing import Any, Iterator, Sequence

from .budget import (
    MAX_ALGEBRAIC_DEGREE,
    STURM_BUDGET,
    WORK_BUDGET,
    active,
    affordable,
    charge,
    descartes_node_cost,
    evaluation_cost,
    modular_squarefree_cost,
    within_sturm_budget,
)
from .budget import MAX_ROOT_BISECTIONS as MAX_BISECTIONS
from .budget import memo as _memo
from .failure import require, require_budget
from .poly_arithmetic import (
    bounded,
    content_free,
    exact_quotient,
    gcd,
    integer_coefficients,
    integer_derivative,
    integer_gcd,
    pseudo_remainder,
    sign,
    strip_zero_roots,
    trim,
)

_PRIMES = (2**61 - 1, 2**31 - 1, 1000000007)  # for the modular squarefree test


def sign_at(ints: Sequence[int], x: Any, bits: int | None = None) -> Any:
    """The sign of the integer polynomial ints at the rational x, in integer arithmetic
    (the homogenised value sum c_k n^k d^(D-k) with x = n/d, d > 0).  Charged by ``bits``, the largest
    coefficient's bits when the caller knows them (a certificate's algebraic number, :class:`reals.Real`), else
    found here (a linear scan): a degree-200 polynomial with 4000-digit middle coefficients and ends 1 was
    charged 15 times low (9e3 word operations for 4.4 ms), 63 bisections between two readings of the clock; priced
    by the leading coefficient's bits, a degree-250 polynomial with lead 1 and 13000-bit middle coefficients at
    62-bit points (isolate's ends, Real.claimed's) was charged 12 times low (red team rt-budget2)."""
    n, d = x.numerator, x.denominator
    if not ints:  # the zero polynomial
        return 0
    if active():
        bits = max(abs(c).bit_length() for c in ints) if bits is None else bits
        charge(evaluation_cost(len(ints) - 1, bits, max(abs(n).bit_length(), d.bit_length())),
               "a sign of a polynomial at a rational")
    acc, power = 0, 1
    for c in ints:  # low to high: acc = sum_{k<=i} c_k n^k d^(i-k), rescaled as i grows
        acc = acc * d + c * power
        power *= n
    return (acc > 0) - (acc < 0)


def descartes_variations(ints: Sequence[int], a: Any, b: Any) -> int:
    """Sign variations of (1+x)^D q(1/(1+x)), q(y) = p(a + (b - a) y): an upper bound,
    of the same parity, on the number of roots of p in the open (a, b) (Descartes'
    rule after the Moebius map (0, oo) -> (a, b)).  Integer arithmetic throughout."""
    D = len(ints) - 1
    w = b - a
    if D < 1:  # a constant: no root, no variation
        return 0
    s = a.denominator * w.denominator
    u, v = a.numerator * w.denominator, w.numerator * a.denominator  # a + w y = (u + v y) / s
    if active():  # charged by the largest coefficient (not the ends': big middle coefficients cost too)
        stride = max(abs(u).bit_length(), v.bit_length(), s.bit_length())  # each Horner step grows q by this
        charge(descartes_node_cost(D, max(abs(c).bit_length() for c in ints) + D * stride, stride),
               "root isolation (Descartes' rule)")
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


def no_root_in(p: Sequence[int | Fraction], T: Fraction, depth: int = 4) -> bool:
    """True proves that p has no root in the open (0, T): Descartes' rule on (0, T),
    on halves where it is inconclusive, up to depth times.  False says nothing."""
    return no_root_between(p, Fraction(0), Fraction(T), depth)


def no_root_between(p: Sequence[int | Fraction], a: Fraction, b: Fraction, depth: int = 4) -> bool:
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


def _affordable(ints: Sequence[int]) -> Any:
    """Reject, before any pseudo-remainder sequence, an integer polynomial whose
    degree^4 * bits^2 (the cost of its gcd or Sturm sequence) is over the budget,
    or more than the certificate has left, whether a certificate wrote it or the kernel built it."""
    bits = max((abs(c).bit_length() for c in ints), default=0)
    within_sturm_budget(len(ints) - 1, bits, "root isolation")
    return ints


def affordable_gcd(p: Any, q: Any) -> Any:
    """gcd(p, q) over Q (monic), priced first: the common denominator of each is built with a
    running bound on its size (at most the bits degree^4 bits^2 <= STURM_BUDGET allows), then
    each integer polynomial is priced by :func:`_affordable` -- so no certificate's coefficients
    can make the content or the pseudo-remainder sequence run for minutes."""
    for r in (trim(p), trim(q)):
        limit = isqrt(STURM_BUDGET // max(1, (len(r) - 1) ** 4))
        den = 1
        for c in r:
            den = den * c.denominator // _igcd(den, c.denominator)
            require_budget(den.bit_length() <= limit, f"over the kernel's work budget: a polynomial of degree "
                    f"{len(r) - 1} whose coefficients' common denominator passes {limit} bits")
        _affordable(integer_coefficients(r))
    return gcd(p, q)


def squarefree(p: Sequence[int | Fraction]) -> Any:
    """The squarefree part p / gcd(p, p') as coprime integers, with p's leading sign.

    p itself when a gcd modulo a prime proves it squarefree (if p = f^2 g over Z with
    deg f >= 1 and the prime does not divide lc(p), f mod the prime has f's degree and
    divides both p and p' there, so their gcd there is not constant); else the priced
    pseudo-remainder sequence.  Within a certificate each polynomial's part is computed once."""
    a = integer_coefficients(bounded(trim(p), MAX_ALGEBRAIC_DEGREE))
    if len(a) <= 2:
        return a
    return list(_memo(("squarefree", tuple(a)), lambda: _squarefree_integers(a)))


def _squarefree_integers(a: Any) -> Any:
    if is_squarefree_mod_prime(a):
        return a
    g = integer_gcd(_affordable(a), integer_derivative(a))
    return exact_quotient(a, g) if len(g) > 1 else a


def is_squarefree_mod_prime(a: Sequence[int]) -> bool:
    """True proves the integer polynomial a (degree >= 1) squarefree over Q: gcd(a, a') = 1
    modulo a prime not dividing its leading coefficient (see :func:`squarefree`).  False
    says nothing (a may be squarefree and every prime tried unlucky)."""
    charge(modular_squarefree_cost(len(a) - 1, max(abs(c).bit_length() for c in a)), "a modular squarefree test")
    for prime in _PRIMES:
        if a[-1] % prime == 0:
            continue
        f = [c % prime for c in a]
        df = [k * f[k] % prime for k in range(1, len(f))]
        return len(_gcd_mod(f, df, prime)) == 1
    return False


def _trim_mod(f: Any) -> Any:
    while f and f[-1] == 0:
        f.pop()
    return f


def _gcd_mod(f: Any, g: Any, prime: Any) -> Any:
    """The gcd of f and g over the integers modulo a prime (Euclid; a constant: [1])."""
    f, g = _trim_mod(list(f)), _trim_mod(list(g))
    while g:
        inv = pow(g[-1], -1, prime)
        while len(f) >= len(g) and f:
            c, shift = f[-1] * inv % prime, len(f) - len(g)
            for k, x in enumerate(g):
                f[k + shift] = (f[k + shift] - c * x) % prime
            _trim_mod(f)
        f, g = g, f
    return f


def isolate(q: Sequence[int], a: Fraction, b: Fraction) -> list[tuple[Fraction, Fraction]]:
    """The real roots of the squarefree integer polynomial q in the open (a, b), a < b, in
    increasing order: (lo, hi) with exactly one root in the open (lo, hi) and none at lo or hi,
    or (r, r) for a rational root r -- by Descartes' rule with bisection (see the module
    docstring).  Priced by its nodes, not by a cap on degree^4 bits^2 (issue 22: the gate DESCARTES_BUDGET
    refused a genuine rho of degree 272 with 1044-bit coefficients, isolated in about a second): one node must
    fit in what the certificate has left, then each is charged to the certificate's account as it runs (at
    budget.RATE, calibrated); the number of nodes is bounded."""
    return list(isolate_ascending(q, a, b))


def isolate_ascending(q: Sequence[int], a: Fraction, b: Fraction) -> Iterator[tuple[Fraction, Fraction]]:
    """:func:`isolate`'s roots one at a time, in increasing order (depth first, the left half first, a rational
    root found at a midpoint between its two halves): a caller that needs only the first root with some property
    stops early, and the isolation of the roots beyond it is never paid for."""
    if len(q) < 2:
        return
    bits = max(abs(c).bit_length() for c in q)
    D = len(q) - 1
    node = descartes_node_cost(D, bits + D * 8, 8)  # the cheapest node: ends of a few bits
    require_budget(node <= WORK_BUDGET and affordable(node), f"over the kernel's work budget: root isolation of a "
            f"polynomial of degree {D} with {bits}-bit coefficients (one Descartes test alone costs {node:.2e} word "
            "operations, more than the certificate has left)")
    stack: list[tuple[Fraction, Fraction, bool]] = [(Fraction(a), Fraction(b), False)]
    nodes = 0
    while stack:
        lo, hi, root = stack.pop()
        if root:  # a rational root, between the two halves
            yield lo, hi
            continue
        nodes += 1
        require(nodes <= MAX_BISECTIONS * len(q), "root isolation does not terminate (is the polynomial squarefree?)")
        v = descartes_variations(q, lo, hi)  # charged there
        if v == 0:
            continue
        if v == 1 and sign_at(q, lo, bits) != 0 and sign_at(q, hi, bits) != 0:
            yield lo, hi  # an end that is a root (a midpoint found exactly): bisect on, away from it
            continue
        m = (lo + hi) / 2
        stack.append((m, hi, False))
        if sign_at(q, m, bits) == 0:
            stack.append((m, m, True))
        stack.append((lo, m, False))


def sign_right_of(p: Sequence[int | Fraction], x: int | Fraction) -> Any:
    """The sign of p on (x, x + eps) for small eps > 0 (0 only for p = 0): the sign of
    the first nonzero derivative at x (at x = 0, of the lowest nonzero coefficient), in integers."""
    q = integer_coefficients(p)
    if x == 0:
        return next((sign(c) for c in q if c), 0)
    while q:
        s = sign_at(q, Fraction(x))
        if s:
            return s
        q = integer_derivative(q)
    return 0


class Sturm:
    """The Sturm sequence of a polynomial: exact counts of its distinct real roots."""

    def __init__(self, p: Sequence[Fraction]) -> None:
        a = _affordable(integer_coefficients(bounded(p)))
        self.p = a
        seq = [a, content_free(integer_derivative(a))] if len(a) > 1 else [a]
        while len(seq) > 1 and seq[-1]:
            seq.append([-c for c in pseudo_remainder(seq[-2], seq[-1])])
        self.ints = [s for s in seq if s]

    def _variations_at(self, x: Fraction) -> int:
        if x is None:  # +oo
            signs = [s[-1] > 0 for s in self.ints]
        else:
            signs = [v > 0 for v in (sign_at(s, x) for s in self.ints) if v]
        return sum(1 for a, b in zip(signs, signs[1:]) if a != b)

    def count(self, a: Fraction, b: Fraction) -> int:
        """Distinct real roots in (a, b]; b = None means +oo."""
        return self._variations_at(a) - self._variations_at(b)


def count_roots(p: Sequence[int | Fraction], a: Any, b: Fraction | None) -> Any:
    """Distinct real roots of p in (a, b] (b = None: +oo), by Descartes isolation of p's
    squarefree part (:func:`isolate`)."""
    if len(trim(p)) <= 1:
        return 0
    q = squarefree(p)
    if b is None:
        b = max(cauchy_bound(p), abs(Fraction(a)) + 1)
    if b <= a:
        return 0
    return len(isolate(q, a, b)) + (sign_at(q, Fraction(b)) == 0)


def cauchy_bound(p: Sequence[int | Fraction]) -> Any:
    """A power of two B (of any sign of exponent) with every complex root of p in |z| < B:
    Fujiwara's bound 2 max_i |p_(d-i)/p_d|^(1/i), each ratio bounded by bit lengths
    (|n/m| < 2^(bits(n) - bits(m) + 1)).  Unlike Cauchy's 1 + max |p_i/p_d| (the name is
    kept), it scales with the roots: roots near 10^60 or 10^-60 cost no more bisections than
    roots near 1 (issue 22: Taylor-12 on 10^-60 A was rejected over the budget).
    The zero polynomial and constants get 1."""
    p = trim(p)
    d = len(p) - 1
    if d < 1:
        return Fraction(1)
    lead = Fraction(p[-1])
    k = None
    for i in range(1, d + 1):
        c = Fraction(p[d - i])
        if c:
            x = abs(c / lead)
            e = x.numerator.bit_length() - x.denominator.bit_length() + 1  # x < 2^e
            bound = 1 - (-e // i)  # 1 + ceil(e / i): x^(1/i) < 2^ceil(e/i), Fujiwara's factor 2
            k = bound if k is None else max(k, bound)
    return Fraction(2) ** (0 if k is None else k)


def positive_roots(p: Sequence[int | Fraction], upper: Fraction | None = None) -> Any:
    """The distinct real roots of p in (0, upper] (upper = None: all positive roots)
    as isolating data, in increasing order: a list of (lo, hi) with lo < hi (one root
    in the open (lo, hi), none at the ends) or (q, q) for an exact rational root q.
    Descartes isolation (:func:`isolate`) of the squarefree part on (0, top), top the
    Cauchy bound (no root at or above it) or upper (tested for being a root)."""
    p = strip_zero_roots(p)
    if len(p) <= 1:
        return []
    q = squarefree(p)
    out = []
    top = cauchy_bound(p)  # every root is below the Cauchy bound
    if upper is not None and upper < top:
        top = Fraction(upper)
        if top <= 0:
            return []
        if sign_at(q, top) == 0:
            out.append((top, top))
    return isolate(q, Fraction(0), top) + out


def positive_roots_ascending(p: Sequence[int | Fraction], upper: Fraction | None = None) -> Iterator[Any]:
    """:func:`positive_roots`, one root at a time in increasing order (:func:`isolate_ascending`)."""
    p = strip_zero_roots(p)
    if len(p) <= 1:
        return
    q = squarefree(p)
    top = cauchy_bound(p)
    last = None
    if upper is not None and upper < top:
        top = Fraction(upper)
        if top <= 0:
            return
        if sign_at(q, top) == 0:
            last = (top, top)
    yield from isolate_ascending(q, Fraction(0), top)
    if last is not None:
        yield last
