"""Non-real poles on the line Re z = p* for an IRRATIONAL algebraic p*, proved exactly (issue 22, item 4).

:mod:`exactinv.monotonicity.line_poles` proves a pole z = p* + iy to lie on the vertical line through the smallest
positive pole p* when p* is rational.  Here p* = alpha is a :class:`~exactinv.core.real_algebraic.RealAlgebraic`,
the root of an irreducible integer polynomial m in an isolating interval, so Q(alpha) = Q[x]/(m) is a field:
an element a(x) mod m is zero at alpha iff it is zero mod m, its inverse comes from the extended Euclid algorithm,
and its sign is exact (alpha's interval is refined until Descartes' rule proves a root-free).

With h(x + iy) = U(x, y) + i V(x, y) (the Taylor shift h(x + w) = sum_k s_k(x) w^k, w^k = (iy)^k), the line
poles alpha + iy (y real) are exactly the real roots of G = gcd(U(alpha, .), V(alpha, .)) in Q(alpha)[y], a
polynomial with real coefficients.  A pole's Arb box [a, b] x [c, d] holds one root of h; when a <= alpha <= b,
0 is not in [c, d] and G(alpha, c), G(alpha, d) differ in sign (or one is 0), G has a real root y in [c, d]
(intermediate value theorem), alpha + iy is a root of h in the box, hence the box's pole: proved on the line.
(If the box's pole is on the line it is a simple root of G -- h squarefree -- so the test succeeds once the box
is narrow enough.)  The kernel re-proves this from inclusion disks (exactinv_check.line_algebraic).
"""

from __future__ import annotations

from fractions import Fraction
from math import comb
from typing import Any

import flint

from ..core.flintq import fmpq_of
from ..core.float_hint import float_hint
from ..core.polys import integer_part, no_root_between, sign_at
from ..core.real_algebraic import RealAlgebraic
from ..core.roots import real_roots

__all__ = ["algebraic_line_gcd", "algebraic_sign", "on_line_indices_algebraic", "algebraic_pair_balance", "lines_nonnegative",
           "real_root_count"]

_MAX_REFINE = 4000  # bisections of alpha's interval for one sign (each halves the width)


def algebraic_sign(a: flint.fmpq_poly, alpha: RealAlgebraic) -> int:
    """The exact sign of a(alpha) (alpha's interval is refined in place; the number is unchanged).

    >>> r2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)          # sqrt 2
    >>> [algebraic_sign(flint.fmpq_poly(c), r2) for c in ([-7, 5], [-2, 0, 1], [3, -3])]   # 5r2 - 7, r2^2 - 2, 3 - 3r2
    [1, 0, -1]
    """
    a = a % flint.fmpq_poly(alpha.poly)
    if a.degree() <= 0:  # a constant (always, when alpha is rational: a linear polynomial)
        return 0 if a.is_zero() else (1 if a[0] > 0 else -1)
    q = integer_part(a)
    for _ in range(_MAX_REFINE):
        lo, hi = alpha.lower, alpha.upper
        s = sign_at(q, lo)
        if s != 0 and no_root_between(q, lo, hi):
            return s
        alpha.refine(max(1, (hi - lo).denominator.bit_length() - (hi - lo).numerator.bit_length() + 1))
    raise ArithmeticError("algebraic_sign: no root-free interval after many bisections (internal)")


