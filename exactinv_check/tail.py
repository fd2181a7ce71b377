"""The tail of the Taylor coefficients of a stability function is positive -- proved exactly.

r = g/h with rational g, h, h(0) > 0, r(0) = 1; for kappa >= 0, c_j(kappa) = r^(j)(-kappa)/j! = [w^j] r(w - kappa).
``prove_tail(g, h, K)`` proves  c_j(kappa) > 0  for EVERY kappa in [0, K] (K = None: [0, oo)) and EVERY j >= N,
and returns N; the caller checks c_0 .. c_{N-1} itself.  Otherwise it raises CheckFailure with the reason.

Mathematics.  After cancelling gcd(g, h), r = q + sum_k sum_{m=1..M_k} a_{k,m} (z - z_k)^(-m) over the poles z_k
(multiplicity M_k, q a polynomial), and a_{k,m} = [w^(M_k-m)] phi_k(w), phi_k(w) = w^M_k g(z_k+w)/h(z_k+w).
Expanding a/(w - (z_k + kappa))^m in w gives, for j > deg q,
  (E)   c_j(kappa) = sum_k sum_m b_{k,m} C(j+m-1, m-1) (z_k + kappa)^(-(m+j)),     b_{k,m} = (-1)^m a_{k,m}.
Certificates, tried in this order (p* = the smallest positive pole, mu its multiplicity):
 * product  (any K): g constant, all poles real and positive: r = prod_k (1 - z/z_k)^(-M_k); each factor
   1/(1 - z/p) has the coefficients p (p + kappa)^(-1-j) > 0 at -kappa, so all c_j > 0:  N = 0.
 * termwise (any K): all poles real and positive, every b_{k,m} >= 0 (exact signs): for j > deg q every
   term of (E) is >= 0 and those with m = M_k are > 0:  N = max(deg g - deg h + 1, 0).
 * dominance (finite K): b_{*,mu} > 0 and rationals Q_k < 1 with p* + kappa <= Q_k |z_k + kappa| on [0, K]
   for every other pole.  Divide (E) by b_{*,mu} C(j+mu-1, mu-1) D^(-(mu+j)), D = p* + kappa in [P_lo, P_hi+K]:
   the quotient is b_{*,mu} + E_j with |E_j| <= B(j) = sum_{m<mu} |b_{*,m}| R_m(j) (P_hi+K)^(mu-m)
        + sum_{k != *} sum_m |b_{k,m}| R_m(j) D_m Q_k^(m+j),   R_m(j) = C(j+m-1, m-1)/C(j+mu-1, mu-1),
   D_m >= D^(mu-m).  R_m(j+1)/R_m(j) = (j+m)/(j+mu), so each term is nonincreasing in j for
   j >= S = max (m Q_k - mu)/(1 - Q_k); the returned N >= S has B(N) < (lower bound of b_{*,mu}).
   Q_k is verified as:  Q^2 |c + kappa|^2 - (P_hi + Q rho + kappa)^2 >= 0  at kappa = 0 and kappa = K, for the
   inclusion disk |z_k - c| <= rho; this quadratic in kappa is concave (leading coefficient Q^2 - 1 < 0), hence
   >= 0 on [0, K], and then P_hi + kappa <= Q (|c + kappa| - rho) <= Q |z_k + kappa|.

Tie (``tie`` = kappa*): before the tie polynomial is built, kappa* must meet some pole's rational enclosure of
kappa_z (a cheap necessary condition); then module tie proves it a root and isolates it.

Rigour.  Exact: Yun's squarefree decomposition h = lc(h) prod_M f_M^M (checked by multiplying back, with each f_M
squarefree and the f_M pairwise coprime, so every root of f_M is a pole of multiplicity M), Sturm counts, and
signs of polynomials at isolated real poles (bisection until the polynomial has no root left beside the pole).
Poles in C (dominance): float Aberth iterates, refined by exact Weierstrass steps x_i <- x_i - W_i in fixed point, are
hints x_1..x_d for the roots of f = f_M.  Inclusion (Gerschgorin form of the Weierstrass/Braess-Hadeler bound,
Carstensen 1991): with W_i = f(x_i) / (lc(f) prod_{j != i} (x_i - x_j)), Lagrange interpolation at the x_i and
the matrix determinant lemma give f(z)/lc(f) = det(z I - A), A = diag(x) - W (1 ... 1); by Gerschgorin's theorem
the roots lie in the disks |z - (x_i - W_i)| <= (d-1)|W_i| and, when these are pairwise disjoint, each disk holds
exactly one root.  Taylor coefficients of g and h on a disk come from the exact Taylor shift at its centre (the
centred form), the b_{k,m} from them by midpoint-radius disk arithmetic over Gaussian rationals (inclusion-
isotone, outward rounding of every centre and radius): each enclosure holds the exact value at the true pole.
"""

