"""The radius of absolute monotonicity of a stability function (paper, Section 3.2).

    rho(r) = sup{ kappa >= 0 : r has no pole in [-kappa, 0] and
                               c_j(kappa) = r^(j)(-kappa)/j! >= 0 for all j = 0, 1, 2, ... }

with j = 0 included (erratum E1: the paper starts at j = 1, which would give
r(z) = 1 + 2z the radius infinity).  The set of such kappa is an interval
[0, rho] (re-expanding the Taylor series at -kappa shows that absolute
monotonicity at -kappa implies it on [-kappa, 0]).

*Polynomials*: only c_0 .. c_p are not identically 0; each is a polynomial in
kappa and rho = min_j (end of the first interval where c_j >= 0), exactly.

*Rational functions with poles*: infinitely many c_j matter.  With
d_j(kappa) = c_j(kappa) h(-kappa)^(j+1), a polynomial with the sign of c_j,
the engine argues in four exact or certified steps:

1. Pringsheim: if all c_j(kappa) >= 0, the nearest singularity of r to
   -kappa lies on the positive real axis.  So without a positive real pole
   rho = 0; a witness j with c_j(0) < 0 is found by exact series expansion.
2. Let p* be the smallest positive real pole, of multiplicity mu.  Its
   principal part dominates the tail, so it must have the right sign:
   a_mu (-1)^mu > 0 where r ~ a_mu/(z - p*)^mu; otherwise rho = 0 (witness j).
3. Dominance: another pole z_k closer to -kappa than p* (for kappa above an
   algebraic bound kappa_A) also violates Pringsheim, so rho <= kappa_A.
4. On [0, K] with K < kappa_A, an explicit index N (certified by FLINT's Arb
   ball arithmetic on the partial fraction expansion) bounds where the tail
   c_j, j >= N, is positive; c_0 .. c_{N-1} are checked exactly.

The value is exact (Fraction, RealAlgebraic, 0 or INF) and the result
records the argument.  Where the argument cannot decide (rho would be limited
by a tie between two poles), :class:`~exactinv.Undecided` is raised rather
than a guess.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from math import comb

import flint

from ..core.algebraic import ExactKey, Real, RealAlgebraic
from ..core.encode import encode_real, envelope
from ..core.latex import latex_real, latex_text
from ..core.polys import count_real_roots, integer_part, sign_at
from ..core.results import ExactValueMixin
from ..core.roots import nonnegative_until, real_roots
from ..core.scalars import INF, dyadic_of, fmpq_of, fraction_of
from ..errors import Undecided
from ..model.methods import Method
from ..model.record import method_record
from ..model.validate import check_method

__all__ = ["AbsoluteMonotonicityRadius", "absolute_monotonicity_radius", "taylor_coefficient_polynomials"]

_WITNESS_SCAN = 4000  # series terms scanned for a negative c_j(0)
_MAX_COEFFICIENTS = 64  # coefficients tried below a dominance bound


@dataclass(frozen=True)
class AbsoluteMonotonicityRadius(ExactValueMixin):
    """rho(r), exactly, with the argument that decides it.

    ``reason`` is one of ``"coefficient"`` (c_binding changes sign at rho),
    ``"no-positive-pole"``, ``"principal-part-sign"``, ``"dominance-at-0"``
    (rho = 0 with ``witness_j``: c_j(0) < 0), ``"all-coefficients"`` (a
    polynomial whose c_j are >= 0 for all kappa), ``"termwise"`` / ``"product"``
    (rho = INF: all partial-fraction terms are absolutely monotonic on
    (-oo, 0], resp. r is a positive multiple of prod (1 - z/p_k)^(-m_k)).
    ``tail_index`` is the N beyond which the tail is certified positive;
    ``pole`` the smallest positive real pole p* (None for polynomials).
    ``attained``: is rho itself in the set (r absolutely monotonic at -rho).
    """

    value: Real
    attained: bool
    reason: str
    method: Method = field(repr=False)
    binding: int | None = None
    witness_j: int | None = None
    tail_index: int | None = None
    pole: Fraction | RealAlgebraic | None = None
    coefficients: tuple[tuple[Fraction, ...], ...] = field(default=(), repr=False)



    @property
    def certificate(self) -> dict:
        """A certificate with the method only (no system or polyhedron)."""
        return envelope({"method": method_record(self.method)}, [self])

    def to_latex(self) -> str:
        return rf"\rho = {latex_real(self.value)}\ ({latex_text(self.reason)})"

    def claims(self) -> list[dict]:
        claim = {"type": "absolute_monotonicity_radius", "value": encode_real(self.value), "reason": self.reason,
                 "attained": self.attained}
        if self.binding is not None:
            claim["binding"] = self.binding
        if self.witness_j is not None:
            claim["witness_j"] = self.witness_j
        if self.tail_index is not None:
            claim["tail_index"] = self.tail_index
        if self.coefficients:
            claim["d"] = [[str(c) for c in d] for d in self.coefficients]
        if self.pole is not None:
            claim["pole"] = encode_real(self.pole)
        return [claim]


def taylor_coefficient_polynomials(method: Method, count: int) -> list[flint.fmpq_poly]:
    """d_0 .. d_{count-1}: polynomials in kappa with d_j = c_j(kappa) h(-kappa)^(j+1),
    c_j(kappa) = r^(j)(-kappa)/j! (for a polynomial method h = 1 and d_j = c_j)."""
    kappa = flint.fmpq_poly([0, 1])

    def shifted(coeffs):  # [w^i] p(w - kappa) as polynomials in kappa
        return [sum((flint.fmpq_poly([fmpq_of(coeffs[k] * comb(k, i))]) * (-kappa) ** (k - i)
                     for k in range(i, len(coeffs))), flint.fmpq_poly([0])) for i in range(len(coeffs))]

    G = shifted(method.numerator)
    Hs = shifted(method.denominator)
    H0 = Hs[0]
    d: list[flint.fmpq_poly] = []
    powers = [flint.fmpq_poly([1])]
    for j in range(count):
        while len(powers) <= j:
            powers.append(powers[-1] * H0)
        value = (G[j] if j < len(G) else flint.fmpq_poly([0])) * powers[j]
        for i in range(1, min(j, len(Hs) - 1) + 1):
            value -= Hs[i] * d[j - i] * powers[i - 1]
        d.append(value)
    return d


def absolute_monotonicity_radius(method: Method) -> AbsoluteMonotonicityRadius:
    """The exact radius of absolute monotonicity (with j = 0, erratum E1)."""
    check_method(method)
    if method.is_polynomial:
        return _polynomial_radius(method)
    return _rational_radius(method)


def _polynomial_radius(method: Method) -> AbsoluteMonotonicityRadius:
    d = taylor_coefficient_polynomials(method, len(method.numerator))
    ends = [nonnegative_until(p) for p in d]
    binding = min(range(len(ends)), key=lambda j: ExactKey(ends[j]))
    value = ends[binding]
    coeffs = tuple(tuple(fraction_of(c) for c in p.coeffs()) for p in d)
    reason = "all-coefficients" if value == INF else "coefficient"
    attained = value != 0 or all(c[0] >= 0 if c else True for c in coeffs)  # rho = 0 may fail at kappa = 0 itself
    return AbsoluteMonotonicityRadius(value, attained, reason, method, None if value == INF else binding,
                                      coefficients=coeffs)


# ------------------------------------------------------------- rational case
def _series_at_zero(method: Method, count: int) -> list[Fraction]:
    """Taylor coefficients c_0(0), c_1(0), ... of r = g/h at 0 (h(0) = 1)."""
    g, h = method.numerator, method.denominator
    c: list[Fraction] = []
    for j in range(count):
        value = g[j] if j < len(g) else Fraction(0)
        for i in range(1, min(j, len(h) - 1) + 1):
            value -= h[i] * c[j - i]
        c.append(value)  # h[0] = 1
    return c


def _negative_coefficient_at_zero(method: Method) -> int | None:
    for j, c in enumerate(_series_at_zero(method, _WITNESS_SCAN)):
        if c < 0:
            return j
    return None


def _zero_radius(method: Method, reason: str, pole=None) -> AbsoluteMonotonicityRadius:
    j = _negative_coefficient_at_zero(method)
    if j is None:
        raise Undecided(f"absolute monotonicity of {method.name}: {reason} implies rho = 0, "
                        f"but no c_j(0) < 0 was found among the first {_WITNESS_SCAN} coefficients")
    return AbsoluteMonotonicityRadius(Fraction(0), False, reason, method, witness_j=j, pole=pole)


def _sign_at_real(p: flint.fmpq_poly, alpha) -> int:
    """Exact sign of p at a Fraction or RealAlgebraic alpha."""
    if isinstance(alpha, Fraction):
        return sign_at(p, alpha)
    q = integer_part(p)
    g = q.gcd(alpha.poly)
    if g.degree() > 0 and sign_at(g, alpha.lower) * sign_at(g, alpha.upper) < 0:
        return 0
    while count_real_roots(q, alpha.lower, alpha.upper) > 0:
        alpha._bisect()
    return sign_at(q, alpha.lower) * (1 if p.numer().leading_coefficient() * q.leading_coefficient() > 0 else -1)


def _rational_radius(method: Method) -> AbsoluteMonotonicityRadius:
    g, h = method.g, method.h
    poles = real_roots(h)
    positive = [(z, m) for z, m in poles if z > 0]
    if not positive:
        return _zero_radius(method, "no-positive-pole")
    p_star, mu = positive[0]
    # sign of a_mu = mu! g(p*)/h^(mu)(p*);  need a_mu (-1)^mu > 0
    h_mu = h
    for _ in range(mu):
        h_mu = h_mu.derivative()
    lead_sign = _sign_at_real(g, p_star) * _sign_at_real(h_mu, p_star) * (-1) ** mu
    if lead_sign <= 0:
        return _zero_radius(method, "principal-part-sign", p_star)

    with _precision(256):
        balls = _pole_balls(method)
        star = _star_ball(balls, p_star)
        kappa_A = _dominance_bound(balls, star)  # arb upper bound on rho, or None (no limit)
        if kappa_A is not None and not kappa_A > 0:
            return _zero_radius(method, "dominance-at-0", p_star)

        count = len(method.numerator) + len(method.denominator) + 2
        while True:
            d = taylor_coefficient_polynomials(method, count)
            ends = [nonnegative_until(p) for p in d]
            candidate = min(ends, key=ExactKey)
            if kappa_A is None:
                if candidate == INF:
                    infinite = _infinite_radius_certificate(method, balls, star)
                    if infinite is None:
                        raise Undecided(f"absolute monotonicity of {method.name}: c_0..c_{count - 1} are nonnegative "
                                        "for every kappa, but no certificate for the infinite tail applies")
                    return AbsoluteMonotonicityRadius(INF, True, infinite, method, pole=p_star)
                break
            if candidate != INF and _certainly_below(candidate, kappa_A):
                break
            if count >= _MAX_COEFFICIENTS:
                raise Undecided(f"absolute monotonicity of {method.name}: rho is limited by a pole as close to "
                                "-rho as p* (kappa_A); no coefficient sign change below kappa_A was found")
            count *= 2
        K = _rational_upper(candidate)
        N = _tail_index(balls, star, K, first=max(len(method.numerator) - len(method.denominator) + 1, 1))
        if N > count:
            d = taylor_coefficient_polynomials(method, N)
            ends += [nonnegative_until(p) for p in d[count:]]
            candidate = min(ends, key=ExactKey)
    binding = next(j for j, e in enumerate(ends) if e == candidate)
    coeffs = tuple(tuple(fraction_of(c) for c in p.coeffs()) for p in d[: max(N, binding + 1)])
    attained = candidate != 0 or all(p(0) >= 0 for p in d)
    return AbsoluteMonotonicityRadius(candidate, attained, "coefficient", method, binding, tail_index=N, pole=p_star,
                                      coefficients=coeffs)


class _precision:
    def __init__(self, bits):
        self.bits = bits

    def __enter__(self):
        self.saved = flint.ctx.prec
        flint.ctx.prec = self.bits

    def __exit__(self, *exc):
        flint.ctx.prec = self.saved


def _certainly_below(v, bound: flint.arb) -> bool:
    """v < bound, certified; refines an algebraic v's enclosure if needed."""
    for _ in range(12):
        if flint.arb(fmpq_of(_rational_upper(v))) < bound:
            return True
        if not isinstance(v, RealAlgebraic) or not flint.arb(fmpq_of(v.lower)) < bound:
            return False
        v.refine(2 * max(64, (v.upper - v.lower).denominator.bit_length()))
    return False


