"""The poles of r = g/h seen from -kappa: dominance, ties and the tail index (paper, Section 3.2).

For j > deg g - deg h the Taylor coefficients of r at -kappa are

    c_j(kappa) = sum_k sum_{m=1..M_k} b_{k,m} C(j+m-1, m-1) (z_k + kappa)^(-(m+j)),   b_{k,m} = (-1)^m a_{k,m},

a linear recurrence with characteristic roots 1/(z_k + kappa).  With p* the smallest positive pole
(multiplicity mu), another pole z_k = a + ib with a < p* is as close to -kappa as p* exactly at

    kappa_k = (a^2 + b^2 - p*^2) / (2 (p* - a))                 (|z_k + kappa| = p* + kappa),

and strictly closer beyond it.  kappa_A = min_k kappa_k is an algebraic number: every kappa_k is a
root of the *tie polynomial*

    T(kappa) = Res_x(P2_kappa, G_kappa) Res_x(G_kappa, G_kappa'),   G_kappa: roots w_l^2,
                                                                     P2_kappa: roots w_i w_j (i < j),

w_l = z_l + kappa the roots of h(w - kappa) (squarefree part).  A tie of a non-real pole is
w_i w_j = |w_i|^2 = w*^2 (first factor), of a negative real pole w_i^2 = w*^2 (the discriminant of G).
T is never identically 0 ((z_i + kappa)(z_j + kappa) = (z_l + kappa)^2 or (z_i + kappa)^2 =
(z_l + kappa)^2 for all kappa force equal poles), so kappa_A is isolated exactly among T's real roots.

Everything here is the engine's (FLINT Arb balls, exact FLINT polynomials); the kernel re-proves it.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from math import comb

import flint

from exactinv_check.format import MAX_TAIL_INDEX

from ..core.flintq import dyadic_of, fmpq_of
from ..core.polys import integer_part, interpolate
from ..core.real_algebraic import RealAlgebraic
from ..core.roots import real_roots
from ..errors import Undecided

__all__ = ["PoleStructure", "pole_structure", "ambiguous_line_poles", "tie_polynomial", "Tie", "dominance_tie", "tail_index"]

_MAX_INDEX = MAX_TAIL_INDEX  # the kernel's bound on a tail index


class precision:
    """Arb working precision (bits) inside a ``with`` block.

    >>> with precision(100):
    ...     flint.ctx.prec
    100
    """

    def __init__(self, bits: int):
        self.bits = bits

    def __enter__(self):
        self.saved = flint.ctx.prec
        flint.ctx.prec = self.bits

    def __exit__(self, *exc):
        flint.ctx.prec = self.saved


@dataclass(frozen=True)
class PoleStructure:
    """The poles of r (Arb balls, multiplicities, b_{k,m} balls) and the index ``star`` of p*."""

    balls: tuple
    star: int
    mu: int
    on_line: frozenset = frozenset()  # poles proved to be p* + iy, y != 0 (exactinv.monotonicity.line_poles)


def _acb(q: Fraction) -> flint.acb:
    return flint.acb(flint.arb(fmpq_of(q)))


def _taylor_at(coeffs: list, z: flint.acb) -> list:
    """p(z + w) = sum_j t_j w^j (repeated Horner)."""
    c = list(coeffs)
    d = len(c) - 1
    for i in range(d):
        for k in range(d - 1, i - 1, -1):
            c[k] = c[k] + z * c[k + 1]
    return c


def pole_structure(numerator, denominator, p_star) -> PoleStructure:
    """Every pole z_k of r = g/h (Arb ball), its multiplicity M and b_{k,m} = (-1)^m a_{k,m}, m = 1..M,
    of r = q + sum a_{k,m} (z - z_k)^(-m); ``star`` holds the exact pole p* (Fraction or RealAlgebraic).

    >>> from fractions import Fraction as F
    >>> with precision(128):
    ...     s = pole_structure([F(1)], [F(1), F(-1)], F(1))     # 1/(1 - z) = -1/(z - 1): b_1 = 1
    >>> s.mu, s.balls[0][2][0].real.mid() == 1
    (1, True)
    """
    g = [_acb(c) for c in numerator]
    h = [_acb(c) for c in denominator]
    hq = flint.fmpq_poly([fmpq_of(c) for c in denominator])
    _, factors = integer_part(hq).factor()
    balls = []
    for p, M in factors:
        for z, _ in p.complex_roots():
            tg, th = _taylor_at(g, z), _taylor_at(h, z)[M:]
            if th[0].contains(0):
                raise Undecided("a pole's leading Taylor coefficient could not be separated from 0")
            phi = []
            for i in range(M):
                acc = tg[i] if i < len(tg) else flint.acb(0)
                for t in range(1, min(i, len(th) - 1) + 1):
                    acc -= th[t] * phi[i - t]
                phi.append(acc / th[0])
            balls.append((z, int(M), [phi[M - m] * (-1) ** m for m in range(1, M + 1)]))
    lo, hi = (p_star.lower, p_star.upper) if isinstance(p_star, RealAlgebraic) else (p_star, p_star)
    for k, (z, M, _) in enumerate(balls):
        if z.imag.is_zero() and dyadic_of(z.real.lower()) <= hi and lo <= dyadic_of(z.real.upper()):
            return PoleStructure(tuple(balls), k, M)
    raise Undecided("could not match the smallest positive pole to its Arb enclosure")


def ambiguous_line_poles(s: PoleStructure) -> list[int]:
    """The non-real poles (not yet proved on the line) whose real part Arb cannot separate from p*'s.

    >>> from fractions import Fraction as F
    >>> with precision(128):                                   # poles 1, 1 +- i
    ...     len(ambiguous_line_poles(pole_structure([F(1)], [F(1), F(-2), F(3, 2), F(-1, 2)], F(1))))
    2
    """
    p = s.balls[s.star][0].real
    return [k for k, (z, _, _) in enumerate(s.balls)
            if k != s.star and k not in s.on_line and not z.imag.is_zero() and not z.real > p and not z.real < p]


# ------------------------------------------------------------------ ties
def _power_sums(monic: list, count: int) -> list:
    """s_1..s_count of the roots of the monic polynomial (coefficients low to high), Newton's identities."""
    d = len(monic) - 1
    e = [(-1) ** k * monic[d - k] for k in range(d + 1)]  # elementary symmetric functions
    s = [0] * (count + 1)
    for k in range(1, count + 1):
        acc = (-1) ** (k - 1) * k * e[k] if k <= d else 0
        for i in range(1, min(k - 1, d) + 1):
            acc += (-1) ** (i - 1) * e[i] * s[k - i]
        s[k] = acc
    return s[1:]