from __future__ import annotations

from fractions import Fraction
from math import ceil, comb
from typing import TYPE_CHECKING, Any, Sequence

from .budget import MAX_TAIL_INDEX as MAX_INDEX  # the largest tail index the kernel will certify
from .budget import MAX_TAIL_REFINE as MAX_REFINE
from .disks import (
    ball,
    ball_abs_upper,
    ball_inv,
    ball_mul,
    pole_disks,
    round_up,
    sqrt_bounds,
    taylor_balls,
)
from .failure import CheckFailure, require
from .poly_arithmetic import derivative, divmod_, evaluate, gcd, monic, mul, power, sign, sub, trim
from .polys import Sturm, count_roots, positive_roots, squarefree
from .tie import kappa_enclosure, tie_interval

if TYPE_CHECKING:
    from .reals import Real



def prove_tail(numerator: Any, denominator: Any, K: Any, N_hint: Any = 0, tie: Any = None) -> Any:
    """An int N >= N_hint with c_j(kappa) > 0 for all kappa in [0, K] (K None: [0, oo)) and all j >= N
    (the least such index the certificate proves); CheckFailure when no certificate applies.
    With ``tie`` (a Real kappa*, claimed to be the first kappa where another pole is as close to -kappa
    as p*): the range is [0, kappa*] instead, K is ignored, and the poles whose tie is proved to be
    kappa* (module tie) enter the dominance bound with ratio Q = 1."""
    require(K is None or (isinstance(K, (int, Fraction)) and not isinstance(K, bool) and K >= 0),
            "tail: K must be a rational >= 0 or None (infinity)")
    require(isinstance(N_hint, int) and not isinstance(N_hint, bool) and N_hint >= 0, "tail: bad N_hint")
    g, h = reduced(numerator, denominator)
    factors = _yun(h)
    poles = positive_roots(h)  # isolating intervals of the distinct positive poles, increasing
    require(poles, "tail: r has no positive real pole, so no pole dominates the tail")
    f_star, mu = _factor_of(factors, poles[0])
    signs = _b_signs(g, h, f_star, mu, poles[0])
    require(signs[mu - 1] > 0, f"tail: the principal part at the smallest positive pole p* has the wrong sign "
                               f"(b_mu = (-1)^mu a_mu < 0, mu = {mu})")
    first = max(len(g) - len(h) + 1, 0)  # (E) holds for j > deg q = deg g - deg h
    if tie is not None:  # K is set by _dominance: the upper end of kappa*'s isolating interval
        return _dominance(g, h, factors, f_star, mu, poles[0], None, max(N_hint, first), tie)
    if len(poles) == len(squarefree(h)) - 1:  # every pole is real and positive
        if len(g) == 1:
            return max(N_hint, 0)  # product certificate
        if all(s >= 0 for iv in poles for s in _b_signs(g, h, *_factor_of(factors, iv), iv)):
            return max(N_hint, first)  # termwise certificate
    require(K is not None, "tail: K = oo needs all poles real and positive, and g constant (product) or all "
                           "partial-fraction coefficients b_{k,m} >= 0 (termwise)")
    return _dominance(g, h, factors, f_star, mu, poles[0], Fraction(K), max(N_hint, first))