def _rational_upper(v) -> Fraction:
    return v.upper if isinstance(v, RealAlgebraic) else v


def _taylor_at(coeffs: list[flint.acb], z: flint.acb) -> list[flint.acb]:
    """p(z + w) = sum_j t_j w^j: the Taylor coefficients t_j = p^(j)(z)/j! (repeated Horner)."""
    c = list(coeffs)
    d = len(c) - 1
    for i in range(d):
        for k in range(d - 1, i - 1, -1):
            c[k] = c[k] + z * c[k + 1]
    return c


def _acb(q: Fraction) -> flint.acb:
    return flint.acb(flint.arb(fmpq_of(q)))


def _pole_balls(method: Method) -> list[tuple[flint.acb, int, list[flint.acb]]]:
    """Every pole z_k of r = g/h (an Arb ball), its multiplicity M and the
    coefficients b_{k,m} = a_{k,m} (-1)^m (m = 1..M) of the partial fraction
    expansion r = q + sum_k sum_m a_{k,m}/(z - z_k)^m (certified balls)."""
    g = [_acb(c) for c in method.numerator]
    h = [_acb(c) for c in method.denominator]
    _, factors = integer_part(method.h).factor()
    out = []
    for p, M in factors:
        for z, _ in p.complex_roots():
            tg = _taylor_at(g, z)
            th = _taylor_at(h, z)[M:]  # the first M coefficients vanish exactly
            if th[0].contains(0):
                raise Undecided("a pole's leading Taylor coefficient could not be separated from 0")
            # phi = G/H~ as a power series to order M;  a_{k,m} = [w^(M-m)] phi
            phi = []
            for i in range(M):
                acc = tg[i] if i < len(tg) else flint.acb(0)
                for t in range(1, i + 1):
                    if t < len(th):
                        acc -= th[t] * phi[i - t]
                phi.append(acc / th[0])
            b = [phi[M - m] * (-1) ** m for m in range(1, M + 1)]
            out.append((z, int(M), b))
    return out