def _from_power_sums(s: list, d: int) -> list:
    """The monic polynomial of degree d (low to high) whose roots have the power sums s_1..s_d."""
    e = [fmpq_of(1)]
    for k in range(1, d + 1):
        e.append(sum(((-1) ** (i - 1) * e[k - i] * s[i - 1] for i in range(1, k + 1)), fmpq_of(0)) / k)
    return [(-1) ** (d - i) * e[d - i] for i in range(d + 1)]


def _tie_value(h: flint.fmpq_poly, kappa: int) -> flint.fmpq:
    q = h(flint.fmpq_poly([-kappa, 1]))  # roots w = z + kappa
    c = [x / q.coeffs()[-1] for x in q.coeffs()]
    d = len(c) - 1
    n2 = d * (d - 1) // 2
    s = _power_sums(c, 2 * max(n2, d))
    pairs = [(s[k - 1] ** 2 - s[2 * k - 1]) / 2 for k in range(1, n2 + 1)]  # power sums of {w_i w_j : i < j}
    P2 = flint.fmpq_poly(_from_power_sums(pairs, n2)) if n2 else flint.fmpq_poly([1])
    G = flint.fmpq_poly(_from_power_sums([s[2 * k - 1] for k in range(1, d + 1)], d))
    return P2.resultant(G) * G.resultant(G.derivative())