def _parts(f: flint.fmpq_poly, m: flint.fmpq_poly) -> tuple[list, list]:
    """(U, V) with f(alpha + iy) = U(y) + i V(y), coefficients fmpq_poly in x reduced mod m."""
    c = [f[k] for k in range(f.degree() + 1)]
    x = flint.fmpq_poly([0, 1])
    s = []
    for i in range(len(c)):
        term = flint.fmpq_poly([0])
        for k in range(i, len(c)):
            term += flint.fmpq_poly([c[k] * comb(k, i)]) * x ** (k - i)
        s.append(term % m)
    zero = flint.fmpq_poly([0])
    U = [s[k] * (-1) ** (k // 2) if k % 2 == 0 else zero for k in range(len(s))]
    V = [s[k] * (-1) ** ((k - 1) // 2) if k % 2 else zero for k in range(len(s))]
    return _trim(U), _trim(V)


def _trim(P: list) -> list:
    while P and P[-1].is_zero():
        P = P[:-1]
    return P


def _monic(P: list, m: flint.fmpq_poly) -> list:
    g, s, _ = P[-1].xgcd(m)  # s P[-1] + t m = g, a nonzero constant (m irreducible, P[-1] != 0 mod m)
    inv = s / g
    return [(c * inv) % m for c in P[:-1]] + [flint.fmpq_poly([1])]


def _remainder(A: list, B: list, m: flint.fmpq_poly) -> list:
    A = list(A)
    while A and len(A) >= len(B):
        shift, c = len(A) - len(B), A[-1]
        for k, bk in enumerate(B):
            A[k + shift] = (A[k + shift] - c * bk) % m
        A = _trim(A[:-1] + [flint.fmpq_poly([0])])
    return A


def algebraic_line_gcd(h: flint.fmpq_poly, alpha: RealAlgebraic) -> list:
    """The monic G = gcd(U(alpha, .), V(alpha, .)) in Q(alpha)[y] as a list of fmpq_poly in x (mod alpha's
    polynomial), low degree first: its real roots y are exactly the roots alpha + iy of h.

    (z^2 - 2)(z^4 - 2z^2 + 9), roots +-sqrt 2 and +-sqrt 2 +- i: on Re z = sqrt 2, G = y^3 - y.

    >>> r2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> [str(c) for c in algebraic_line_gcd(flint.fmpq_poly([-18, 0, 13, 0, -4, 0, 1]), r2)]
    ['0', '(-1)', '0', '1']
    """
    m = flint.fmpq_poly(alpha.poly)
    U, V = _parts(h, m)
    if not U or not V:
        G = U or V
        return _monic(G, m) if G else [flint.fmpq_poly([1])]
    A, B = U, V
    while B:
        B = _monic(B, m)
        A, B = B, _remainder(A, B, m)
    return _monic(A, m)


def real_root_count(G: list, alpha: Any) -> int:
    """The number of distinct real roots of G(alpha, .), G in Q(alpha)[y] (a list of fmpq_poly in x modulo alpha's
    polynomial, low degree first), by Sturm's theorem over the ordered field Q(alpha): S_0 = G, S_1 = G',
    S_(k+1) = -rem(S_(k-1), S_k), each kept as sign(lc) times its monic part; V(-oo) - V(+oo) from the exact signs of
    the leading coefficients.  On Re z = 3 with poles 3 and 3 +- sqrt 2, G = y^3 + 2y has one real root (y = 0): the
    poles 3 +- sqrt 2 are real, off the line.

    >>> r2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> [real_root_count([flint.fmpq_poly(c) for c in G], r2) for G in ([[0], [2], [0], [1]], [[0], [-1], [0], [1]],
    ...                                                                  [[0], [0, -1], [0], [1]])]
    [1, 3, 3]
    """
    m = flint.fmpq_poly(alpha.poly)
    A = _trim([c % m for c in G])
    if len(A) <= 1:
        return 0
    dA = _trim([(k * c) % m for k, c in enumerate(A)][1:])
    seq = [(algebraic_sign(A[-1], alpha), len(A) - 1), (algebraic_sign(dA[-1], alpha), len(dA) - 1)]
    A, B = _monic(A, m), _monic(dA, m)
    s_a, s_b = seq[0][0], seq[1][0]
    while len(B) > 1:
        R = _remainder(A, B, m)  # rem(S_(k-1), S_k) = s_(k-1) rem(A, B): S_(k+1) = -s_(k-1) R
        if not R:
            break
        s_r = -s_a * algebraic_sign(R[-1], alpha)
        seq.append((s_r, len(R) - 1))
        A, s_a, B, s_b = B, s_b, _monic(R, m), s_r

    def changes(signs: list) -> int:
        return sum(1 for a, b in zip(signs, signs[1:]) if a != b)
    return changes([s_ * (-1) ** d for s_, d in seq]) - changes([s_ for s_, _ in seq])


def _value_sign(G: list, y: Fraction, alpha: RealAlgebraic) -> int:
    acc = flint.fmpq_poly([0])
    for c in reversed(G):
        acc = acc * fmpq_of(y) + c
    return algebraic_sign(acc, alpha)


def _inside(alpha: RealAlgebraic, lo: Fraction, hi: Fraction) -> bool | None:
    """lo <= alpha <= hi: True, False, or None (not decided after refinement)."""
    for bits in (0, 32, 64, 128, 256, 512, 1024):
        if bits:
            alpha.refine(bits)
        if lo <= alpha.lower and alpha.upper <= hi:
            return True
        if alpha.upper < lo or alpha.lower > hi:
            return False
    return None


def on_line_indices_algebraic(h: flint.fmpq_poly, alpha: RealAlgebraic, boxes: list, candidates) -> frozenset:
    """The indices k in ``candidates`` whose pole (the one root of h in the box boxes[k] = (re_lo, re_hi, im_lo,
    im_hi), rationals) is proved to be alpha + iy, y != 0 real (module docstring).

    >>> from fractions import Fraction as F
    >>> r2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> h = flint.fmpq_poly([-18, 0, 13, 0, -4, 0, 1])                        # +-sqrt 2, +-sqrt 2 +- i
    >>> boxes = [(F(7, 5), F(3, 2), F(9, 10), F(11, 10)), (F(7, 5), F(3, 2), F(-11, 10), F(-9, 10)),
    ...          (F(-3, 2), F(-7, 5), F(9, 10), F(11, 10))]
    >>> sorted(on_line_indices_algebraic(h, r2, boxes, [0, 1, 2]))
    [0, 1]
    """
    ints = integer_part(h)
    sq = flint.fmpq_poly(ints // ints.gcd(ints.derivative()))
    G = algebraic_line_gcd(sq, alpha)
    if len(G) <= 1:
        return frozenset()
    out = set()
    for k in candidates:
        re_lo, re_hi, im_lo, im_hi = boxes[k]
        if im_lo <= 0 <= im_hi or not _inside(alpha, re_lo, re_hi):
            continue
        if _value_sign(G, im_lo, alpha) * _value_sign(G, im_hi, alpha) <= 0:
            out.add(k)
    return frozenset(out)


def _norm_at_pair(P: flint.fmpq_poly, m: flint.fmpq_poly, Y: flint.fmpq_poly) -> flint.fmpq_poly:
    """|P(alpha + iy)|^2 for y^2 = Y (Y in Q(alpha)) as an element of Q(alpha): P(alpha + iy) = A + i y B with
    A, B polynomials in Y (U even, V odd in y), so |P|^2 = A^2 + Y B^2."""
    U, V = _parts(P, m)
    A, B = flint.fmpq_poly([0]), flint.fmpq_poly([0])
    for k in reversed(range(len(U))):
        if k % 2 == 0:
            A = (A * Y + U[k]) % m
    for k in reversed(range(len(V))):
        if k % 2 == 1:
            B = (B * Y + V[k]) % m
    return (A * A + Y * B * B) % m


def algebraic_pair_balance(g: list, h: list, alpha: RealAlgebraic) -> tuple[int, float] | None:
    """For p* = alpha simple with exactly one pair alpha +- iy of simple poles on its line (G = gcd(U, V) of h itself
    is y^3 - Y y, Y(alpha) > 0): (sign of b_*^2 - 4|b|^2, a float hint of y), exact in Q(alpha); None otherwise.
    The line part of e^(p* t) f(t) is B(t) = b_* + 2 Re(b e^(-iyt)), whose minimum is b_* - 2|b| (b_* > 0):
    sign -1 means B < 0 somewhere (so f < 0 for large t when every other pole has Re z > p*), 0 that B touches 0.

    (z^2 - 2)(z^4 - 2z^2 + 9) (shifted by 2 so that p* = 2 - sqrt 2 is the smallest positive pole) with g = 1 + z:

    >>> from fractions import Fraction as F
    >>> a = RealAlgebraic.from_isolating_interval([2, -4, 1], 0, 1)                         # 2 - sqrt 2
    >>> w = flint.fmpq_poly([-2, 1]); h = (w**2 - 2) * (w**4 - 2 * w**2 + 9); h = h / h(0)
    >>> sign, y = algebraic_pair_balance([F(1), F(1)], [F(int(c.p), int(c.q)) for c in h.coeffs()], a)
    >>> sign, round(y, 6)
    (-1, 1.0)
    """
    m = flint.fmpq_poly(alpha.poly)
    hq = flint.fmpq_poly([fmpq_of(c) for c in h])
    gq = flint.fmpq_poly([fmpq_of(c) for c in g])
    G = algebraic_line_gcd(hq, alpha)
    if len(G) != 4 or not G[0].is_zero() or not G[2].is_zero() or G[1].is_zero():
        return None
    Y = (-G[1]) % m
    if algebraic_sign(Y, alpha) <= 0:
        return None
    dh = hq.derivative()
    n_star, d_star = gq % m, dh % m  # b_* = -g(alpha)/h'(alpha)
    if d_star.is_zero():
        return None
    nh = _norm_at_pair(dh, m, Y)  # |h'(z)|^2 > 0 (z a simple pole)
    E = (n_star * n_star * nh - 4 * _norm_at_pair(gq, m, Y) * d_star * d_star) % m
    sign = algebraic_sign(E, alpha)  # b_*^2 - 4|b|^2 = E / (h'(alpha)^2 |h'(z)|^2)
    return sign, max(_float_at(Y, alpha), 0.0) ** 0.5


def _float_at(a: flint.fmpq_poly, alpha: RealAlgebraic) -> float:
    """A float hint of a(alpha) (never raising: 0.0 when it cannot be formed)."""
    try:
        x = (alpha.lower + alpha.upper) / 2
        return float_hint(sum(Fraction(int(c.p), int(c.q)) * x ** k for k, c in enumerate(a.coeffs())))
    except (OverflowError, ValueError, ZeroDivisionError):
        return 0.0


def lines_nonnegative(g: list, h: list) -> str | None:
    """f >= 0 on (0, oo) proved line by line, or None: every pole of h is simple and lies on a vertical line
    Re z = x_j through a positive real pole x_j (rational or algebraic), each line holding x_j and at most one pair
    x_j +- iy_j, and every line part B_j(t) = b_j + 2 Re(beta_j e^(-i y_j t)) is >= 0, i.e. b_j > 0 and
    b_j^2 >= 4|beta_j|^2 (exact in Q(x_j)).  Then f(t) = sum_j e^(-x_j t) B_j(t) >= 0 even where it touches 0, e.g.
    f = (e^(-(2 - sqrt 2) t) + e^(-(2 + sqrt 2) t))(1 + cos t).  The kernel re-proves it
    (exactinv_check.line_algebraic.lines_nonnegative).

    1/((1 - z)(1 - z + z^2/2)): f = 2 e^(-t) (1 - cos t), b = 2 = 2|beta|; 1/h with h = (w^2 - 2)(w^4 - 2w^2 + 9),
    w = z - 2: f > 0 (rho = oo by dominance), but the line through 2 + sqrt 2 has b_q < 2|beta_q|, so not line by line:

    >>> from fractions import Fraction as F
    >>> lines_nonnegative([F(1)], [F(1), F(-2), F(3, 2), F(-1, 2)])
    'every pole on a line Re z = x_j through a real pole, each line part B_j >= 0 (1 +- i y: b^2 = 4|beta|^2)'
    >>> w = flint.fmpq_poly([-2, 1]); h = (w**2 - 2) * (w**4 - 2 * w**2 + 9); h = h / h(0)
    >>> lines_nonnegative([F(1)], [F(int(c.p), int(c.q)) for c in h.coeffs()]) is None
    True
    """
    hq = flint.fmpq_poly([fmpq_of(c) for c in h])
    gq = flint.fmpq_poly([fmpq_of(c) for c in g])
    if hq.degree() < 1 or hq.gcd(hq.derivative()).degree() > 0 or not hq.gcd(gq).degree() == 0:
        return None
    dh = hq.derivative()
    count, parts = 0, []
    for root, _ in real_roots(hq):
        if not root > 0:
            return None
        x: Any = _Rational(root) if isinstance(root, Fraction) else root
        m = flint.fmpq_poly(x.poly)
        G = algebraic_line_gcd(hq, x)
        if not G[0].is_zero():  # (x_j is a root of h, so y = 0 is a root of G)
            return None
        if len(G) == 2 or real_root_count(G, x) == 1:  # y, or no other real root (3 between 3 +- sqrt 2): x_j alone
            count += 1
            if algebraic_sign(gq % m, x) * algebraic_sign(dh % m, x) >= 0:  # b_j = -g/h' <= 0
                return None
            parts.append(f"{x}: b > 0")
            continue
        if len(G) != 4 or not G[0].is_zero() or not G[2].is_zero() or G[1].is_zero():
            return None
        Y = (-G[1]) % m
        if algebraic_sign(Y, x) <= 0 or algebraic_sign(gq % m, x) * algebraic_sign(dh % m, x) >= 0:
            return None
        E = ((gq % m) ** 2 * _norm_at_pair(dh, m, Y) - 4 * _norm_at_pair(gq, m, Y) * (dh % m) ** 2) % m
        if algebraic_sign(E, x) < 0:
            return None
        count += 3
        parts.append(f"{x} +- i y: b^2 {'=' if E.is_zero() else '>'} 4|beta|^2")
    if count != hq.degree():
        return None
    return "every pole on a line Re z = x_j through a real pole, each line part B_j >= 0 (" + "; ".join(parts) + ")"


class _Rational:
    """A rational x as the root of the linear x - q, with the interface algebraic_sign and algebraic_line_gcd use."""

    def __init__(self, q: Fraction) -> None:
        self.q = q
        self.poly = flint.fmpz_poly([-q.numerator, q.denominator])
        self.lower = self.upper = q

    def refine(self, bits: int = 0) -> "_Rational":
        return self

    def __str__(self) -> str:
        return str(self.q)
