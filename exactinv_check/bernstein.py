"""rho = oo by Bernstein's theorem -- proved exactly.

r = g/h is absolutely monotonic on all of (-oo, 0] (rho = oo) iff F(x) = r(-x) is completely monotone on
[0, oo), since c_j(kappa) = r^(j)(-kappa)/j! = (-1)^j F^(j)(kappa)/j!.  The kernel needs only the sufficient
direction.  If deg g <= deg h and every pole z_k of r has Re z_k > 0, then with r = c + sum_k sum_m
a_{k,m} (z - z_k)^(-m) (c = lim r at oo), b_{k,m} = (-1)^m a_{k,m} and (x + z)^(-m) = int_0^oo
t^(m-1) e^(-(x+z) t) dt/(m-1)! (Re z > 0):

    F(x) = c + int_0^oo e^(-x t) f(t) dt,     f(t) = sum_k sum_m b_{k,m} t^(m-1) e^(-z_k t)/(m-1)!,

so c_0(kappa) = c + int e^(-kappa t) f(t) dt and c_j(kappa) = int t^j e^(-kappa t) f(t) dt / j! (j >= 1).
Hence c >= 0 and f >= 0 on (0, oo) give c_j(kappa) >= 0 for every j and kappa >= 0, and no pole lies on
(-oo, 0]: rho = oo.  (Conversely Bernstein's theorem and the uniqueness of the Laplace transform make these
conditions necessary, which is why the engine can decide rho = oo this way.)

The proof of f >= 0:
 * simple rational poles p_k > 0 (found exactly: a rational root k/q of H has q | lc(H)): with u = e^(-t/L),
   L the lcm of their denominators, f(t) = F(u) = sum b_k u^(L p_k), a polynomial; f >= 0 iff F >= 0 on (0, 1),
   an exact Sturm count (this decides f touching 0, e.g. e^(-t) (1 - 2 e^(-t))^2);
 * one distinct pole p (h = lc (z - p)^mu, p rational > 0): f(t) = e^(-p t) P(t) with
   P(t) = sum_m b_m t^(m-1)/(m-1)! and b_m = (-1)^m [w^(mu-m)] g(p + w)/lc exact rationals; P >= 0 on
   (0, oo) is exact: P positive right of 0 and no positive root of odd multiplicity (Yun + Sturm).
 * otherwise, with p* the smallest positive pole (multiplicity mu) and every other pole certified to have
   Re z_k > p* (inclusion disks, module disks), in three pieces:
   - near 0: f(t) = sum_n f_n t^n/n! with f_n = [x^(-n-1)] r(-x) exact rationals (r at infinity).  The first
     f_n0 != 0 (n0 < deg h, as f solves a linear ODE of order deg h) must be > 0; with B >= |f^(n0+1)| on
     [0, 1], f(t) >= t^n0 (f_n0/n0! - t B/(n0+1)!) > 0 on (0, t_a], t_a = min(1, (n0+1) f_n0 / (2B)).  Further,
     with N = n0 + 1 + BERNSTEIN_REACH_TERMS Taylor terms and B_N >= |f^(N)| on [0, T] (|e^(-z_k t)| <= 1 there):
     f(t) >= t^n0 Q(t), Q(t) = sum_{n0 <= n < N} f_n t^(n-n0)/n! - B_N t^(N-n0)/N!, so f > 0 on (0, t] when Q(t) > 0
     and Descartes' rule shows Q root-free on (0, t) (Q(0) = f_n0/n0! > 0); t_a is the largest such dyadic t <= 4
     (T = 4).  An f vanishing to a high order at 0 (1/h, deg h = 6: f ~ t^5/5!) otherwise needs a march of tiny
     steps (issue 22: 3,577 steps from 1/64, 54 s of CPU, for ((z-2)^2 - 2)((z-2)^4 - 2(z-2)^2 + 9)).
   - far: for t >= T, f(t) e^(p* t) (mu-1)!/t^(mu-1) = b_{*,mu} + sum_{m<mu} b_{*,m} (mu-1)!/(m-1)! t^(m-mu)
     + sum_{k != *} sum_m b_{k,m} (mu-1)!/(m-1)! t^(m-mu) e^(-(z_k - p*) t), and
     |e^(-(z_k - p*) t)| <= n!/(delta_k t)^n for any n >= 0, delta_k <= Re z_k - p*.  With n >= M_k - mu every
     term's bound is nonincreasing in t, so the bound at T holds on [T, oo): b_{*,mu} > (sum at T) proves
     f > 0 there.
   - far, *balanced line* (the poles proved on Re z = p*, of multiplicity mu, have sum |b_(k,mu)| >= b_(*,mu),
     so p*'s bound above never holds; e.g. e^(p* t) f = 1 + cos(9t/4) + e^(-2t), issue 22): split
     e^(p* t) f(t) = B(t) + R(t), B the terms of p* and of the poles on the line, R those of the poles off it.
     (i) B >= 0 on R exactly (line_poles.line_part; p* and every line pole simple, so B = b_* + sum_k b_k
     e^(-i y_k t): one pair, min B = b_* - 2|b| with b_*^2 >= 4|b|^2 rational; or rational heights, B(t) = T(t/L)
     with Q >= 0 on R).  (ii) R's slowest-decaying pole is a real pole q (the second distinct positive pole, its disk
     matched to its exact isolating interval [Q_lo, Q_hi] as p*'s), multiplicity M, b_(q,M) > 0, and every other
     pole off the line has Re z_k - Q_hi >= delta_k > 0 (disks).  Then for t >= T
         R(t) e^((q - p*) t) (M-1)!/t^(M-1) = b_(q,M) + sum_{m<M} b_(q,m) (M-1)!/(m-1)! t^(m-M)
             + sum_{k} sum_m b_(k,m) (M-1)!/(m-1)! t^(m-M) e^(-(z_k - q) t),
     with |e^(-(z_k - q) t)| <= e^(-delta_k t) <= n!/(delta_k t)^n (n >= M_k - M, so each bound is nonincreasing in
     t): the sum of the bounds at T below the lower end of b_(q,M) proves R > 0 on [T, oo), hence
     f = e^(-p* t)(B + R) > 0 there.  The compact piece before T is the certified march below, as before.  No pole
     off the line (all on it): f = e^(-p* t) B >= 0 at once.  Rejected: a multiple p* or line pole, B not proved
     >= 0, the slowest pole off the line not a single real pole (a non-real pair: R oscillates at B's zeros, open in
     general), or b_(q,M) not proved positive (if negative, f < 0 near B's zeros for large t).
   - between: from a = t_a step by dyadic d, with disks E_k = e^(-z_k a) (exp of a disk: scaling and
     squaring of an exact Taylor sum with its remainder; e^(-z_k (a + d)) = E_k e^(-z_k d)):
     f(a + s) >= f(a) + min(0, f'(a) d) - d^2/2 max|f''| on [0, d], with
     |f^(n)(t)| <= sum_k |E_k| sum_m |b_{k,m}| sum_i C(n,i) t^(m-1-i) |z_k|^(n-i)/(m-1-i)! (Re z_k > 0).
Every number is an exact rational; disks round outward; what is not proved within MAX_STEPS steps is rejected.

:func:`prove_density_nonnegative` proves f >= 0 (every pole with Re z > 0) whatever the sign of c: f depends only
on the principal parts, not on c.  With c < 0 (claims_radius, reason bernstein-root) every c_j, j >= 1, is still
>= 0 for every kappa >= 0, and c_0(kappa) = c + int e^(-kappa t) f(t) dt decreases strictly from r(0) = 1 to c.
"""

