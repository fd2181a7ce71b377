"""rho = oo by Bernstein's theorem: is r(-x) completely monotone on [0, oo)?  (paper, Section 3.2)

r is absolutely monotonic on all of (-oo, 0] iff F(x) = r(-x) is completely monotone on [0, oo)
(c_j(kappa) = (-1)^j F^(j)(kappa)/j!).  By Bernstein's theorem F is then a Laplace transform of a measure
>= 0; for rational r this means: deg g <= deg h, every pole has Re z_k > 0, and

    F(x) = c + int_0^oo e^(-x t) f(t) dt,   f(t) = sum_k sum_m b_{k,m} t^(m-1) e^(-z_k t)/(m-1)!,

with c = lim r >= 0 and f >= 0 on (0, oo) (b_{k,m} = (-1)^m a_{k,m}, r = c + sum a_{k,m} (z - z_k)^(-m)).
Conversely, if f(t0) < 0 then c_j(j/t0) < 0 for j large enough (the weight t^j e^(-j t/t0) concentrates
at t0), so rho < oo, and an exact witness c_j(K) < 0 bounds rho <= K for the certified tail scan.

Decided here (the kernel re-proves rho = oo: exactinv_check.bernstein):
* simple rational poles: f(t) = F(e^(-t/L)) with F a polynomial (L the lcm of the poles' denominators), and
  f >= 0 iff F >= 0 on (0, 1): exact, even where f touches 0 (e^(-t) (1 - 2 e^(-t))^2 at t = ln 2);
* one distinct pole p (any multiplicity, any numerator): f(t) = e^(-p t) P(t), P a polynomial with exact
  rational coefficients; f >= 0 iff P >= 0 on (0, oo): an exact Sturm count;
* p* (the smallest positive pole) of smallest real part, every other pole with Re z_k > p* (Arb): f > 0 near
  0 from its exact Taylor coefficients (r at infinity), on a compact piece by certified Arb steps, and beyond
  by p*'s dominance bound.
Not decided (the answer is None and the caller reports Undecided): f touches 0 at some t > 0 to working
precision -- deciding f >= 0 for an exponential polynomial with algebraic exponents is the continuous
positivity problem for linear differential equations, open in general.
"""

from __future__ import annotations

from cmath import phase
from contextvars import ContextVar
from dataclasses import dataclass
from fractions import Fraction
from math import comb, factorial, gcd, pi

import flint

from ..core.flintq import fmpq_of, fraction_of
from ..core.float_hint import float_hint
from ..core.polys import sign_at
from ..core.roots import real_roots
from .line_algebraic import algebraic_pair_balance, lines_nonnegative
from .line_poles import line_density, line_part, nonnegative, pair_minimum_points, single_pair, trig_minimum_points
from .poles import PoleStructure

__all__ = ["Verdict", "completely_monotone", "density_nonnegative", "density_at_zero", "coefficient_at"]

_MAX_STEPS = 4000
_REACH_TERMS = 24  # Taylor terms of f at 0 beyond its first nonzero one (the longer bound near 0)
_REACH_SPAN = 4  # the longer bound near 0 is tried on (0, 4], (0, 2], ...
_MAX_WITNESS_J = 1 << 13
_SEARCH = ContextVar("exactinv_bernstein_witness_search", default=True)  # False: f's verdict only, no witness search


@dataclass(frozen=True)
class Verdict:
    """``infinite``: rho = oo proved (``how`` says why).  ``finite``: r(-x) is proved not completely monotone
    (rho < oo), with ``bound`` = K and c_``j``(K) < 0 exactly (rho < K) when a witness was found; ``root`` (also
    finite): c < 0 but f >= 0 is proved, so every c_j, j >= 1, is >= 0 for every kappa and c_0 = r(-kappa)
    decreases: rho is the one positive root of g(-kappa).  None of these: not decided (``how`` says why)."""

    infinite: bool
    how: str
    bound: Fraction | None = None
    j: int | None = None
    finite: bool = False
    root: bool = False  # c < 0 and f >= 0 proved: rho = the one positive root of g(-kappa) (reason bernstein-root)