def reduced(numerator: Sequence[float | Fraction], denominator: Any) -> Any:
    """(g, h): r = g/h in lowest terms with h(0) > 0, checked exact, h(0) > 0 and r(0) = 1; every root of h
    is then a pole of r (CheckFailure for a polynomial r)."""
    exact = all(isinstance(c, (int, Fraction)) and not isinstance(c, bool) for c in [*numerator, *denominator])
    require(exact, "tail: coefficients must be exact rationals (int or Fraction)")
    g = [Fraction(c) for c in trim(numerator)]
    h = [Fraction(c) for c in trim(denominator)]
    require(len(h) >= 2 and h[0] > 0, "tail: the denominator needs h(0) > 0 and degree >= 1")
    require(len(g) >= 1 and g[0] == h[0], "tail: r(0) = g(0)/h(0) must be 1")
    common = gcd(g, h)
    if len(common) > 1:  # r is unchanged; every remaining root of h is a pole of r
        g, h = divmod_(g, common)[0], divmod_(h, common)[0]
        g, h = ([-c for c in g], [-c for c in h]) if h[0] < 0 else (g, h)
    require(len(h) >= 2, "tail: r = g/h is a polynomial after cancellation; it has no pole")
    return g, h


# ----------------------------------------------------------------- exact algebra
def _yun(h: Sequence[Fraction]) -> Any:
    """[(f, M)]: h = lc(h) prod f^M, f monic squarefree and pairwise coprime (checked)."""
    a = gcd(h, derivative(h))
    b = divmod_(h, a)[0]
    d = sub(divmod_(derivative(h), a)[0], derivative(b))
    out, M = [], 1
    while len(b) > 1:
        require(M < len(h), "tail: squarefree decomposition does not terminate")
        f = gcd(b, d)
        if len(f) > 1:
            out.append((f, M))
        b = divmod_(b, f)[0]
        d = sub(divmod_(d, f)[0], derivative(b))
        M += 1
    product = [Fraction(1)]
    for f, M in out:
        product = mul(product, power(f, M))
    require(product == monic(h), "tail: squarefree decomposition does not multiply back to h")
    require(all(len(gcd(f, derivative(f))) == 1 for f, _ in out), "tail: a squarefree factor is not squarefree")
    require(all(len(gcd(f, e)) == 1 for i, (f, _) in enumerate(out) for e, _ in out[i + 1:]),
            "tail: squarefree factors are not coprime")
    return out


def _factor_of(factors: Sequence[tuple[list[Any], int]], iv: tuple[Fraction, Fraction]) -> tuple[list[Fraction], int]:
    """(f, M): the factor of h with the real root isolated by iv (an open (lo, hi) or an exact (q, q))."""
    lo, hi = iv
    for f, M in factors:
        if (evaluate(f, lo) == 0) if lo == hi else count_roots(f, lo, hi) > 0:
            return f, M
    raise CheckFailure("tail: a real pole belongs to no squarefree factor")


def _halve(f: Sequence[Fraction], lo: Fraction, hi: Fraction, cut: Fraction | None = None) -> tuple[Fraction, Fraction]:
    """The part (lo, cut) or (cut, hi) holding the root z of f (or (cut, cut) when cut = z; cut defaults to the
    midpoint).  f squarefree with exactly one root in (lo, hi) and none at lo, hi: f changes sign at z only."""
    cut = (lo + hi) / 2 if cut is None else cut
    value = evaluate(f, cut)
    if value == 0:
        return cut, cut
    return (lo, cut) if sign(value) != sign(evaluate(f, lo)) else (cut, hi)