from __future__ import annotations

from fractions import Fraction
from math import ceil, comb, factorial, gcd
from typing import Any, Sequence

from .budget import BERNSTEIN_REACH_TERMS as REACH_TERMS
from .budget import (
    CERTIFICATE_BUDGET,
    MAX_RATIONAL_BISECTIONS,
    STURM_BUDGET,
    STURM_WORDS,
    affordable,
    charge,
    disk_step_cost,
    sturm_cost,
)
from .budget import MAX_BERNSTEIN_DEGREE as MAX_DEGREE
from .budget import MAX_BERNSTEIN_STEPS as MAX_STEPS
from .budget import MAX_BERNSTEIN_TRIALS as MAX_TRIALS
from .budget import MAX_DEGREE as MAX_DEGREE_OF_F
from .budget import MAX_RATIONAL_POLE_EXPONENT as MAX_EXPONENT
from .disks import ball, ball_abs_upper, ball_mul
from .failure import require
from .line_algebraic import AlgebraicLine, lines_nonnegative
from .line_poles import disk_on_line, line_density, line_gcd, line_part, nonnegative_on_line, rational_root, single_pair
from .poly_arithmetic import evaluate, integer_coefficients, mul, trim
from .poly_arithmetic import gcd as poly_gcd
from .polys import count_roots, no_root_between, positive_roots, sign_at, sign_right_of
from .rationals import describe
from .reals import Real
from .tail import b_disks, factor_of, reduced, squarefree_decomposition, star_enclosure

MIN_STEP = Fraction(1, 2 ** 50)
TAYLOR_TERMS = 28
TAYLOR_REACH_SPAN = Fraction(4)  # the longer bound near 0 is tried on (0, 4], (0, 2], ... (dyadic ends)

__all__ = ["prove_completely_monotone", "prove_density_nonnegative", "density_at_zero"]