def tie_polynomial(h: flint.fmpq_poly) -> flint.fmpq_poly:
    """T(kappa): its real roots contain every kappa at which a pole of r is exactly as far from -kappa as
    another (module docstring); computed by exact interpolation at integer kappa.

    >>> tie_polynomial(flint.fmpq_poly([2, -2, 1])).degree() >= 1    # h = z^2 - 2z + 2, poles 1 +- i
    True
    """
    sq = integer_part(h)
    sq = sq // sq.gcd(sq.derivative())
    d = sq.degree()
    if d < 2:
        return flint.fmpq_poly([1])
    n2 = d * (d - 1) // 2
    degree = 2 * n2 * d + 2 * d * (d - 1)
    hq = flint.fmpq_poly(sq)
    points = list(range(degree + 1))
    return interpolate(points, [_tie_value(hq, t) for t in points])


@dataclass(frozen=True)
class Tie:
    """kappa_A (exact) and the poles that reach p*'s distance from -kappa exactly there."""

    kappa: object
    tied: tuple


def _tie_balls(s: PoleStructure) -> list:
    """[(k, kappa_k ball, exact)] for every pole that gets as close to -kappa as p* for some kappa;
    exact = False marks a lower bound only (real part not separated from p*)."""
    p = s.balls[s.star][0].real
    out = []
    for k, (z, _, _) in enumerate(s.balls):
        a, b = z.real, z.imag
        if k == s.star or (b.is_zero() and a > 0) or a > p or k in s.on_line:
            continue  # p* is the smallest positive pole; Re z >= p* (exactly, on the line) never gets closer
        if a < p:
            out.append((k, (a * a + b * b - p * p) / (2 * (p - a)), True))
        else:  # Re z = p* to working precision: kappa_k >= b^2 / (2 |p - a|) - p - |a| is huge
            gap = flint.arb((p - a).mid().abs_upper() + (p - a).rad() + flint.arb(2) ** (-flint.ctx.prec))
            out.append((k, flint.arb((b * b / (2 * gap) - p - abs(a)).lower()), False))
    return out


def dominance_tie(s: PoleStructure, h: flint.fmpq_poly, exact: bool = True) -> Tie | None:
    """kappa_A = min kappa_k and the tied poles; None when no pole ever gets as close to -kappa as p*.
    ``exact``: kappa_A as the root of :func:`tie_polynomial` (else an Arb ball).  Undecided when the
    balls cannot be separated.

    >>> from fractions import Fraction as F
    >>> from exactinv.model.methods import pade
    >>> m = pade(2, 3)                     # Radau IIA 3: p* = 3.6378..., a complex pair
    >>> p = RealAlgebraic.from_isolating_interval([-60, 36, -9, 1], F(36, 10), F(37, 10))
    >>> with precision(256):
    ...     tie = dominance_tie(pole_structure(m.numerator, m.denominator, p), m.h)
    >>> tie.kappa.poly, len(tie.tied)      # kappa_A: the root of 2k^3 + 9k^2 - 36 near 1.703
    (2*x^3 + 9*x^2 + (-36), 2)
    """
    values = _tie_balls(s)
    if not values:
        return None
    lowest = min(values, key=lambda v: v[1].upper())
    cluster = [v for v in values if not v[1].lower() > lowest[1].upper()]
    if not all(exact for _, _, exact in cluster):
        raise Undecided("a non-real pole's real part is not separated from p*'s, and it is not proved to equal it "
                        "(exactinv.monotonicity.line_poles)")
    lo = min(dyadic_of(v[1].lower()) for v in cluster)
    hi = max(dyadic_of(v[1].upper()) for v in cluster)
    if any(not v[1].lower() > flint.arb(fmpq_of(hi)) for v in values if v not in cluster):
        raise Undecided("two equal-modulus conditions could not be separated at working precision")
    if not exact:
        return Tie(flint.arb(fmpq_of((lo + hi) / 2), fmpq_of((hi - lo) / 2)), tuple(k for k, _, _ in cluster))
    roots = [r for r, _ in real_roots(tie_polynomial(h)) if lo <= r <= hi]
    if len(roots) != 1:
        raise Undecided("the tie polynomial has several roots where kappa_A lies (refine the precision)")
    return Tie(roots[0], tuple(k for k, _, _ in cluster))