def _star_ball(balls, p_star) -> int:
    """The index of the ball that holds the exact pole p*."""
    lo, hi = (p_star.lower, p_star.upper) if isinstance(p_star, RealAlgebraic) else (p_star, p_star)
    for k, (z, _, _) in enumerate(balls):
        if z.imag.is_zero() and dyadic_of(z.real.lower()) <= hi and lo <= dyadic_of(z.real.upper()):
            return k
    raise Undecided("could not match the smallest positive pole to its Arb enclosure")


def _dominance_bound(balls, star):
    """An Arb enclosure of kappa_A: the largest kappa for which p* is still
    (weakly) the nearest pole to -kappa; None when no pole ever gets closer."""
    p = balls[star][0].real
    bound = None
    for k, (z, M, _) in enumerate(balls):
        if k == star:
            continue
        a, b = z.real, z.imag
        if b.is_zero() and a > 0:
            continue  # a farther positive real pole is never closer
        if not (a < p):
            if b.is_zero() or a > p:
                continue
            raise Undecided("a pole has the same real part as p*; dominance not decided")
        value = (a * a + b * b - p * p) / (2 * (p - a))
        bound = value if bound is None else _arb_min(bound, value)
    return bound


def _arb_min(x, y):
    if x < y:
        return x
    if y < x:
        return y
    return flint.arb.union(x, y) if hasattr(flint.arb, "union") else x.union(y)