def density_at_zero(g: Sequence[Fraction], h: Sequence[Fraction], count: int) -> tuple[Fraction, list[Fraction]]:
    """(c, [f_0 .. f_{count-1}]): r(-x) = c + sum_n f_n x^(-n-1) at x = oo (deg g <= deg h), exactly:
    with u = 1/x, r(-1/u) = A(u)/B(u), A = sum g_i (-1)^i u^(D-i), B likewise (D = deg h, B(0) != 0)."""
    D = len(h) - 1
    A = [Fraction(0)] * (D + 1)
    B = [Fraction(0)] * (D + 1)
    for i, c in enumerate(g):
        A[D - i] = c * (-1) ** i
    for i, c in enumerate(h):
        B[D - i] = c * (-1) ** i
    s: list[Any] = []
    for n in range(count + 1):
        v = A[n] if n <= D else Fraction(0)
        for i in range(1, min(n, D) + 1):
            v -= B[i] * s[n - i]
        s.append(v / B[0])
    return s[0], s[1:]


def prove_completely_monotone(numerator: Any, denominator: Any, pole_poly: Any = None) -> Any:
    """A sentence saying why rho = oo (c >= 0 and f >= 0 on (0, oo), module docstring), or CheckFailure.
    ``pole_poly`` (optional, untrusted: the claim's recorded pole's polynomial) only speeds up the arithmetic in
    Q(p*) for an irrational p* (:func:`_line_modulus`); it is never believed."""
    g, h = reduced(numerator, denominator)
    require(len(g) <= len(h), "bernstein: deg g > deg h, so r(-x) is unbounded and not completely monotone")
    c, _ = density_at_zero(g, h, 0)
    require(c >= 0, f"bernstein: r(-x) tends to c = {describe(c)} < 0")
    return f"{_density_nonnegative(g, h, pole_poly)}, c = {describe(c)} >= 0 (Bernstein: r(-x) completely monotone)"


def _line_modulus(f_star: Any, iv: Any, pole_poly: Any) -> Any:
    """p* (irrational) as a Real, and the squarefree polynomial m with m(p*) = 0 in which Q(p*) = Q[x]/(m) is
    computed (exactinv_check.line_algebraic: any squarefree m with p* as a root is sound): gcd(f_star, pole_poly)
    when it keeps p* as a root -- usually p*'s minimal polynomial, far smaller than f_star (a product of sextic
    factors: the inversions modulo the degree-12 f_star cost 30 times those modulo p*'s quadratic) -- else f_star.
    The hint is only a candidate: the gcd divides the squarefree f_star and p*'s sign on it is tested exactly."""
    alpha = Real.root_in(f_star, *iv)
    if pole_poly is not None and 2 < len(f_star):
        m = trim(poly_gcd(list(f_star), list(pole_poly)))
        if 2 <= len(m) < len(f_star) and alpha.sign_of(m) == 0:
            return alpha, m
    return alpha, f_star


def prove_density_nonnegative(numerator: Any, denominator: Any) -> Any:
    """(c, a sentence saying why f >= 0 on (0, oo)), or CheckFailure: r(-x) = c + int_0^oo e^(-xt) f(t) dt with
    f >= 0 and every pole Re z > 0, whatever the sign of c (f does not depend on c: r - c has the same poles
    and principal parts).  Then c_j(kappa) = int t^j e^(-kappa t) f(t) dt/j! >= 0 for every j >= 1 and kappa >= 0,
    and c_0(kappa) = r(-kappa) decreases from r(0) = 1 to c (claims_radius: reason bernstein-root)."""
    g, h = reduced(numerator, denominator)
    require(len(g) <= len(h), "bernstein: deg g > deg h, so r(-x) is unbounded and not completely monotone")
    c, _ = density_at_zero(g, h, 0)
    return c, _density_nonnegative(g, h)