def density_at_zero(g: list, h: list, count: int) -> tuple[Fraction, list[Fraction]]:
    """(c, [f_0 .. f_{count-1}]) with r(-x) = c + sum_n f_n x^(-n-1) at x = oo, exactly (deg g <= deg h).

    >>> from fractions import Fraction as F
    >>> density_at_zero([F(1)], [F(1), F(-1)], 3)      # 1/(1 + x) = x^-1 - x^-2 + ...: f(t) = e^-t
    (Fraction(0, 1), [Fraction(1, 1), Fraction(-1, 1), Fraction(1, 1)])
    """
    D = len(h) - 1
    A = [Fraction(0)] * (D + 1)
    B = [Fraction(0)] * (D + 1)
    for i, c in enumerate(g):
        A[D - i] = c * (-1) ** i
    for i, c in enumerate(h):
        B[D - i] = c * (-1) ** i
    s: list[Fraction] = []
    for n in range(count + 1):
        v = A[n] if n <= D else Fraction(0)
        for i in range(1, min(n, D) + 1):
            v -= B[i] * s[n - i]
        s.append(v / B[0])
    return s[0], s[1:]


def coefficient_at(g: list, h: list, kappa: Fraction, j: int) -> int:
    """The exact sign of c_j(kappa) = [w^j] r(w - kappa), in integers: with G, H the coefficients of
    L g(w - kappa), L h(w - kappa) (L clears every denominator), c_n = u_n / H_0^(n+1) where
    u_n = G_n H_0^n - sum_{i=1..n} H_i u_{n-i} H_0^(i-1) (no Fraction gcds).

    The trapezoid r = (1 + z/2)/(1 - z/2) = -1 + 4/(2 - z): c_0(kappa) = -1 + 4/(2 + kappa) < 0 for kappa > 2,
    and c_j(kappa) = 4 (2 + kappa)^-(j+1) > 0 for j >= 1.

    >>> from fractions import Fraction as F
    >>> g, h = [F(1), F(1, 2)], [F(1), F(-1, 2)]
    >>> coefficient_at(g, h, F(3), 0), coefficient_at(g, h, F(2), 0), coefficient_at(g, h, F(3), 5)
    (-1, 0, 1)
    """
    def shift(p):
        return [sum(p[k] * comb(k, i) * (-kappa) ** (k - i) for k in range(i, len(p))) for i in range(len(p))]
    Gq, Hq = shift(g), shift(h)
    L = 1
    for x in [*Gq, *Hq]:
        L = L * x.denominator // gcd(L, x.denominator)
    G, H = [int(x * L) for x in Gq], [int(x * L) for x in Hq]
    powers = [1]
    for _ in range(max(len(H), len(G))):
        powers.append(powers[-1] * H[0])
    u: list[int] = []
    for n in range(j + 1):
        v = G[n] * powers[n] if n < len(G) else 0
        for i in range(1, min(n, len(H) - 1) + 1):
            v -= H[i] * u[n - i] * powers[i - 1]
        u.append(v)
    sign = (u[j] > 0) - (u[j] < 0)
    return sign if H[0] > 0 or j % 2 else -sign  # sign(H_0)^(j+1)


def _witness(g, h, candidates) -> tuple[Fraction, int] | None:
    """The first (kappa, j) among candidates with c_j(kappa) < 0 exactly."""
    for kappa, j in candidates:
        if kappa >= 0 and coefficient_at(g, h, kappa, j) < 0:
            return kappa, j
    return None


def _at_infinity_witness(g, h) -> tuple[Fraction, int] | None:
    """c < 0 or deg g > deg h: some c_j, j <= deg g - deg h, is negative for large kappa."""
    top = max(len(g) - len(h) + 1, 0)
    return _witness(g, h, [(Fraction(2) ** e, j) for e in range(0, 64) for j in range(top + 1)])