def _tail_index(balls, star, K: Fraction, first: int) -> int:
    """An index N >= first with c_j(kappa) > 0 for all j >= N and all kappa in [0, K].

    Dividing c_j by its dominant term b_mu C(j+mu-1, mu-1) D^-(mu+j) (D = p* + kappa)
    leaves b_mu + E_j(kappa) with
    |E_j| <= sum_{m<mu} |b_{*,m}| R_m(j) D^(mu-m) + sum_{k != *} sum_m |b_{k,m}| R_m(j) D^(mu-m) Q_k^(m+j),
    R_m(j) = C(j+m-1, m-1)/C(j+mu-1, mu-1) and Q_k >= D/|z_k + kappa| on [0, K].
    R_m(j+1)/R_m(j) = (j+m)/(j+mu), so each term is nonincreasing in j once
    j >= (m Q_k - mu)/(1 - Q_k); N is the first such index with E_N < b_mu."""
    z_star, mu, b_star = balls[star]
    p = z_star.real
    b_mu = b_star[mu - 1].real
    if not b_mu > 0:
        raise Undecided("the dominant principal part could not be certified positive")
    Kq = flint.arb(fmpq_of(K))
    D_max = p + Kq
    others = []
    for k, (z, M, b) in enumerate(balls):
        if k == star:
            continue
        Q = _ratio_bound(z, p, K)
        if not Q < 1:
            raise Undecided("the tail bound needs p* to dominate every other pole on [0, rho]; "
                            "a pole is (nearly) as close as p*")
        others.append((Q, M, [abs(v) for v in b]))
    start = max(first, 1)
    for Q, M, _ in others:
        for m in range(mu + 1, M + 1):
            need = (m * Q - mu) / (1 - Q)
            while not flint.arb(start) >= need:
                start *= 2
    N = start
    while True:
        E = flint.arb(0)
        for m in range(1, mu):
            E += abs(b_star[m - 1]) * _R(N, m, mu) * D_max ** (mu - m)
        for Q, M, b in others:
            for m in range(1, M + 1):
                scale = D_max ** (mu - m) if mu >= m else p ** (mu - m)
                E += b[m - 1] * _R(N, m, mu) * scale * Q ** (m + N)
        if E < b_mu:
            return N
        N *= 2
        if N > 1 << 20:
            raise Undecided("no tail index below 2^20 could be certified")