def _density_nonnegative(g: Any, h: Any, pole_poly: Any = None) -> Any:
    """A sentence saying why f >= 0 on (0, oo) and every pole has Re z > 0 (g, h reduced, deg g <= deg h)."""
    factors = squarefree_decomposition(h)
    poles = positive_roots(h)
    require(poles, "bernstein: r has no positive real pole")
    if len(factors) == 1 and len(factors[0][0]) == 2:
        return _single_pole(g, h, factors[0][1])
    rational = _rational_simple_poles(h, factors, poles)
    if rational is not None:
        how = _rational_exponents(g, h, rational)
        if how is not None:
            return how
    require(len(h) - 1 <= MAX_DEGREE, f"bernstein: deg h > {MAX_DEGREE}")
    f_star, mu = factor_of(factors, poles[0])
    p_exact = rational_root(f_star, *poles[0])  # p* exactly when rational (poles on Re z = p* need it)
    if p_exact is not None and len(factors) == 1 and mu == 1:
        pair = single_pair(g, h, p_exact)  # p* and one pair p* +- iy, y irrational: min T = b_* - 2|b| exactly
        if pair is not None:
            b_star, b2 = pair
            require(b_star >= 0 and b_star * b_star >= 4 * b2, f"bernstein: p* = {describe(p_exact)} and one pair on its line: "
                    f"f(t) = e^(-p* t) (b_* + 2 Re(b e^(-iyt))) with b_*^2 = {describe(b_star * b_star)} "
                    f"< 4|b|^2 = {describe(4 * b2)}, "
                    "negative somewhere")
            return (f"p* = {describe(p_exact)} and one pair on its line: f(t) = e^(-p* t) (b_* + 2 Re(b e^(-iyt))) >= 0, "
                    f"b_* = {describe(b_star)} >= 2|b| (4|b|^2 = {describe(4 * b2)})")
        line = line_density(g, h, p_exact)  # every pole on Re z = p*: f = e^(-p* t) T(t/L), exact
        if line is not None and _sturm_affordable(line[0]):  # else the general proof below (dominance)
            Q, where = line
            require(nonnegative_on_line(Q), f"bernstein: {where}, and the trigonometric density "
                                            "T(theta) = Q(tan(theta/2))/(1 + x^2)^N is negative somewhere")
            return (f"{where}: f(t) = e^(-p* t) T(t/L) with T >= 0 on the circle (Q = {[describe(c) for c in Q]} >= 0 on "
                    "R, Sturm)")
    disks, hits, P_lo, P_hi = star_enclosure(factors, f_star, poles[0])
    # p* irrational: its line is proved in Q(p*) (exactinv_check.line_algebraic), built only when a pole needs it
    algebraic: list[AlgebraicLine] = []
    terms = []  # (z disk, M, b disks, is p*, on the line Re z = p*)
    gcds: dict[int, Any] = {}
    for f, M in factors:
        for k, z in enumerate(disks[id(f)]):
            star = f is f_star and k == hits[0]
            on_line = False
            if star:
                z = ((P_lo + P_hi) / 2, Fraction(0), (P_hi - P_lo) / 2)
            elif not z[0] - z[2] > P_hi:
                if p_exact is not None and z[0] - z[2] <= p_exact <= z[0] + z[2]:
                    if id(f) not in gcds:
                        gcds[id(f)] = line_gcd(f, p_exact)
                    on_line = disk_on_line(gcds[id(f)], z, p_exact)
                elif p_exact is None and z[0] - z[2] <= P_hi and P_lo <= z[0] + z[2]:
                    if not algebraic:
                        algebraic.append(AlgebraicLine(*_line_modulus(f_star, poles[0], pole_poly)))
                    if id(f) not in gcds:
                        gcds[id(f)] = algebraic[0].line_gcd(f)
                    on_line = algebraic[0].disk_on_line(gcds[id(f)], z)
                require(on_line, "bernstein: a pole is not proved to have Re z > p* or Re z = p* (then it may "
                                 "be as close to -kappa as p* for large kappa, or f is not proved dominated)")
                require(M <= mu, "bernstein: a pole on Re z = p* has a higher multiplicity than p*, so p* does not "
                                 "dominate f")
            terms.append((z, M, b_disks(g, h, M, z), star, on_line))
    star_b = next(t[2] for t in terms if t[3])
    require(star_b[mu - 1][0] - star_b[mu - 1][2] > 0, "bernstein: b_{*,mu} is not proved positive")
    rest, line = None, ""
    if _line_outweighs(terms, mu) and p_exact is None:  # p* irrational: the balance is decided line by line
        lines = lines_nonnegative(g, h, len(factors) == 1 and factors[0][1] == 1)
        require(lines is not None, "bernstein: the poles on Re z = p* (irrational) balance p* (sum |b| >= b_*), and f is "
                                   "not proved >= 0 line by line (every pole simple, on a line through a positive real "
                                   "pole with at most one pair, b_j^2 >= 4|beta_j|^2 exactly in Q(x_j))")
        return f"f(t) = sum_j e^(-x_j t) B_j(t) >= 0: {lines}"
    if _line_outweighs(terms, mu):  # the line poles balance p* (sum |b| >= b_*): p*'s dominance can never hold
        rest, line = _balanced_line(g, h, factors, poles, disks, terms, p_exact)
        if rest is True:  # every pole on the line and B >= 0: f = e^(-p* t) B(t) >= 0
            return f"f(t) = e^(-p* t) B(t), {line}"
    steps = _positive(g, h, terms, mu, P_hi, rest)
    far = (f"beyond, {line} and the rest R(t) > 0 by the dominance of the slowest-decaying pole q off the line"
           if rest else "dominance of p* beyond")
    return f"f > 0 on (0, oo): Taylor at 0, {steps} certified steps, {far}"