def _sign_at(P: Any, f: Any, iv: Any) -> Any:
    """The exact sign of P at the root z of f isolated by iv (f squarefree, no root at lo or hi)."""
    lo, hi = iv
    if lo == hi:
        return sign(evaluate(P, lo))
    P = divmod_(P, f)[1]  # P(z) is unchanged
    if not P:
        return 0
    G = gcd(P, f)
    if len(G) > 1 and count_roots(G, lo, hi) > 0:  # a root of G in (lo, hi] is a root of f there: it is z
        return 0
    sturm = Sturm(P)
    for _ in range(MAX_REFINE):
        if lo == hi:
            return sign(evaluate(P, lo))
        if sturm.count(lo, hi) == 0:  # P has constant sign on (lo, hi], which holds z
            return sign(evaluate(P, hi))
        lo, hi = _halve(f, lo, hi)
    raise CheckFailure("tail: could not separate a real pole from the roots of a polynomial")


def _taylor(p: Sequence[Fraction]) -> list[list[Fraction]]:
    """T[i]: the polynomial in z with p(z + w) = sum_i T[i](z) w^i."""
    return [[comb(k, i) * p[k] for k in range(i, len(p))] for i in range(len(p))]


def _b_signs(g: Sequence[Fraction], h: Sequence[Fraction], f: Sequence[Fraction], M: int,
             iv: tuple[Fraction, Fraction]) -> list[int]:
    """Exact signs of b_1..b_M at the real pole z (root of f in iv, multiplicity M).  With tg_i, th_t the
    Taylor coefficients of g, h at z (th_t = 0 for t < M): phi_i th_M = tg_i - sum_{t=1..i} th_{M+t} phi_{i-t};
    A_i = phi_i th_M^(i+1) is a polynomial in z, so sign(phi_i) = sign(A_i(z)) sign(th_M(z))^(i+1)."""
    Tg, Th = _taylor(g), _taylor(h)
    tg = [divmod_(Tg[i], f)[1] if i < len(Tg) else [] for i in range(M)]
    th = [divmod_(Th[M + t], f)[1] if M + t < len(Th) else [] for t in range(M)]
    A: list[Any] = []
    for i in range(M):
        acc = mul(tg[i], power(th[0], i))
        for t in range(1, i + 1):
            acc = sub(acc, mul(mul(th[t], A[i - t]), power(th[0], t - 1)))
        A.append(divmod_(acc, f)[1])
    s = _sign_at(th[0], f, iv)
    require(s != 0, "tail: the multiplicity of a real pole is wrong")
    return [(-1) ** m * _sign_at(A[M - m], f, iv) * s ** (M - m + 1) for m in range(1, M + 1)]



# ----------------------------------------------------------------- disk enclosures of b_{k,m} (module disks)
def _b_balls(g: Sequence[Fraction], h: Sequence[Fraction], M: int,
             z: tuple[Fraction, Fraction, Fraction]) -> list[tuple[Fraction, Fraction, Fraction]]:
    """Enclosures of b_1..b_M at the pole in the disk z (multiplicity M), by the recursion of _b_signs."""
    tg, th = taylor_balls(g, z, 0, M), taylor_balls(h, z, M, M)
    inverse = ball_inv(th[0])
    phi: list[Any] = []
    for i in range(M):
        acc = tg[i]
        for t in range(1, i + 1):
            p = ball_mul(th[t], phi[i - t])
            acc = ball(acc[0] - p[0], acc[1] - p[1], acc[2] + p[2])
        phi.append(ball_mul(acc, inverse))
    return [ball((-1) ** m * phi[M - m][0], (-1) ** m * phi[M - m][1], phi[M - m][2]) for m in range(1, M + 1)]