def _R(j: int, m: int, mu: int) -> flint.arb:
    return flint.arb(fmpq_of(Fraction(comb(j + m - 1, m - 1), comb(j + mu - 1, mu - 1))))


def _ratio_bound(z: flint.acb, p: flint.arb, K: Fraction, pieces: int = 64) -> flint.arb:
    """An upper bound of (p + kappa)/|z + kappa| over kappa in [0, K] (Arb, by subdivision)."""
    best = flint.arb(0)
    for t in range(pieces):
        lo, hi = K * t / pieces, K * (t + 1) / pieces
        kappa = flint.arb(fmpq_of((lo + hi) / 2), fmpq_of((hi - lo) / 2))
        distance = abs(z + flint.acb(kappa))
        ratio = (p + flint.arb(fmpq_of(hi))) / distance
        best = _arb_max(best, ratio)
    return best


def _arb_max(x: flint.arb, y: flint.arb) -> flint.arb:
    """An arb whose every point is >= every point of x and of y."""
    hi = x.upper() if x.upper() > y.upper() else y.upper()
    return flint.arb(hi)


def _infinite_radius_certificate(method: Method, balls, star) -> str | None:
    """Why rho = INF, if a sufficient certificate applies:
    ``product``  -- r = prod (1 - z/p_k)^(-m_k) with all p_k > 0 (each factor and
                    so the product is absolutely monotonic on (-oo, 0]);
    ``termwise`` -- deg g <= deg h, all poles real and positive and every
                    b_{k,m} > 0: each c_j, j >= 1, is a sum of positive terms."""
    real_positive = all(z.imag.is_zero() and z.real > 0 for z, _, _ in balls)
    if not real_positive:
        return None
    if len(method.numerator) == 1:
        return "product"
    if len(method.numerator) <= len(method.denominator) and all(v.real > 0 for _, _, b in balls for v in b):
        return "termwise"
    return None