def _line_outweighs(terms: Any, mu: Any) -> Any:
    """Is the sum over the line poles of multiplicity mu of |b_(k,mu)| (upper bounds) >= b_(*,mu) (lower bound)?
    Only then is the far piece the balanced line's (p*'s own dominance bound, with |e^(-(z - p*) t)| = 1 on the
    line, can never hold; line poles of lower multiplicity decay against t^(mu-1))."""
    if not any(t[4] for t in terms):
        return False
    star_b = next(t[2] for t in terms if t[3])[mu - 1]
    return sum(ball_abs_upper(t[2][mu - 1]) for t in terms if t[4] and t[1] == mu) >= star_b[0] - star_b[2]


def _balanced_line(g: Any, h: Any, factors: Any, poles: Any, disks: Any, terms: Any, p_exact: Any) -> Any:
    """The far piece when the line poles balance p* (module docstring, "balanced line"): e^(p* t) f = B + R with
    B, the part of p* and of the poles on the line, proved >= 0 exactly (line_poles.line_part: p* and every line
    pole simple; one pair, or rational heights), and R, the part of the poles off the line, dominated by its
    slowest-decaying pole q -- a real pole (the second positive pole, its inclusion disk matched to its exact
    isolating interval) with b_{q,M} > 0 and every other pole off the line at Re z > q (disks).  Returns
    (True, sentence) when R is empty, else ((index of q, M_q, [delta_k]), sentence); CheckFailure otherwise."""
    require(p_exact is not None and all(t[1] == 1 for t in terms if t[3] or t[4]),
            "bernstein: the poles on Re z = p* balance p* (sum |b| >= b_*) and p* or a line pole is not simple (or p* "
            "is irrational): p*'s dominance bound cannot hold and the balanced-line proof does not apply")
    line = line_part(g, h, p_exact)
    require(line is not None, "bernstein: the poles on Re z = p* balance p* (sum |b| >= b_*), and their part "
                              "B(t) = b_* + sum b_k e^(-i y_k t) is not proved >= 0 (one pair, or rational heights)")
    off = [k for k, t in enumerate(terms) if not t[3] and not t[4]]
    if not off:
        return True, line
    require(len(poles) >= 2, "bernstein: the poles on Re z = p* balance p*, and the slowest-decaying pole off the line "
                             "is not real (a non-real pair: R(t) oscillates, deciding it is open in general)")
    f_q, M_q = factor_of(factors, poles[1])
    _, hits, Q_lo, Q_hi = star_enclosure(factors, f_q, poles[1], disks)
    z_q = disks[id(f_q)][hits[0]]
    q = next((k for k in off if terms[k][0] == z_q and terms[k][1] == M_q), None)
    require(q is not None, "bernstein: the second positive pole is not among the poles off the line (internal)")
    exact = ((Q_lo + Q_hi) / 2, Fraction(0), (Q_hi - Q_lo) / 2)
    terms[q] = (exact, M_q, b_disks(g, h, M_q, exact), False, False)
    delta = {}
    for k in off:
        if k != q:
            z = terms[k][0]
            delta[k] = z[0] - z[2] - Q_hi
            require(delta[k] > 0, "bernstein: the poles on Re z = p* balance p*, and the slowest-decaying pole off the "
                                  "line is not proved to be the single real pole q (another pole has Re z <= q to working "
                                  "precision: deciding R > 0 is open in general)")
    b_q = terms[q][2][M_q - 1]
    require(b_q[0] - b_q[2] > 0, "bernstein: the poles on Re z = p* balance p*, and the slowest-decaying term off the "
                                 "line, b_(q,M) t^(M-1) e^(-q t), is not proved positive (f < 0 near B's zeros when it "
                                 "is negative)")
    return (q, M_q, delta), line


def _sturm_affordable(Q: Any) -> Any:
    """The line density's Sturm count fits the per-computation and the certificate's budgets.  When it does not
    (N = max |n_k| near MAX_LINE_EXPONENT: Q of degree 2N with 2N-bit binomials), the general proof below still
    decides every f that p* dominates strictly (a genuine certificate, 1 +- 60i beside p* = 1, was rejected)."""
    ints = integer_coefficients(Q)
    if len(ints) <= 2:
        return True
    cost = sturm_cost(len(ints) - 1, max(abs(c).bit_length() for c in ints))
    # at most half the certificate's account: the count's real work can exceed this estimate (a Descartes isolation
    # of a density with near-real complex roots), and the dominance proof is the cheaper road when p* dominates
    return cost <= STURM_BUDGET and cost // STURM_WORDS <= CERTIFICATE_BUDGET // 2 and affordable(cost // STURM_WORDS)