# ----------------------------------------------------------------- dominance
def _ratio_bound(z: tuple[Fraction, Fraction, Fraction], P: Fraction, K: Any) -> Any:
    """A rational Q < 1 with p + kappa <= Q |w + kappa| for all kappa in [0, K], p <= P, w in the disk z."""
    a, b, rho = z

    def ratio(k: int | Fraction) -> float:  # float hint
        dist = abs(complex(float(a) + float(k), float(b))) - float(rho)
        return (float(P) + float(k)) / dist if dist > 0 else float("inf")

    hint = max(ratio(0), ratio(K))
    require(hint < 1, f"tail: p* does not dominate the pole near {complex(float(a), float(b)):.6g} on [0, {K}] "
                      f"(it is as close to -kappa as p*, ratio {hint:.6g})")
    for slack in (2.0 ** -24, 2.0 ** -8, 0.5):
        Q = round_up(Fraction(hint + (1 - hint) * slack))
        P1 = P + Q * rho
        if Q < 1 and all(Q * Q * ((a + k) ** 2 + b * b) - (P1 + k) ** 2 >= 0 for k in (0, K)):
            return Q
    raise CheckFailure(f"tail: could not certify that p* dominates the pole near {complex(float(a), float(b)):.6g}")


def _tie_located(h: Sequence[Fraction], value: Real, disks: dict[int, list[tuple[Any, Any, Any]]], P_lo: Fraction,
                 P_hi: Fraction) -> Any:
    """(lo, hi) isolating kappa* = value among the roots of the tie polynomial (tie.tie_interval), after a
    cheap necessary test: kappa* = kappa_z for some pole z, so value meets some pole's kappa_z enclosure."""
    v_lo, v_hi = value.bounds()
    near = [kappa_enclosure(z, P_lo, P_hi, sqrt_bounds) for zs in disks.values() for z in zs]
    require(any(e and e[0] <= v_hi and v_lo <= e[1] for e in near),
            "tie: the claimed kappa* meets no pole's enclosure of kappa_z (no pole ties with p* there)")
    return tie_interval(h, value)


def _pow_up(Q: Fraction, n: int) -> Fraction:
    """A dyadic upper bound of Q^n (0 < Q < 1), by squaring with upward rounding."""
    result, base = Fraction(1), Q
    while n:
        if n & 1:
            result = round_up(result * base)
        base, n = round_up(base * base), n >> 1
    return result


def _dominance(g: Any, h: Any, factors: Any, f_star: Any, mu: Any, iv: Any, K: Any, first: Any, tie: Any = None) -> Any:
    """The least N >= first with B(N) < b_{*,mu} (module docstring, dominance), or CheckFailure.
    ``tie`` = kappa* (a Real; K is then hi), located by _tie_located as (lo, hi) isolating kappa* among the
    roots of the tie polynomial: a pole whose
    kappa_z enclosure lies in (lo, hi) has kappa_z = kappa*, so p* + kappa <= |z + kappa| on [0, kappa*]
    and it enters with Q = 1 (multiplicity <= mu required); at least one pole must be tied."""
    disks, hits, P_lo, P_hi = star_enclosure(factors, f_star, iv)
    star = _b_balls(g, h, mu, ((P_lo + P_hi) / 2, Fraction(0), (P_hi - P_lo) / 2))
    b_mu = star[mu - 1][0] - star[mu - 1][2]  # b_{*,mu} is real: a lower bound
    require(b_mu > 0, "tail: the dominant principal part could not be bounded away from 0")
    if tie is not None:
        tie = _tie_located(h, tie, disks, P_lo, P_hi)
        K = tie[1]
    D_hi = P_hi + K
    others, tied = [], 0
    for f, M in factors:
        for k, z in enumerate(disks[id(f)]):
            if f is f_star and k == hits[0]:
                continue
            enclosure = kappa_enclosure(z, P_lo, P_hi, sqrt_bounds) if tie else None
            if enclosure and tie[0] < enclosure[0] and enclosure[1] < tie[1]:
                require(M <= mu, "tie: a tied pole has a higher multiplicity than p*; p* does not dominate")
                Q, tied = Fraction(1), tied + 1
            else:
                Q = _ratio_bound(z, P_hi, K)
            others.append((Q, M, [ball_abs_upper(b) for b in _b_balls(g, h, M, z)]))
    return _least_index(others, star, mu, b_mu, D_hi, P_lo, first, tie is None or tied > 0)


