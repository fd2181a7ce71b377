"""Polynomials over Q, coefficient lists from x^0 up, and their real roots.

Everything the kernel knows about roots comes from Sturm sequences: exact
counts of distinct real roots in half-open intervals, with no tolerance and no
float.  Root isolation bisects until each interval holds one root.
"""

from fractions import Fraction
from math import gcd as _igcd

from .rationals import require

MAX_DEGREE = 200  # bound on every polynomial the kernel builds from a certificate
MAX_BISECTIONS = 4000
STURM_BUDGET = 5 * 10**12  # degree^4 * bits^2 of a polynomial to isolate: up to about half a minute of gcd / Sturm work
# (measured: 1.5e12 ~ 8 s, 5e12 ~ 23 s on random polynomials); the tail polynomials of Pade(6,5) need 4e12


def trim(p):
    p = list(p)
    while p and p[-1] == 0:
        p.pop()
    return p


def degree(p):
    return len(trim(p)) - 1


def evaluate(p, x):
    acc = Fraction(0)
    for c in reversed(p):
        acc = acc * x + c
    return acc


def sign(x):
    return (x > 0) - (x < 0)


def integer_coefficients(p):
    """Coprime integers proportional to p by a positive factor (so signs agree)."""
    p = trim(p)
    den = 1
    for c in p:
        if not isinstance(c, int):
            den = den * c.denominator // _igcd(den, c.denominator)
    return _content_free([c * den if isinstance(c, int) else c.numerator * (den // c.denominator) for c in p])


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


def add(p, q):
    n = max(len(p), len(q))
    return trim([(p[i] if i < len(p) else 0) + (q[i] if i < len(q) else 0) for i in range(n)])


def sub(p, q):
    return add(p, [-c for c in q])


def scale(p, c):
    return trim([c * a for a in p])


def mul(p, q):
    if not p or not q:
        return []
    out = [Fraction(0)] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        if a:
            for j, b in enumerate(q):
                out[i + j] += a * b
    return trim(out)


def mul_integers(p, q):
    """The product of two polynomials with integer coefficients, in integers (not trimmed)."""
    out = [0] * (len(p) + len(q) - 1)
    for i, a in enumerate(p):
        if a:
            for j, c in enumerate(q):
                out[i + j] += a * c
    return out


def power(p, k):
    out = [Fraction(1)]
    for _ in range(k):
        out = mul(out, p)
    return out


def derivative(p):
    return trim([k * p[k] for k in range(1, len(p))])


def divmod_(p, d):
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


def primitive(p):
    """p scaled by a POSITIVE rational to coprime integer coefficients (sign kept)."""
    return [Fraction(c) for c in integer_coefficients(p)]


def monic(p):
    p = trim(p)
    return [Fraction(c, 1) / p[-1] for c in p] if p else p


# --------------------------------------------- integer core (Python ints, no Fractions)
def _content_free(a):
    """a divided by the positive gcd of its coefficients (signs kept)."""
    g = 0
    for c in a:
        g = _igcd(g, c)
    return [c // g for c in a] if g > 1 else a


def _pseudo_remainder(a, b):
    """r with s^k a = q b + r for s = |lc(b)| > 0: the remainder up to a POSITIVE factor,
    so signs (Sturm) and divisibility (gcd) are those of the rational remainder."""
    s, sgn = abs(b[-1]), (1 if b[-1] > 0 else -1)
    r = list(a)
    while len(r) >= len(b) and r:
        shift, c = len(r) - len(b), r[-1] * sgn
        r = [s * x for x in r]
        for k, bk in enumerate(b):
            r[k + shift] -= c * bk
        while r and r[-1] == 0:
            r.pop()
        r = _content_free(r)
    return r


def _integer_gcd(a, b):
    """gcd of two integer polynomials: primitive, positive leading coefficient."""
    while b:
        a, b = b, _pseudo_remainder(a, b)
    a = _content_free(a)
    return [-c for c in a] if a and a[-1] < 0 else a


def _exact_quotient(a, b):
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


def _integer_derivative(a):
    return [k * a[k] for k in range(1, len(a))]


def gcd(p, q):
    """The monic gcd over Q."""
    g = _integer_gcd(integer_coefficients(_bounded(p)), integer_coefficients(_bounded(q)))
    return [Fraction(c, g[-1]) for c in g] if g else []


def _bounded(p):
    require(len(p) - 1 <= MAX_DEGREE, f"a polynomial of degree {len(p) - 1} exceeds the kernel's bound {MAX_DEGREE}")
    return p


def _affordable(ints):
    """Reject, before any pseudo-remainder sequence, an integer polynomial whose
    degree^4 * bits^2 (the cost of its gcd or Sturm sequence) is over the budget,
    whether a certificate wrote it or the kernel built it."""
    bits = max((abs(c).bit_length() for c in ints), default=0)
    require((len(ints) - 1) ** 4 * bits ** 2 <= STURM_BUDGET,
            f"over the kernel's work budget: root isolation of a polynomial of degree {len(ints) - 1} "
            f"with {bits}-bit coefficients (degree^4 bits^2 > {STURM_BUDGET:.0e})")
    return ints


def squarefree(p):
    """The squarefree part p / gcd(p, p') as coprime integers, with p's leading sign."""
    a = integer_coefficients(_bounded(trim(p)))
    if len(a) <= 2:
        return a
    g = _integer_gcd(_affordable(a), _integer_derivative(a))
    return _exact_quotient(a, g) if len(g) > 1 else a


def strip_zero_roots(p):
    p = trim(p)
    while p and p[0] == 0:
        p = p[1:]
    return p


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


def resultant(f, g):
    """The resultant of f and g over Q (Euclid's algorithm on the defining identity
    res(f, g) = lc(g)^deg f * prod_{g(b)=0} f(b))."""
    f, g = trim(f), trim(g)
    if not f or not g:
        return Fraction(0)
    result = Fraction(1)
    while len(g) > 1:
        df, dg = len(f) - 1, len(g) - 1
        r = divmod_(f, g)[1]
        if not r:
            return Fraction(0)
        dr = len(r) - 1
        # res(f, g) = (-1)^(df dg) res(g, f) = (-1)^(df dg) lc(g)^(df - dr) res(g, r)
        result *= (-1) ** (df * dg) * g[-1] ** (df - dr)
        f, g = g, r
    return result * g[0] ** (len(f) - 1)


def interpolate(points, values):
    """The polynomial of degree < len(points) through (points, values) (Newton form)."""
    k = len(points)
    coef = list(values)
    for level in range(1, k):
        for i in range(k - 1, level - 1, -1):
            coef[i] = (coef[i] - coef[i - 1]) / (points[i] - points[i - level])
    result = [coef[-1]] if coef else []
    for i in range(k - 2, -1, -1):
        result = add(mul(result, [-points[i], Fraction(1)]), [coef[i]])
    return trim(result)


def quotient_polynomial(p, q):
    """A nonzero polynomial in t vanishing at a/b for every root a of p and b != 0 of q:
    res_y(p(t y), q(y)), by evaluation and interpolation."""
    p, q = strip_zero_roots(p), strip_zero_roots(q)
    dp, dq = len(p) - 1, len(q) - 1
    require(dp * dq <= MAX_DEGREE, "the quotient of two algebraic numbers has too large a degree for this kernel")
    # T = 0 would drop the degree of p(T y) and, with it, the resultant's formal
    # degree: interpolate at T = 1 .. dp dq + 1 only
    points = [Fraction(k) for k in range(1, dp * dq + 2)]
    values = [resultant([c * t ** k for k, c in enumerate(p)], q) for t in points]
    return interpolate(points, values)