def _single_pole(g: Any, h: Any, mu: Any) -> Any:
    f = squarefree_decomposition(h)[0][0]
    p = -f[0] / f[1]
    require(p > 0, "bernstein: the pole is not positive")
    lc = h[-1]
    taylor = [sum(comb(k, i) * g[k] * p ** (k - i) for k in range(i, len(g))) for i in range(mu)]
    P = trim([(-1) ** m * taylor[mu - m] / lc / factorial(m - 1) for m in range(1, mu + 1)])
    require(P and sign_right_of(P, Fraction(0)) > 0, "bernstein: P(t) = e^(p t) f(t) is not positive right of 0")
    if len(P) > 1:
        odd = [Fraction(1)]
        for q, M in squarefree_decomposition(P):
            if M % 2:
                odd = mul(odd, q)
        require(len(odd) == 1 or count_roots(odd, Fraction(0), None) == 0,
                "bernstein: P(t) = e^(p t) f(t) changes sign on (0, oo)")
    return (f"one pole p = {describe(p)} of multiplicity {mu}: f(t) = e^(-p t) P(t), P = {[describe(x) for x in P]} >= 0 on "
            f"(0, oo) (Sturm)")


def _rational_simple_poles(h: Any, factors: Any, poles: Any) -> Any:
    """The poles as exact rationals when every pole is simple, real, positive and rational; else None.  A
    rational root k/q of the integer polynomial H has q | lc(H): an isolating interval narrower than 1/lc^2
    holds at most one fraction with such a denominator, the candidate ceil(lo lc)/lc, tested exactly."""
    if len(factors) != 1 or factors[0][1] != 1 or len(poles) != len(h) - 1:
        return None
    H = integer_coefficients(h)
    lc = abs(H[-1])
    out = []
    for lo, hi in poles:
        if lo != hi:
            for _ in range(MAX_RATIONAL_BISECTIONS):
                if (hi - lo) * lc * lc < 1:
                    break
                mid = (lo + hi) / 2
                if sign_at(H, mid) == 0:
                    lo = hi = mid
                    break
                lo, hi = (lo, mid) if sign_at(H, lo) * sign_at(H, mid) < 0 else (mid, hi)
            else:
                return None
        q = lo if lo == hi else Fraction(ceil(lo * lc), lc)
        if not lo <= q <= hi or sign_at(H, q) != 0:
            return None
        out.append(q)
    return out


def _rational_exponents(g: Any, h: Any, ps: Any) -> Any:
    """Simple rational poles p_k > 0: f(t) = sum b_k e^(-p_k t) = F(u) with u = e^(-t/L), L the lcm of the
    denominators, F(u) = sum b_k u^(L p_k) exactly (b_k = -g(p_k)/h'(p_k)); f >= 0 on (0, oo) iff F >= 0 on
    (0, 1): F positive right of 0 and no root of odd multiplicity in (0, 1) (Yun + Sturm).  None when F does
    not show it (the general proof may still)."""
    L = 1
    for p in ps:
        L = L * p.denominator // gcd(L, p.denominator)
    exponents = [int(p * L) for p in ps]
    if max(exponents) > MAX_EXPONENT or max(exponents) - min(exponents) > MAX_DEGREE_OF_F:
        return None  # F (u^min stripped) would pass the kernel's polynomial bound: the general proof decides
    dh = [k * c for k, c in enumerate(h)][1:]
    F = [Fraction(0)] * (max(exponents) + 1)
    for p, n in zip(ps, exponents):
        F[n] += -evaluate(g, p) / evaluate(dh, p)
    F = trim(F)
    if not F or sign_right_of(F, Fraction(0)) <= 0:
        return None
    odd = [Fraction(1)]
    for q, M in squarefree_decomposition(F[next(i for i, c in enumerate(F) if c):]):
        if M % 2:
            odd = mul(odd, q)
    inside = count_roots(odd, Fraction(0), Fraction(1)) - (1 if evaluate(odd, Fraction(1)) == 0 else 0)
    if len(odd) > 1 and inside:
        return None
    return (f"simple rational poles {[describe(p) for p in ps]}: f(t) = F(e^(-t/{L})) with the polynomial F >= 0 on "
            f"(0, 1) (Sturm)")


# ----------------------------------------------------------------- disk helpers
def _add(x: Any, y: Any) -> Any:
    return ball(x[0] + y[0], x[1] + y[1], x[2] + y[2])


def _scale(x: Any, q: Any) -> Any:
    return ball(x[0] * q, x[1] * q, x[2] * abs(q))