def star_enclosure(factors: Any, f_star: Any, iv: Any, disks: Any=None) -> Any:
    """(disks, hits, P_lo, P_hi): the inclusion disks of every squarefree factor (by id; computed unless given),
    the index hits[0] of the disk among f_star's of the real pole in the isolating interval iv (p* by default),
    and rationals 0 < P_lo <= that pole <= P_hi."""
    disks = {id(f): pole_disks(f) for f, _ in factors} if disks is None else disks
    lo, hi = iv
    for step in range(MAX_REFINE):  # shrink iv until one disk of f_star meets it and lo > 0
        hits = [i for i, (a, b, rho) in enumerate(disks[id(f_star)])
                if (min(max(a, lo), hi) - a) ** 2 + b * b <= rho * rho]
        if len(hits) == 1 and lo > 0:
            break
        require(lo != hi, "tail: p* lies in no inclusion disk")
        a, _, rho = disks[id(f_star)][hits[0]] if hits else (lo, 0, 0)
        cuts = [c for c in (a + 2 * rho, a - 2 * rho) if lo < c < hi]  # around a disk, or else halve
        lo, hi = _halve(f_star, lo, hi, cuts[0] if cuts and step % 3 < 2 else None)
    else:
        raise CheckFailure("tail: could not match p* to its inclusion disk")
    a, _, rho = disks[id(f_star)][hits[0]]
    P_lo, P_hi = max(lo, a - rho), min(hi, a + rho)  # p* is in [lo, hi] and within rho of a
    require(0 < P_lo <= P_hi, "tail: inconsistent enclosure of p*")
    return disks, hits, P_lo, P_hi


def _least_index(others: Sequence[tuple[Fraction, int, list[Any]]],
                 star: Sequence[tuple[Fraction, Fraction, Fraction]], mu: int, b_mu: Fraction, D_hi: Fraction,
                 P_lo: Fraction, first: int, some_tied: bool) -> int | None:
    """The least N >= first with B(N) < b_mu (module docstring, dominance)."""
    require(some_tied, "tie: no pole is proved to reach p*'s distance at the claimed kappa*")
    start = first
    for Q, M, _ in others:
        if M > mu:
            start = max(start, ceil((M * Q - mu) / (1 - Q)))
    require(start <= MAX_INDEX, f"tail: the tail bound is monotone only beyond index {start} > {MAX_INDEX}")

    def bound(j: int) -> Any:
        def R(m: int) -> Fraction:
            return Fraction(comb(j + m - 1, m - 1), comb(j + mu - 1, mu - 1))
        total = sum(ball_abs_upper(star[m - 1]) * R(m) * D_hi ** (mu - m) for m in range(1, mu))
        for Q, M, babs in others:
            for m in range(1, M + 1):
                D_m = D_hi ** (mu - m) if m <= mu else P_lo ** (mu - m)
                total += babs[m - 1] * R(m) * D_m * _pow_up(Q, m + j)
        return total

    if bound(start) < b_mu:
        return start
    bad, good = start, max(2 * start, 1)
    while not bound(good) < b_mu:
        require(good < MAX_INDEX, f"tail: no tail index up to {MAX_INDEX} is certified (p* dominates too weakly)")
        bad, good = good, 2 * good
    while good - bad > 1:
        mid = (bad + good) // 2
        bad, good = (bad, mid) if bound(mid) < b_mu else (mid, good)
    return good


# public names for module bernstein
squarefree_decomposition, factor_of, b_disks = _yun, _factor_of, _b_balls