# ------------------------------------------------------------------ tail index
def _R(j: int, m: int, mu: int) -> flint.arb:
    return flint.arb(fmpq_of(Fraction(comb(j + m - 1, m - 1), comb(j + mu - 1, mu - 1))))


def _ratio_bound(z: flint.acb, p: flint.arb, K: Fraction) -> flint.arb:
    """An upper bound Q of (p + kappa)/|z + kappa| over kappa in [0, K]: the larger of the two end
    values.  If Q < 1, Q^2 |z + kappa|^2 - (p + kappa)^2 is concave in kappa (leading coefficient
    Q^2 - 1 < 0), so nonnegative at both ends means nonnegative on [0, K]."""
    ends = [(p + flint.arb(fmpq_of(k))) / abs(z + flint.acb(flint.arb(fmpq_of(k)))) for k in (Fraction(0), K)]
    return flint.arb(ends[0].upper() if ends[0].upper() > ends[1].upper() else ends[1].upper())


def tail_index(s: PoleStructure, K: Fraction, first: int, tied: tuple = ()) -> int:
    """An index N >= first with c_j(kappa) > 0 for all j >= N and kappa in [0, K] (the kernel's
    dominance bound, exactinv_check.tail).  Poles in ``tied`` are at most as close as p* on [0, K]
    (K <= kappa_A): they enter with ratio Q = 1 and must have multiplicity <= mu.

    >>> from fractions import Fraction as F
    >>> with precision(128):                # trapezoid: one pole, c_j > 0 for j >= 1 on [0, 2]
    ...     tail_index(pole_structure([F(1), F(1, 2)], [F(1), F(-1, 2)], F(2)), F(2), first=1)
    1
    """
    z_star, mu, b_star = s.balls[s.star]
    p = z_star.real
    b_mu = b_star[mu - 1].real
    if not b_mu > 0:
        raise Undecided("the dominant principal part could not be certified positive")
    D_max = p + flint.arb(fmpq_of(K))
    others = []
    for k, (z, M, b) in enumerate(s.balls):
        if k == s.star:
            continue
        Q = flint.arb(1) if k in tied else _ratio_bound(z, p, K)
        if k not in tied and not Q < 1:
            raise Undecided("the tail bound needs p* to dominate every other pole on [0, K]")
        others.append((Q, M, [abs(v) for v in b], k in tied))
    start = max(first, 1)
    for Q, M, _, is_tied in others:
        if M > mu and not is_tied:
            need = (M * Q - mu) / (1 - Q)
            while not flint.arb(start) >= need:
                start *= 2
    N = start
    while not _bound_below(s, others, D_max, N, b_mu):
        N *= 2
        if N > _MAX_INDEX:
            raise Undecided(f"no tail index below {_MAX_INDEX} could be certified (p* dominates too weakly)")
    return _least(N, start, lambda n: _bound_below(s, others, D_max, n, b_mu))


def _bound_below(s: PoleStructure, others, D_max, N: int, b_mu) -> bool:
    z_star, mu, b_star = s.balls[s.star]
    p = z_star.real
    E = flint.arb(0)
    for m in range(1, mu):
        E += abs(b_star[m - 1]) * _R(N, m, mu) * D_max ** (mu - m)
    for Q, M, b, _ in others:
        for m in range(1, M + 1):
            scale = D_max ** (mu - m) if mu >= m else p ** (mu - m)
            E += b[m - 1] * _R(N, m, mu) * scale * Q ** (m + N)
    return bool(E < b_mu)


def _least(good: int, start: int, ok) -> int:
    """The least n in [start, good] with ok(n), by bisection (ok is monotone for n >= start)."""
    if ok(start):
        return start
    bad = start
    while good - bad > 1:
        mid = (bad + good) // 2
        bad, good = (bad, mid) if ok(mid) else (mid, good)
    return good