def _exp_point(x: Fraction, y: Fraction) -> tuple[Fraction, Fraction, Fraction]:
    """A disk holding e^(x + iy) (x, y rational): an exact Taylor sum at (x + iy)/2^s, |.| <= 1/16, with its
    remainder 2|v|^(N+1)/(N+1)!, then s squarings."""
    s, size = 0, abs(x) + abs(y)
    while size > Fraction(2 ** s, 16):
        s += 1
    vr, vi = x / 2 ** s, y / 2 ** s
    sr, si = Fraction(1), Fraction(0)
    for n in range(TAYLOR_TERMS, 0, -1):  # 1 + v/n (1 + v/(n+1) (...))
        sr, si = 1 + (vr * sr - vi * si) / n, (vr * si + vi * sr) / n
    rem = 2 * Fraction(1, 16) ** (TAYLOR_TERMS + 1) / factorial(TAYLOR_TERMS + 1)
    E = ball(sr, si, rem)
    for _ in range(s):
        E = ball_mul(E, E)
    return E


def _exp(w: tuple[Fraction, Fraction, Fraction]) -> tuple[Fraction, Fraction, Fraction]:
    """A disk holding e^u for every u in the disk w (radius <= 1: |e^(u-c) - 1| <= e^rad - 1 <= 2 rad)."""
    require(w[2] <= 1, "bernstein: an exponent's enclosure is too wide")
    return ball_mul(_exp_point(w[0], w[1]), (Fraction(1), Fraction(0), 2 * w[2]))


def _exp_of(z: Any, t: Any) -> Any:
    """A disk holding e^(-z t) for every z in the disk z, t >= 0 rational."""
    return _exp((-z[0] * t, -z[1] * t, z[2] * t))


# ----------------------------------------------------------------- f > 0 on (0, oo)
def _taylor_reach(fs: Sequence[Fraction], n0: int, derivative_bound: Any, size: int, floor: Fraction) -> Fraction:
    """The largest dyadic t_a in {TAYLOR_REACH_SPAN, .../2, ...} above ``floor`` with f > 0 on (0, t_a] proved by
    the longer Taylor bound at 0 (module docstring, "near 0"), else ``floor``: with N = n0 + 1 + REACH_TERMS
    and B >= |f^(N)| on [0, T] (every pole has Re z > 0, so |e^(-z t)| <= 1 there),
        f(t) >= t^n0 Q(t),   Q(t) = sum_{n0 <= n < N} f_n t^(n - n0)/n! - B t^(N - n0)/N!,
    and Q(0) = f_n0/n0! > 0 with Q(t_a) > 0 and no root of Q in (0, t_a) (Descartes' rule, priced) give Q > 0 on
    [0, t_a].  A function that vanishes to a high order at 0 (f ~ t^n0) then needs no march of tiny steps there."""
    N = n0 + 1 + REACH_TERMS
    if len(fs) < N:
        return floor
    T = TAYLOR_REACH_SPAN
    charge(disk_step_cost(size) * N, "the Taylor bound of the Bernstein density at 0")
    B = derivative_bound(N, [Fraction(1)] * size, T)
    Q = integer_coefficients([fs[n] / factorial(n) for n in range(n0, N)] + [-B / factorial(N)])
    t = T
    while t > floor:
        if sign_at(Q, t) > 0 and no_root_between(Q, Fraction(0), t):
            return t
        t /= 2
    return floor