def _density_witness(g, h, ts: list, s: PoleStructure) -> tuple[Fraction, int] | None:
    """f(t0) < 0 for every t0 in ts: c_j(j/t0) < 0 for j large (not searched, None, when the caller discards it).
    The least j (on a geometric scale) for which
    some t0 works, screened in Arb and confirmed exactly; then kappa is lowered by bisection while c_j stays
    negative (a smaller K gives a shorter certified tail)."""
    if not _SEARCH.get():
        return None
    j = 1
    while j <= _MAX_WITNESS_J:
        found = [(Fraction(j) / t0, j) for t0 in ts if _arb_coefficient(s, Fraction(j) / t0, j) < 0]
        found = [w for w in found if _witness(g, h, [w]) is not None]
        if found:
            kappa, j = min(found)
            lo = Fraction(0)
            for _ in range(24):
                mid = _short((lo + kappa) / 2)
                if not lo < mid < kappa:
                    break
                if coefficient_at(g, h, mid, j) < 0:
                    kappa = mid
                else:
                    lo = mid
            return kappa, j
        j = max(j + 1, j * 3 // 2)
    return _grid_witness(g, h, s)


def _grid_witness(g, h, s: PoleStructure) -> tuple[Fraction, int] | None:
    """A last search: c_j(kappa) < 0 for j < 64 and kappa = 2^(k/4) on a grid (Arb screen, exact check)."""
    for j in range(1, 64):
        for k in range(-16, 81):
            kappa = _short(Fraction(2) ** (k // 4) * Fraction([4, 5, 6, 7][k % 4], 4))
            if _arb_coefficient(s, kappa, j) < 0 and coefficient_at(g, h, kappa, j) < 0:
                return kappa, j
    return None


def _short(q: Fraction, bits: int = 24) -> Fraction:
    """q rounded to a dyadic with about ``bits`` significant bits."""
    if q == 0:
        return q
    e = bits - (q.numerator.bit_length() - q.denominator.bit_length())
    return Fraction(round(q * 2 ** e), 2 ** e) if e >= 0 else Fraction(round(q / 2 ** -e) * 2 ** -e)


def _arb_coefficient(s: PoleStructure, kappa: Fraction, j: int) -> flint.arb:
    """c_j(kappa) for j > deg q from the partial fractions (Arb): sum b C(j+m-1, m-1) (z + kappa)^-(m+j)."""
    k = flint.acb(flint.arb(fmpq_of(kappa)))
    total = flint.acb(0)
    for z, M, b in s.balls:
        w = z + k
        for m in range(1, M + 1):
            total += b[m - 1] * comb(j + m - 1, m - 1) / w ** (m + j)
    return total.real


def _finite(g, h, witness, how) -> Verdict:
    if witness is None:
        return Verdict(False, how + "; no exact witness c_j(kappa) < 0 was found", finite=True)
    return Verdict(False, how, witness[0], witness[1], finite=True)


def completely_monotone(g: list, h: list, s: PoleStructure, bits: int = 256, p_star=None) -> Verdict:
    """Is rho = oo (module docstring)?  g, h coprime with h(0) = 1; s the pole structure (Arb) with p* = s.star,
    every other pole's real part beyond p*'s or proved equal to it (``s.on_line``; then ``p_star``, the exact
    p*, decides the cases where every pole is on the line: the caller's case: no pole ever gets as close as p*).

    (1 - z)/(1 - 2z)^4: one pole 1/2, f(t) = e^(-t/2) (t^2/32 + t^3/192) >= 0, so rho = oo (issue 22);
    the trapezoid r = -1 + 4/(2 - z): r(-x) -> c = -1 < 0 while f(t) = 4 e^(-2t) >= 0, so rho is the root of
    g(-kappa) = 1 - kappa/2 (``root``); 1/(1 - z)^2 - 1/2 has c = -1/2 and f(t) = t e^(-t) >= 0 too, while
    (1 + z)/(1 - z)^2 has f(t) = (2t - 1) e^(-t) < 0 near 0 (a witness c_j(K) < 0 bounds rho).

    >>> from fractions import Fraction as F
    >>> from exactinv.monotonicity.poles import pole_structure, precision
    >>> g, h = [F(1), F(-1)], [F(1), F(-8), F(24), F(-32), F(16)]
    >>> with precision(256):
    ...     completely_monotone(g, h, pole_structure(g, h, F(1, 2))).infinite
    True
    >>> g, h = [F(1), F(1, 2)], [F(1), F(-1, 2)]
    >>> with precision(256):
    ...     v = completely_monotone(g, h, pole_structure(g, h, F(2)))
    >>> v.infinite, v.finite, v.root
    (False, True, True)
    >>> g, h = [F(1), F(1)], [F(1), F(-2), F(1)]
    >>> with precision(256):
    ...     v = completely_monotone(g, h, pole_structure(g, h, F(1)))
    >>> v.infinite, v.finite, v.root, v.j is not None
    (False, True, False, True)
    """
    if len(g) > len(h):
        return _finite(g, h, _at_infinity_witness(g, h), "deg g > deg h: r(-x) is unbounded")
    c, _ = density_at_zero(g, h, 0)
    token = _SEARCH.set(c >= 0)  # c < 0: only f >= 0 matters (a witness for f < 0 would be discarded)
    try:
        density = density_nonnegative(g, h, s, bits, p_star)
    finally:
        _SEARCH.reset(token)
    if c < 0:
        if density.infinite and g[0] > 0:  # r(0) > 0 > c: c_0 = r(-kappa) has its one zero on (0, oo)
            return Verdict(False, f"r(-x) tends to c = {c} < 0 while {density.how}", finite=True, root=True)
        return _finite(g, h, _at_infinity_witness(g, h), f"r(-x) tends to c = {c} < 0")
    return density


def density_nonnegative(g: list, h: list, s: PoleStructure, bits: int = 256, p_star=None) -> Verdict:
    """Is f >= 0 on (0, oo) (whatever the sign of c; f does not depend on c)?  ``infinite`` says it is proved,
    ``finite`` that f < 0 somewhere (with a witness c_j(K) < 0 when found), neither: not decided.
    deg g <= deg h; s as for :func:`completely_monotone`.

    The trapezoid -1 + 4/(2 - z): f(t) = 4 e^(-2t) >= 0 (its c = -1 < 0 does not matter here).

    >>> from fractions import Fraction as F
    >>> from exactinv.monotonicity.poles import pole_structure, precision
    >>> g, h = [F(1), F(1, 2)], [F(1), F(-1, 2)]
    >>> with precision(256):
    ...     density_nonnegative(g, h, pole_structure(g, h, F(2))).infinite
    True
    """
    if len(s.balls) == 1:
        return _single_pole(g, h, s)
    rational = _rational_exponents(g, h)
    if rational is not None:
        return rational
    if s.on_line and isinstance(p_star, Fraction):
        on_line = _line_verdict(g, h, p_star, s)
        if on_line is not None:
            return on_line
    return _general(g, h, s, bits, p_star)


def _line_verdict(g, h, p_star: Fraction, s: PoleStructure) -> Verdict | None:
    """Every pole on the line Re z = p* (p* rational): the exact trigonometric density (rational heights) or
    the closed form of one pair (exactinv.monotonicity.line_poles); None when neither applies."""
    line = line_density(g, h, p_star)
    if line is not None:
        Q, L, _ = line
        how = f"every pole on Re z = {p_star} at rational heights: f(t) = e^(-p* t) T(t/{L}), T a trigonometric polynomial"
        if nonnegative(Q):
            return Verdict(True, how + " >= 0 (Sturm on Q(tan(theta/2)))")
        return _finite(g, h, _density_witness(g, h, trig_minimum_points(Q, L), s), how + " < 0 somewhere")
    pair = single_pair(g, h, p_star)
    if pair is not None:
        b_star, b2, Y = pair
        how = f"p* = {p_star} and one pair p* +- i sqrt({Y}): f(t) = e^(-p* t) (b_* + 2 Re(b e^(-iyt)))"
        if b_star >= 0 and b_star * b_star >= 4 * b2:
            return Verdict(True, how + f", b_* >= 2|b| (b_*^2 = {b_star * b_star}, 4|b|^2 = {4 * b2})")
        return _finite(g, h, _density_witness(g, h, pair_minimum_points(g, h, p_star, Y), s), how + ", b_* < 2|b|")
    return None


def _rational_exponents(g, h) -> Verdict | None:
    """Simple rational poles p_k > 0: f(t) = F(e^(-t/L)) with F(u) = sum b_k u^(L p_k) a polynomial (L the lcm
    of the denominators); rho = oo when F >= 0 on (0, 1) (exact).  None otherwise (the general route decides)."""
    _, factors = flint.fmpq_poly([fmpq_of(c) for c in h]).factor()
    if any(f.degree() != 1 or m != 1 for f, m in factors):
        return None
    ps = [Fraction(-fraction_of(f.coeffs()[0]) / fraction_of(f.coeffs()[1])) for f, _ in factors]
    if min(ps) <= 0:
        return None
    L = 1
    for p in ps:
        L = L * p.denominator // gcd(L, p.denominator)
    exponents = [int(p * L) for p in ps]
    if max(exponents) > 2000:
        return None
    dh = [k * c for k, c in enumerate(h)][1:]
    F = [Fraction(0)] * (max(exponents) + 1)
    for p, n in zip(ps, exponents):
        F[n] += -sum(c * p ** i for i, c in enumerate(g)) / sum(c * p ** i for i, c in enumerate(dh))
    poly = flint.fmpq_poly([fmpq_of(c) for c in F])
    if poly.is_zero() or next(c for c in F if c) <= 0:
        return None
    if any(0 < x < 1 and m % 2 for x, m in real_roots(poly)):
        return None
    return Verdict(True, f"simple rational poles {[str(p) for p in ps]}: f(t) = F(e^(-t/{L})), F >= 0 on (0, 1)")


def _single_pole(g, h, s: PoleStructure) -> Verdict:
    mu = s.mu
    p = -h[0] * mu / h[1]  # h = h_0 (1 - z/p)^mu: h_1 = -mu h_0/p
    taylor = [sum(comb(k, i) * g[k] * p ** (k - i) for k in range(i, len(g))) for i in range(mu)]
    lc = h[-1]
    P = [(-1) ** m * taylor[mu - m] / lc / factorial(m - 1) for m in range(1, mu + 1)]
    poly = flint.fmpq_poly([fmpq_of(x) for x in P])
    roots = sorted(x for x, mult in real_roots(poly) if x > 0 and mult % 2) if poly.degree() > 0 else []
    if not poly.is_zero() and next(x for x in P if x) > 0 and not roots:
        return Verdict(True, f"one pole p = {p} (multiplicity {mu}): f(t) = e^(-p t) P(t) with P >= 0 on (0, oo)")
    points = [Fraction(1, 2 ** 20)]
    for x in roots:
        lo, hi = (x.lower, x.upper) if hasattr(x, "lower") else (x, x)
        points += [lo / 2, hi + 1, (lo + hi) / 2 + Fraction(1, 2 ** 20)]
    points += [(a + b) / 2 for a, b in zip(points, points[1:])]
    ts = [t for t in points if t > 0 and sign_at(poly, t) < 0]
    how = f"one pole p = {p}: P(t) = e^(p t) f(t) changes sign on (0, oo)"
    return _finite(g, h, _density_witness(g, h, ts, s) if ts else None, how)


def _general(g, h, s: PoleStructure, bits: int, p_star=None) -> Verdict:
    with _precision(bits):
        star_z = s.balls[s.star][0]
        p = star_z.real
        for k, (z, _, _) in enumerate(s.balls):
            if k != s.star and k not in s.on_line and not z.real > p:
                return Verdict(False, "a pole's real part is not separated from p*'s at working precision")
        far = None
        if s.on_line and _line_outweighs(s):
            far = _balanced_far(g, h, s, p_star)
            if isinstance(far, Verdict):
                return far
        _, fs = density_at_zero(g, h, len(h) + _REACH_TERMS)
        n0 = next((n for n, v in enumerate(fs) if v != 0), None)
        if n0 is None:
            return Verdict(False, "f vanishes to order deg h at 0")
        if fs[n0] < 0:
            t0 = _negative_near_zero(s, fs, n0)
            return _finite(g, h, None if t0 is None else _density_witness(g, h, [t0, t0 / 2], s),
                           f"f(t) ~ {fs[n0]} t^{n0}/{n0}! < 0 near 0")
        outcome = _march(s, fs, n0, far)
        if outcome is True:
            beyond = ("the line part B >= 0 exactly and the rest R > 0 by the dominance of the slowest-decaying real "
                      "pole off the line" if far else "dominance of p*")
            return Verdict(True, f"f > 0 on (0, oo) (Taylor at 0, certified Arb steps, {beyond})")
        if isinstance(outcome, Fraction):
            return _finite(g, h, _density_witness(g, h, [outcome], s), f"f({outcome}) < 0")
        return Verdict(False, outcome)


class _precision:
    def __init__(self, bits):
        self.bits = bits

    def __enter__(self):
        self.saved, flint.ctx.prec = flint.ctx.prec, self.bits

    def __exit__(self, *exc):
        flint.ctx.prec = self.saved


def _f_and_derivative(s: PoleStructure, t: flint.arb):
    f = df = flint.acb(0)
    for z, M, b in s.balls:
        e = (-z * t).exp()
        S0 = sum((b[m - 1] * t ** (m - 1) / factorial(m - 1) for m in range(1, M + 1)), flint.acb(0))
        S1 = sum((b[m - 1] * t ** (m - 2) / factorial(m - 2) for m in range(2, M + 1)), flint.acb(0))
        f += S0 * e
        df += (S1 - z * S0) * e
    return f.real, df.real


def _bound(s: PoleStructure, n: int, t_lo, t_hi) -> flint.arb:
    total = flint.arb(0)
    for z, M, b in s.balls:
        e = (-z.real * t_lo).exp()
        for m in range(1, M + 1):
            part = sum((comb(n, i) * t_hi ** (m - 1 - i) * abs(z) ** (n - i) / factorial(m - 1 - i)
                        for i in range(min(n, m - 1) + 1)), flint.arb(0))
            total += e * abs(b[m - 1]) * part
    return total


def _negative_near_zero(s, fs, n0) -> Fraction | None:
    t = Fraction(1, 2)
    for _ in range(60):
        value, _ = _f_and_derivative(s, flint.arb(fmpq_of(t)))
        if value < 0:
            return t
        t /= 2
    return None


def _dominated_beyond(s: PoleStructure, T: flint.arb) -> bool:
    z_star, mu, b_star = s.balls[s.star]
    p = z_star.real
    total = sum((abs(b_star[m - 1]) * fmpq_of(Fraction(factorial(mu - 1), factorial(m - 1))) * T ** (m - mu)
                 for m in range(1, mu)), flint.arb(0))
    for k, (z, M, b) in enumerate(s.balls):
        if k == s.star:
            continue
        x = (z.real - p) * T
        n = max(M - mu, 0, min(int(x.lower().floor().unique_fmpz()) if x.lower() > 0 else 0, 60))
        decay = factorial(n) / x ** n if n else flint.arb(1)
        total += decay * sum((abs(b[m - 1]) * fmpq_of(Fraction(factorial(mu - 1), factorial(m - 1))) * T ** (m - mu)
                              for m in range(1, M + 1)), flint.arb(0))
    return bool(total < b_star[mu - 1].real)


def _line_outweighs(s: PoleStructure) -> bool:
    """The line poles' |b| add up to b_* or more (not separated below it): p*'s dominance bound can never hold."""
    z, mu, b = s.balls[s.star]
    total = sum((abs(s.balls[k][2][mu - 1]) for k in s.on_line if s.balls[k][1] == mu), flint.arb(0))
    return bool(s.on_line) and not total < b[mu - 1].real


def _balanced_far(g, h, s: PoleStructure, p_star):
    """The far piece when the line poles balance p* (e^(p* t) f = B + R, B the part of p* and the line poles):
    B >= 0 exactly (:func:`exactinv.monotonicity.line_poles.line_part`) and R dominated by its slowest-decaying pole q,
    real with b_(q,M) > 0 -- a function T -> bool proving f > 0 on [T, oo); or a Verdict: f >= 0 (no pole off the
    line), f < 0 somewhere (B negative somewhere, or b_(q,M) < 0 with B touching 0: R < 0 at B's zeros for
    large t), or not decided (the case named)."""
    open_case = "deciding f >= 0 there is the continuous positivity problem (open in general)"
    if s.mu != 1 or any(s.balls[k][1] != 1 for k in s.on_line):
        return Verdict(False, "the poles on Re z = p* balance p* and p* or a line pole is multiple: "
                              f"the line part B(t) then has polynomial terms; {open_case}")
    if not isinstance(p_star, Fraction):
        return _balanced_far_algebraic(g, h, s, p_star, open_case)
    part = line_part(g, h, p_star)
    if part is None:
        return Verdict(False, "the poles on Re z = p* balance p*, and their part B(t) = b_* + sum b_k e^(-i y_k t) is "
                              "neither one pair nor at rational heights (B >= 0 is then not decided exactly); " + open_case)
    if not part.nonnegative:
        return _finite(g, h, _density_witness(g, h, list(part.points), s),
                       f"the line part B(t) is negative somewhere ({part.how}), so f < 0 there for large t")
    off = [k for k in range(len(s.balls)) if k != s.star and k not in s.on_line]
    if not off:
        return Verdict(True, f"every pole on the line Re z = p* and B >= 0 ({part.how})")
    q = min(off, key=lambda k: float_hint(_mid(s.balls[k][0].real)))
    z_q, M, b = s.balls[q]
    slow = [k for k in off if k != q and not s.balls[k][0].real > z_q.real]
    if slow or not z_q.imag.contains(0):
        return Verdict(False, f"the poles on Re z = p* balance p* exactly (B >= 0 touches 0: {part.how}), and the "
                              "slowest-decaying poles off the line are a non-real pair (or not separated from another "
                              "pole): the rest R(t) oscillates at B's zeros; " + open_case)
    lead = b[M - 1].real
    if lead > 0:
        return lambda T: _rest_dominated_beyond(s, q, off, T)
    if lead < 0:
        return _finite(g, h, _density_witness(g, h, list(part.points), s),
                       f"B >= 0 touches 0 ({part.how}) and the slowest-decaying term off the line, b_(q,M) t^(M-1) "
                       "e^(-q t), is negative: f < 0 near B's zeros for large t")
    return Verdict(False, "the sign of the slowest-decaying term off the line is not decided at working precision")


def _balanced_far_algebraic(g, h, s: PoleStructure, p_star, open_case: str) -> Verdict:
    """The balanced line for an irrational p* (exactinv.monotonicity.line_algebraic): one pair p* +- iy, b_*^2 - 4|b|^2 in
    Q(p*) decided exactly.  Negative: B(t) = b_* + 2 Re(b e^(-iyt)) < 0 somewhere, and every pole off the line has
    Re z > p* (a conjugate of p* is never on its line), so f < 0 for large t: rho < oo, with a witness c_j(K) < 0
    searched near B's minima (the witness alone is the proof).  Zero: B touches 0 and the sign of f near its zeros
    is the rest's (open in general); positive: p* dominates, not separated at working precision."""
    pair = algebraic_pair_balance(g, h, p_star)
    if pair is None or pair[0] == 0:
        lines = lines_nonnegative(g, h)
        if lines is not None:
            return Verdict(True, f"f >= 0 on (0, oo): {lines}")
    if pair is None:
        return Verdict(False, f"the poles on Re z = p* = {p_star} (irrational) balance p*, they are not one pair "
                              "p* +- iy, and f is not >= 0 line by line (several pairs or a multiple pole on a line, a "
                              "pole off every line through a real pole, or a line part negative somewhere); " + open_case)
    sign, y = pair
    if sign < 0:
        points = _pair_points(s, y)
        return _finite(g, h, _density_witness(g, h, points, s),
                       f"p* = {p_star} (irrational) and one pair on its line with b_*^2 < 4|b|^2 (exact in Q(p*)): "
                       "B(t) = b_* + 2 Re(b e^(-iyt)) < 0 somewhere, so f < 0 for large t")
    if sign == 0:
        return Verdict(False, f"p* = {p_star} (irrational) and one pair on its line with b_*^2 = 4|b|^2 exactly "
                              "(in Q(p*)): B(t) >= 0 touches 0 periodically and f's sign there is the rest's (not >= 0 "
                              "line by line: a "
                              "conjugate line's part is negative somewhere, or a pole off every line through a real "
                              "pole); " + open_case)
    return Verdict(False, f"p* = {p_star} (irrational) dominates its line pair (b_*^2 > 4|b|^2, exact), but not "
                          "separated at working precision")


def _pair_points(s: PoleStructure, y: float) -> list[Fraction]:
    """Rational t > 0 near the minima of B(t) = b_* + 2 Re(b e^(-iyt)) (float hints only, never raising):
    arg b - y t = pi mod 2 pi, b the residue of the line pole with Im z > 0, several periods out."""
    try:
        k = next(k for k in s.on_line if s.balls[k][0].imag > 0)
        b = s.balls[k][2][0]
        b_c = complex(float_hint(_mid(b.real)), float_hint(_mid(b.imag)))
        arg = phase(b_c)
        period = 2 * pi / y
        t0 = (arg - pi) / y
        return [Fraction(t0 + n * period).limit_denominator(1 << 24) for n in range(64) if t0 + n * period > 0][:24]
    except (OverflowError, ValueError, ZeroDivisionError, StopIteration):
        return []


def _rest_dominated_beyond(s: PoleStructure, q: int, off: list, T: flint.arb) -> bool:
    """R(t) > 0 on [T, oo): R e^((q - p*) t) (M-1)!/t^(M-1) = b_(q,M) + lower terms + the other off-line poles'
    terms times e^(-(z_k - q) t), each bounded at T and nonincreasing beyond (as :func:`_dominated_beyond`)."""
    z_q, M, b_q = s.balls[q]
    x0 = z_q.real
    total = sum((abs(b_q[m - 1]) * fmpq_of(Fraction(factorial(M - 1), factorial(m - 1))) * T ** (m - M)
                 for m in range(1, M)), flint.arb(0))
    for k in off:
        if k == q:
            continue
        z, Mk, b = s.balls[k]
        x = (z.real - x0) * T
        n = max(Mk - M, 0, min(int(x.lower().floor().unique_fmpz()) if x.lower() > 0 else 0, 60))
        decay = factorial(n) / x ** n if n else flint.arb(1)
        total += decay * sum((abs(b[m - 1]) * fmpq_of(Fraction(factorial(M - 1), factorial(m - 1))) * T ** (m - M)
                              for m in range(1, Mk + 1)), flint.arb(0))
    return bool(total < b_q[M - 1].real)


def _mid(x: flint.arb) -> Fraction:
    """The midpoint of an Arb ball as an exact Fraction (a hint for ordering only)."""
    m, e = x.mid().man_exp()
    m, e = int(m), int(e)
    return Fraction(m * 2 ** e) if e >= 0 else Fraction(m, 2 ** -e)


def _probes(a: Fraction, f: flint.arb, df: flint.arb) -> list[Fraction]:
    """Points just beyond a where f may already be negative: Newton's guesses past the root, then a + 2^-k."""
    out = []
    if df < 0:
        step = Fraction(f.mid().str(30, radius=False)) / Fraction(abs(df).mid().str(30, radius=False))
        out += [a + step * k for k in (Fraction(3, 2), 2, 4)]
    out += [a + Fraction(1, 2 ** k) for k in range(0, 50, 2)]
    return [t for t in out if t > a]


def _upper(x: flint.arb) -> Fraction:
    """An exact Fraction >= every point of the Arb ball x."""
    return _mid(x.upper())


def _taylor_reach(s: PoleStructure, fs, n0: int, floor: Fraction) -> Fraction:
    """The largest dyadic t_a in {4, 2, 1, ...} above ``floor`` with f > 0 on (0, t_a] by the longer Taylor bound
    at 0, else ``floor``: with N = n0 + 1 + _REACH_TERMS and B >= |f^(N)| on [0, 4] (every pole has Re z > 0),
    f(t) >= t^n0 Q(t), Q(t) = sum_{n0 <= n < N} f_n t^(n - n0)/n! - B t^(N - n0)/N!, and Q(0) = f_n0/n0! > 0, so f > 0
    on (0, t_a] when Q has no root in (0, t_a] (exact isolation).  An f that vanishes to a high order at 0 (1/h,
    deg h = 12: f ~ t^11) then needs no march of tiny steps near 0 (the kernel proves the same bound:
    exactinv_check.bernstein._taylor_reach, by Descartes' rule)."""
    N = n0 + 1 + _REACH_TERMS
    if len(fs) < N:
        return floor
    B = _upper(_bound(s, N, flint.arb(0), flint.arb(_REACH_SPAN)))
    Q = [fs[n] / factorial(n) for n in range(n0, N)] + [-B / factorial(N)]
    positive = [r for r, _ in real_roots(flint.fmpq_poly([fmpq_of(c) for c in Q])) if r > 0]
    first = min((r if isinstance(r, Fraction) else r.lower for r in positive), default=None)
    t = Fraction(_REACH_SPAN)
    while t > floor:
        if first is None or t < first:
            return t
        t /= 2
    return floor


def _march(s: PoleStructure, fs, n0, far=None):
    """True (f > 0 on (0, oo) certified), a Fraction t0 with f(t0) < 0 (certified), or a reason string.  ``far(T)``
    proves f > 0 on [T, oo) (default: p*'s dominance bound)."""
    B = _bound(s, n0 + 1, flint.arb(0), flint.arb(1))
    t_a = Fraction(1)
    while not flint.arb(fmpq_of(t_a)) * B < (n0 + 1) * fmpq_of(fs[n0]) / 2:
        t_a /= 2
        if t_a < Fraction(1, 2 ** 60):
            return "f's Taylor bound at 0 is not conclusive"
    t_a = max(t_a, _taylor_reach(s, fs, n0, t_a))
    a, d = t_a, t_a
    for _ in range(_MAX_STEPS):
        A = flint.arb(fmpq_of(a))
        if far(A) if far is not None else _dominated_beyond(s, A):
            return True
        f, df = _f_and_derivative(s, A)
        if f < 0:
            return a
        if not f > 0:
            return f"f({float_hint(a):.6g}) is 0 to working precision"
        while True:
            D = flint.arb(fmpq_of(d))
            lower = f + (df * D if df < 0 else 0) - D * D * _bound(s, 2, A, A + D) / 2
            if lower > 0:
                break
            d /= 2
            if d < Fraction(1, 2 ** 40):
                for probe in _probes(a, f, df):
                    if _f_and_derivative(s, flint.arb(fmpq_of(probe)))[0] < 0:
                        return probe  # f crosses 0 just beyond a: rho < oo
                return (f"f comes within working precision of 0 near t = {float_hint(a):.6g}: deciding f >= 0 there is "
                        "the continuous positivity problem for linear differential equations (open in general)")
        a += d
        d = min(2 * d, Fraction(8))
    return f"f was not certified positive within {_MAX_STEPS} steps (p* dominates the other poles too weakly)"