def _positive(g: Any, h: Any, terms: Any, mu: Any, P_hi: Any, rest: Any=None) -> Any:
    babs = [[ball_abs_upper(b) for b in bs] for _, _, bs, _, _ in terms]
    zabs = [ball_abs_upper(z) for z, _, _, _, _ in terms]

    def derivative_bound(n: Any, e: Any, t_hi: Any) -> Any:  # >= |f^(n)(t)| for t in [t_lo, t_hi]; e[k] >= |e^(-z_k t_lo)|
        total = Fraction(0)
        for k, (_, M, _, _, _) in enumerate(terms):
            for m in range(1, M + 1):
                part = sum(comb(n, i) * t_hi ** (m - 1 - i) * zabs[k] ** (n - i) / factorial(m - 1 - i)
                           for i in range(min(n, m - 1) + 1))
                total += e[k] * babs[k][m - 1] * part
        return total

    _, fs = density_at_zero(g, h, len(h) + REACH_TERMS)
    n0 = next((n for n, v in enumerate(fs) if v != 0), None)
    require(n0 is not None, "bernstein: f vanishes to order deg h at 0")
    require(fs[n0] > 0, f"bernstein: f(t) ~ {fs[n0]} t^{n0}/{n0}! < 0 near t = 0")  # type: ignore[index]
    B = derivative_bound(n0 + 1, [Fraction(1)] * len(terms), Fraction(1))  # type: ignore[operator]
    t_a = min(Fraction(1), (n0 + 1) * fs[n0] / (2 * B)) if B else Fraction(1)  # type: ignore[index, operator]
    t_a = Fraction(1, 2 ** max(0, (1 / t_a).__ceil__().bit_length()))  # a dyadic <= t_a
    t_a = max(t_a, _taylor_reach(fs, n0, derivative_bound, len(terms), t_a))  # type: ignore[arg-type]

    star = next(k for k, t in enumerate(terms) if t[3])
    b_mu = terms[star][2][mu - 1][0] - terms[star][2][mu - 1][2]
    # delta_k <= Re z_k - p*: 0 for a pole proved on the line (|e^(-(z_k - p*) t)| = 1 exactly)
    delta = [None if k == star else Fraction(0) if line else z[0] - z[2] - P_hi
             for k, (z, _, _, _, line) in enumerate(terms)]

    def dominated_beyond(T: Any) -> Any:
        total = sum(babs[star][m - 1] * Fraction(factorial(mu - 1), factorial(m - 1)) * T ** (m - mu)
                    for m in range(1, mu))
        for k, (_, M, _, _, _) in enumerate(terms):
            if k == star:
                continue
            x = delta[k] * T
            n = max(M - mu, 0, min(int(x), 60))
            decay = Fraction(factorial(n)) / x ** n
            total += decay * sum(babs[k][m - 1] * Fraction(factorial(mu - 1), factorial(m - 1)) * T ** (m - mu)
                                 for m in range(1, M + 1))
            if total >= b_mu:
                return False
        return total < b_mu

    def rest_dominated_beyond(T: Any) -> Any:  # R(t) > 0 for t >= T (balanced line): q's dominance over the poles off the line
        q, M, delta_of = rest
        b_q = terms[q][2][M - 1][0] - terms[q][2][M - 1][2]
        total = sum(babs[q][m - 1] * Fraction(factorial(M - 1), factorial(m - 1)) * T ** (m - M) for m in range(1, M))
        for k, delta_k in delta_of.items():
            x = delta_k * T
            n = max(terms[k][1] - M, 0, min(int(x), 60))
            decay = Fraction(factorial(n)) / x ** n
            total += decay * sum(babs[k][m - 1] * Fraction(factorial(M - 1), factorial(m - 1)) * T ** (m - M)
                                 for m in range(1, terms[k][1] + 1))
            if total >= b_q:
                return False
        return total < b_q

    a, d = t_a, t_a
    E = [_exp_of(z, a) for z, _, _, _, _ in terms]
    steps_of, trials = {}, 0
    size = sum(t[1] for t in terms)
    for step in range(MAX_STEPS):
        charge(disk_step_cost(size), "a step of the Bernstein positivity proof")  # the clock too: no charge, no limit
        if (rest_dominated_beyond(a) if rest else dominated_beyond(a)):
            return step
        F0 = F1 = (Fraction(0), Fraction(0), Fraction(0))
        for k, (z, M, bs, _, _) in enumerate(terms):
            S0 = S1 = (Fraction(0), Fraction(0), Fraction(0))
            for m in range(1, M + 1):
                S0 = _add(S0, _scale(bs[m - 1], a ** (m - 1) / factorial(m - 1)))
                if m >= 2:
                    S1 = _add(S1, _scale(bs[m - 1], a ** (m - 2) / factorial(m - 2)))
            zS0 = ball_mul(z, S0)
            F0 = _add(F0, ball_mul(S0, E[k]))
            F1 = _add(F1, ball_mul(ball(S1[0] - zS0[0], S1[1] - zS0[1], S1[2] + zS0[2]), E[k]))
        f_lo, df_lo = F0[0] - F0[2], F1[0] - F1[2]
        require(f_lo > 0, f"bernstein: f({float(a):.6g}) is not proved positive")
        e = [ball_abs_upper(x) for x in E]
        while True:
            trials += 1
            charge(disk_step_cost(size) // 4, "a step-size trial of the Bernstein positivity proof")
            require(trials <= MAX_TRIALS, f"bernstein: more than {MAX_TRIALS} step trials (f is too close to 0)")
            B2 = derivative_bound(2, e, a + d)
            if f_lo + min(Fraction(0), df_lo * d) - d * d * B2 / 2 > 0:
                break
            d /= 2
            require(d >= MIN_STEP, f"bernstein: f is not proved positive near t = {float(a):.6g} (it may touch 0)")
        if d not in steps_of:
            steps_of[d] = [_exp_of(z, d) for z, _, _, _, _ in terms]
        E = [ball_mul(x, y) for x, y in zip(E, steps_of[d])]
        a += d
        d = min(2 * d, Fraction(8))
    require(False, f"bernstein: f not proved positive within {MAX_STEPS} steps (p* dominates too weakly)")
