"""The radius of absolute monotonicity of a rational stability function with poles
(paper, Section 3.2; the definition and the polynomial case:
:mod:`exactinv.monotonicity.radius`).

*Rational functions with poles*: infinitely many c_j matter.  With
d_j(kappa) = c_j(kappa) h(-kappa)^(j+1), a polynomial with the sign of c_j,
the engine argues in four exact or certified steps:

1. Pringsheim: if all c_j(kappa) >= 0, the nearest singularity of r to
   -kappa lies on the positive real axis.  So without a positive real pole
   rho = 0; a witness j with c_j(0) < 0 is found by exact series expansion.
2. Let p* be the smallest positive real pole, of multiplicity mu.  Its
   principal part dominates the tail, so it must have the right sign:
   a_mu (-1)^mu > 0 where r ~ a_mu/(z - p*)^mu; otherwise rho = 0 (witness j).
3. Dominance: another pole z_k = a + ib (a < p*) is as close to -kappa as p* at
   kappa_k = (|z_k|^2 - p*^2)/(2(p* - a)) and closer beyond it, which again
   violates Pringsheim, so rho <= kappa_A = min_k kappa_k.  kappa_A is exact:
   a root of the tie polynomial (:mod:`exactinv.monotonicity.poles`), an algebraic
   condition isolated among that polynomial's real roots.
4. The tail: on [0, K] with K < kappa_A an explicit index N (Arb ball bounds
   on the partial fraction expansion) bounds where c_j, j >= N, is positive.
   The scan runs d_0, d_1, ... incrementally (Descartes' rule on [0, K]
   first, FLINT root isolation only where it is inconclusive); each sign
   change found below the current K lowers K and with it N.
5. The tie itself: if no coefficient ends below kappa_A and p* still wins
   there -- every tied pole has multiplicity < mu, or = mu with
   sum |b_{k,mu}| < b_{*,mu} -- the dominance bound holds uniformly on
   [0, kappa_A] with the tied poles at ratio 1, and rho = kappa_A
   (reason ``"tie"``, attained).  If the tied poles outweigh p*, some c_j
   turns negative below kappa_A and the scan finds it.

6. No tie (every other pole has Re z > p*, so no tail index is uniform in
   kappa): rho = oo iff r(-x) is completely monotone (Bernstein's theorem,
   :mod:`exactinv.monotonicity.bernstein`, reason ``"bernstein"``); when f >= 0 but
   c = lim r < 0, every c_j with j >= 1 is >= 0 for every kappa and c_0 =
   r(-kappa) decreases, so rho is the one positive root of g(-kappa) (reason
   ``"bernstein-root"``, no tail: the trapezoid); otherwise an exact witness
   c_j(K) < 0 gives the bound K for step 4.
7. An exactly balanced tie of two simple real poles (|b_a| = b_*, e.g.
   1/(1 - 2z/3 - z^2/4)): the closed form c_j = b_* w*^-(j+1) + b_a w_a^-(j+1)
   is >= 0 on [0, kappa*] (reason ``"balanced-tie"``); of several simple Gaussian-rational poles:
   :mod:`exactinv.monotonicity.balanced_tie` (the poles go into the claim).
8. Non-real poles with exactly p*'s real part are proved on the line (p* rational:
   :mod:`exactinv.monotonicity.line_poles`; p* irrational: :mod:`exactinv.monotonicity.line_algebraic`, in Q(p*)) and never
   tie; Bernstein then decides (for p* irrational with a balancing pair: the exact sign of b_*^2 - 4|b|^2 in Q(p*),
   or f >= 0 line by line).

Undecided (documented, never a guess; docs/design.md): (a) an exact balance
with more poles, or (b) tied poles that outweigh p* with no c_j, j < 600,
negative below kappa_A -- the positivity problem of linear recurrences with
several dominant characteristic roots, open in general; (c) f touching 0 with
exponents not all rational -- the continuous positivity problem, open in
general; (d) p* irrational with line poles that balance it and neither one pair with b_*^2 < 4|b|^2 nor the
line-by-line proof (several pairs on the line, a multiple pole, a conjugate line negative somewhere: f touches 0,
the continuous positivity problem); an exact balance of several poles that are not all Gaussian
rationals (:mod:`exactinv.monotonicity.balanced_tie` decides the rest).
The value is exact (Fraction, RealAlgebraic, 0 or INF) and the result
records the argument; the kernel re-proves it (exactinv_check.tail, .tie).
"""

from __future__ import annotations

from fractions import Fraction
from math import comb

import flint

from exactinv_check.format import MAX_ALGEBRAIC_DEGREE, MAX_COEFFICIENTS, RadiusReason

from ..core.algebraic import ExactKey, Real
from ..core.flintq import dyadic_of, fmpq_of, fraction_of
from ..core.polys import count_real_roots, integer_part, no_root_between, sign_at, sign_right_of, sign_variations
from ..core.real_algebraic import RealAlgebraic
from ..core.roots import nonnegative_until, real_roots
from ..core.scalars import INF
from ..errors import Undecided
from ..model.methods import Method
from .balanced_tie import balanced_tie
from .bernstein import completely_monotone
from .kernel_price import priced
from .line_algebraic import on_line_indices_algebraic
from .line_poles import on_line_indices
from .poles import PoleStructure, ambiguous_line_poles, dominance_tie, pole_structure, precision, tail_index
from .result import AbsoluteMonotonicityRadius

_WITNESS_SCAN = 4000  # series terms scanned for a negative c_j(0)
_MAX_SCAN = 600  # coefficients scanned for a sign change below kappa_A when p* loses the tie
_MAX_SCAN_NO_TIE = 96  # ... when no pole ever gets as close as p* (rho = oo is then the likely answer)
_BITS = 256  # Arb working precision
_MAX_INDEX = MAX_COEFFICIENTS  # the kernel's bound: a longer scan could not be certified
_MAX_VALUE_DEGREE = MAX_ALGEBRAIC_DEGREE  # the kernel's bound on a certificate's algebraic value (priced by size above 200)


def _negative_coefficient_at_zero(method: Method) -> int | None:
    """The least j < _WITNESS_SCAN with c_j(0) < 0 (exact series of g/h at 0, stopping at the first)."""
    g, h = method.numerator, method.denominator
    c: list[Fraction] = []
    for j in range(_WITNESS_SCAN):
        value = g[j] if j < len(g) else Fraction(0)
        for i in range(1, min(j, len(h) - 1) + 1):
            value -= h[i] * c[j - i]
        if value < 0:
            return j
        c.append(value)  # h[0] = 1
    return None


def _zero_radius(method: Method, reason: RadiusReason, pole=None) -> AbsoluteMonotonicityRadius:
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


def coefficient_polynomials(method: Method):
    """d_0, d_1, ... incrementally (:func:`exactinv.monotonicity.radius.taylor_coefficient_polynomials`
    lists the first ones): with G, H the coefficients of g(w - kappa), h(w - kappa) in w
    (polynomials in kappa), d_j = G_j H_0^j - sum_{i=1}^{min(j, deg h)} H_i d_{j-i} H_0^(i-1):
    the coefficients of w^j in g(w - kappa) = r(w - kappa) h(w - kappa), with the c_j of
    r(w - kappa) scaled to d_j = c_j H_0^(j+1).

    >>> import itertools, exactinv as ei
    >>> [str(d) for d in itertools.islice(coefficient_polynomials(ei.methods.PRESETS["backward_euler"]()), 3)]
    ['1', '1', '1']
    """
    kappa = flint.fmpq_poly([0, 1])

    def shifted(coeffs):  # [w^i] p(w - kappa) as polynomials in kappa
        return [sum((flint.fmpq_poly([fmpq_of(coeffs[k] * comb(k, i))]) * (-kappa) ** (k - i)
                     for k in range(i, len(coeffs))), flint.fmpq_poly([0])) for i in range(len(coeffs))]

    G, Hs = shifted(method.numerator), shifted(method.denominator)
    d, powers, j = [], [flint.fmpq_poly([1])], 0
    while True:
        while len(powers) <= j:
            powers.append(powers[-1] * Hs[0])
        value = (G[j] if j < len(G) else flint.fmpq_poly([0])) * powers[j]
        for i in range(1, min(j, len(Hs) - 1) + 1):
            value -= Hs[i] * d[j - i] * powers[i - 1]
        d.append(value)
        yield value
        j += 1


def _nonnegative_on(d: flint.fmpq_poly, K: Fraction | None) -> bool:
    """True proves d >= 0 on [0, K] ([0, oo) for None): positive right of 0 and, by Descartes' rule,
    no root in (0, K).  False means: not proved (the caller then locates the sign change exactly)."""
    if d.is_zero():
        return True
    if sign_right_of(d, Fraction(0)) < 0:
        return False
    if K is None:
        return sign_variations(d.coeffs()) == 0
    return K == 0 or no_root_between(d, Fraction(0), K)


def _first_end(d: flint.fmpq_poly) -> Real:
    """sup{T : d >= 0 on [0, T]} (d >= 0 just right of 0 or not): 0, INF or the least positive root of
    odd multiplicity -- Descartes' rule, then Vincent-Collins-Akritas bisection on the odd part
    (:func:`exactinv.core.roots.nonnegative_until`).  (Isolating every complex root of d_j in Arb, as before,
    took over ten minutes for a d_j of degree ~300 from tests/monotonicity/test_line_poles.py's random tie family.)  An algebraic
    end is refined to 64 relative bits: the bound K = its 48-bit upper end sets the tail index."""
    end = nonnegative_until(d, 0)
    return end.refine_relative(64) if isinstance(end, RealAlgebraic) else end


def rational_radius(method: Method) -> AbsoluteMonotonicityRadius:
    """The exact radius of absolute monotonicity of a rational r = g/h with poles (see the module
    docstring): 0, a positive algebraic number or oo with the reason that decides it, or Undecided.

    >>> from fractions import Fraction
    >>> import exactinv as ei
    >>> r = rational_radius(ei.methods.rational([Fraction(1), Fraction(1, 2)], [Fraction(1), Fraction(-1, 2)]))
    >>> r.value, r.reason                                   # the trapezoid: c = -1, f = 4 e^(-2t) >= 0
    (Fraction(2, 1), 'bernstein-root')
    """
    h = method.h
    positive = [(z, m) for z, m in real_roots(h) if z > 0]
    if not positive:
        return _zero_radius(method, RadiusReason.NO_POSITIVE_POLE)
    p_star, mu = positive[0]
    h_mu = h
    for _ in range(mu):
        h_mu = h_mu.derivative()
    if _sign_at_real(method.g, p_star) * _sign_at_real(h_mu, p_star) * (-1) ** mu <= 0:
        return _zero_radius(method, RadiusReason.PRINCIPAL_PART_SIGN, p_star)
    with precision(_BITS):
        s = _with_line_poles(method, p_star)
        tie = dominance_tie(s, h, exact=False)
        if tie is not None and tie.kappa < 0:
            return _zero_radius(method, RadiusReason.DOMINANCE_AT_0, p_star)
        return priced(_decide(method, s, tie, p_star))


def _with_line_poles(method: Method, p_star) -> PoleStructure:
    """The pole structure, with every non-real pole whose real part Arb cannot separate from p*'s proved to be
    p* + iy exactly (exactinv.monotonicity.line_poles); the precision is raised (to 4096 bits) for a pole that is not
    on the line (p* rational: exactinv.monotonicity.line_poles; p* irrational: exactinv.monotonicity.line_algebraic, in Q(p*))."""
    bits = _BITS
    while True:
        with precision(bits):
            s = pole_structure(method.numerator, method.denominator, p_star)
            left = ambiguous_line_poles(s)
            if not left:
                return s
            if isinstance(p_star, Fraction):
                proved = on_line_indices(method.h, p_star, s.balls, left)
            else:  # p* irrational: the line is proved in Q(p*) (exactinv.monotonicity.line_algebraic)
                boxes = {k: _box(s.balls[k][0]) for k in left}
                proved = on_line_indices_algebraic(method.h, p_star, boxes, left)
            s = PoleStructure(s.balls, s.star, s.mu, proved)
            if len(proved) == len(left):
                break
        if bits >= 4096:
            raise Undecided(f"absolute monotonicity of {method.name}: a non-real pole's real part is neither proved "
                            f"equal to p* = {p_star} nor separated from it at {bits} bits")
        bits *= 4
    return s  # balls from a higher precision stay valid enclosures at _BITS


def _box(z: flint.acb) -> tuple[Fraction, Fraction, Fraction, Fraction]:
    """Rationals (re_lo, re_hi, im_lo, im_hi) bounding an Arb box exactly (Arb's ends are dyadic)."""
    return (dyadic_of(z.real.lower()), dyadic_of(z.real.upper()), dyadic_of(z.imag.lower()), dyadic_of(z.imag.upper()))


def _tie_positive(s, tie) -> bool | None:
    """At kappa_A, does p* still win?  True: every tied pole has multiplicity < mu, or = mu with
    sum |b_{k,mu}| < b_{*,mu}; False: it loses (a tied pole dominates, so c_j(kappa_A) < 0 for some j
    when the tied poles are one non-real pair or a negative real pole); None: not separated."""
    mu, b_mu = s.mu, s.balls[s.star][2][s.mu - 1].real
    if any(s.balls[k][1] > mu for k in tie.tied):
        return False
    total = sum((abs(s.balls[k][2][mu - 1]) for k in tie.tied if s.balls[k][1] == mu), flint.arb(0))
    if total < b_mu:
        return True
    return False if total > b_mu else None


def _decide(method, s, tie, p_star) -> AbsoluteMonotonicityRadius:
    """Scan d_0, d_1, ... for the first end of nonnegativity below the current bound K (Descartes on
    [0, K] first, exact location only when it fails), with the tail index N bounded before the scan.
    An exact kappa_A <= 0 is no tie (rho is a sup over kappa >= 0): rho = 0, not attained, by a witness
    c_j(0) < 0 (Undecided without one)."""
    first = max(len(method.numerator) - len(method.denominator) + 1, 1)
    positive_tie = None if tie is None else _tie_positive(s, tie)
    balanced, listed = _balanced_tie_kappa(method) if tie is not None and positive_tie is None else (None, ())
    if tie is not None and positive_tie is None and balanced is None:
        raise Undecided(f"absolute monotonicity of {method.name}: at kappa_A the tied poles' principal parts "
                        "balance p*'s (sum |b_k,mu| = b_*,mu to working precision) and the closed form does not apply "
                        "(decided when every pole is simple and a Gaussian rational with the other poles real, positive "
                        "and b_k > 0): the tied part of c_j(kappa_A) can vanish for infinitely many j, and the sign of "
                        "the rest there is the positivity problem for linear recurrences (open in general)")
    bound = None if tie is None else _short_upper(dyadic_of(tie.kappa.upper()))  # rational K >= the bound
    exact_bound = None
    tied = ()
    N = None
    if positive_tie:
        exact_bound = dominance_tie(s, method.h, exact=True).kappa
        if not ExactKey(Fraction(0)) < ExactKey(exact_bound):  # kappa_A <= 0: kappa = 0 decides, not a tie
            return _zero_radius(method, RadiusReason.DOMINANCE_AT_0, p_star)
        bound, tied = _short_upper(exact_bound), tie.tied
        N = tail_index(s, bound, first, tied)
    if balanced is not None:  # c_j >= 0 on [0, kappa*] for j > deg q by the closed form: scan the first ones only
        bound = exact_bound = balanced
        N = max(len(method.numerator), len(method.denominator))
    verdict = None
    if tie is None:  # every other pole has Re z > p*: rho = oo or a witness c_j(K) < 0 (Bernstein)
        infinite = _infinite_radius_certificate(method, s.balls, s.star)
        if infinite is not None:
            return AbsoluteMonotonicityRadius(INF, True, infinite, method, pole=p_star)
        verdict = completely_monotone(method.numerator, method.denominator, s, _BITS, p_star)
        if verdict.infinite:
            return AbsoluteMonotonicityRadius(INF, True, RadiusReason.BERNSTEIN, method, pole=p_star)
        if verdict.root:  # c < 0, f >= 0: c_j >= 0 for j >= 1 and every kappa, c_0 = r(-kappa) decreases
            return AbsoluteMonotonicityRadius(_first_end(g_minus(method)), True, RadiusReason.BERNSTEIN_ROOT, method,
                                              pole=p_star)
        if verdict.finite and verdict.bound is None:
            raise Undecided(f"absolute monotonicity of {method.name}: rho < oo is proved (r(-x) is not completely "
                            f"monotone: {verdict.how}), but no exact witness c_j(K) < 0 bounds it for the certified "
                            "scan (the binding coefficient index lies beyond the searched j <= 8192)")
        if not verdict.finite:
            line = ("; poles on Re z = p* balance p* exactly here, so e^(p* t) f(t) comes arbitrarily close to 0 and "
                    "deciding its sign is the continuous positivity problem (open in general)") if s.on_line else ""
            raise Undecided(f"absolute monotonicity of {method.name}: every other pole has Re z >= p*, so rho = oo "
                            f"iff r(-x) is completely monotone (Bernstein's theorem), and that is not decided: "
                            f"{verdict.how}{line}")
        if verdict.bound is not None:  # rho < K = verdict.bound: the tail on [0, K] has an index
            bound = exact_bound = verdict.bound
            N = tail_index(s, bound, first)
            if N > _MAX_INDEX:
                raise Undecided(f"absolute monotonicity of {method.name}: rho < {verdict.bound} (c_{verdict.j} < 0 "
                                f"there), but the certified tail starts at j = {N} > {_MAX_INDEX} coefficients")
    value, binding, ds = None, None, []
    for j, d in enumerate(coefficient_polynomials(method)):
        if N is not None and j >= max(N, first):
            break
        if N is None and j >= (_MAX_SCAN if tie is not None else _MAX_SCAN_NO_TIE):
            return _undecided_scan(method, tie, verdict)
        ds.append(d)
        if _nonnegative_on(d, bound):
            continue
        end = _first_end(d)
        if end == INF:
            continue
        if exact_bound is None and tie is not None and _ambiguous(end, tie.kappa):
            exact_bound = dominance_tie(s, method.h, exact=True).kappa
        if exact_bound is not None and not ExactKey(end) < ExactKey(exact_bound):
            continue
        if exact_bound is None and tie is not None and not flint.arb(fmpq_of(_rational_upper(end))) < tie.kappa:
            continue
        if value is None or ExactKey(end) < ExactKey(value):
            value, binding, exact_bound = end, j, end
            bound, tied = _short_upper(end), ()
            N = tail_index(s, bound, first)
    return _finish(method, exact_bound, p_star, value, binding, ds, N, tie, balanced is not None, listed)


def g_minus(method: Method) -> flint.fmpq_poly:
    """g(-kappa) = d_0(kappa): its one positive root is rho for reason ``bernstein-root``.

    >>> from exactinv.model import methods
    >>> g_minus(methods.trapezoid())          # 1 + z/2 at z = -kappa
    (-1/2)*x + 1
    """
    return flint.fmpq_poly([fmpq_of(c * (-1) ** k) for k, c in enumerate(method.numerator)])


def _ambiguous(end, ball: flint.arb) -> bool:
    """Is end < kappa_A (an Arb ball) undecided after refining end's enclosure?"""
    for bits in (0, 32, 64, 128, 256, 512):
        if bits and isinstance(end, RealAlgebraic):
            end.refine(bits)
        lo, hi = (end.lower, end.upper) if isinstance(end, RealAlgebraic) else (end, end)
        if flint.arb(fmpq_of(hi)) < ball or flint.arb(fmpq_of(lo)) > ball:
            return False
    return True


def _undecided_scan(method, tie, verdict=None) -> AbsoluteMonotonicityRadius:
    if tie is None:
        raise Undecided(f"absolute monotonicity of {method.name}: every other pole has Re z > p*, so rho = oo iff "
                        "r(-x) is completely monotone (Bernstein), and that was not decided: "
                        f"{verdict.how if verdict is not None else 'no verdict'}; "
                        f"c_0 .. c_{_MAX_SCAN_NO_TIE - 1} are nonnegative for every kappa >= 0")
    raise Undecided(f"absolute monotonicity of {method.name}: rho <= kappa_A = {float(tie.kappa.mid()):.6g}, where "
                    f"{len(tie.tied)} other pole(s) reach p*'s distance from -kappa and outweigh it; no c_j with "
                    f"j < {_MAX_SCAN} turns negative below kappa_A.  Deciding this is the positivity problem for a "
                    "linear recurrence with several dominant characteristic roots (open in general)")


def _balanced_tie_kappa(method: Method) -> tuple[Fraction | None, tuple]:
    """(kappa*, ()) when r has exactly two simple poles p* > 0 > a, |a| > p*, whose residues balance
    exactly, |b_a| = b_* (exactinv_check.tie.balanced_tie has the proof); (kappa*, poles) for a balanced tie of
    several Gaussian-rational simple poles (:mod:`exactinv.monotonicity.balanced_tie`, the poles listed in the
    certificate); else (None, ()).  With s = sqrt(D) the two poles are (-h1 +- s)/(2 h2), g there is
    G0 +- G1 s, h' = +-s, and |b_+| = |b_-| iff G0 = 0 or G1 = 0."""
    h, g = method.denominator, method.numerator
    if len(h) != 3:
        several = balanced_tie(g, h)
        return (None, ()) if several is None else several
    h0, h1, h2 = h
    D = h1 * h1 - 4 * h0 * h2
    if D <= 0 or h0 / h2 >= 0 or -h1 / h2 >= 0:
        return None, ()
    x, y = Fraction(0), Fraction(0)
    zr, zs = -h1 / (2 * h2), 1 / (2 * h2)
    for c in reversed(g):
        x, y = x * zr + y * zs * D + c, x * zs + y * zr
    return (h1 / (2 * h2), ()) if x == 0 or y == 0 else (None, ())


def _finish(method, kappa_A, p_star, value, binding, ds, N, tie=None, balanced=False, listed=()) -> AbsoluteMonotonicityRadius:
    if value is None and tie is None:  # cannot happen: a witness c_j(K) < 0 has j < N
        raise Undecided(f"absolute monotonicity of {method.name}: no coefficient ends below the witness bound")
    if value is None and balanced:  # the closed form covers every c_j beyond the scanned ones
        return AbsoluteMonotonicityRadius(kappa_A, True, RadiusReason.BALANCED_TIE, method, pole=p_star, poles=listed)
    if value is None:  # no coefficient ends below kappa_A, and p* wins the tie there
        return AbsoluteMonotonicityRadius(kappa_A, True, RadiusReason.TIE, method, tail_index=N, pole=p_star)
    attained = value != 0 or all(p(0) >= 0 for p in ds)
    if not attained:  # rho = 0 with some c_j(0) < 0: that witness is the whole certificate (no tail needed)
        return _zero_radius(method, RadiusReason.NEGATIVE_AT_0, p_star)
    if isinstance(value, RealAlgebraic) and value.poly.degree() > _MAX_VALUE_DEGREE:
        raise Undecided(f"absolute monotonicity of {method.name}: rho is the first end of c_{binding}, a root of an "
                        f"irreducible polynomial of degree {value.poly.degree()} > {_MAX_VALUE_DEGREE}, beyond the "
                        "kernel's polynomial bound, so no certificate of it could be verified (a resource limit, "
                        "not an open problem)")
    coeffs = tuple(tuple(fraction_of(c) for c in p.coeffs()) for p in ds[: binding + 1])
    return AbsoluteMonotonicityRadius(value, attained, RadiusReason.COEFFICIENT, method, binding, tail_index=N, pole=p_star,
                                      coefficients=coeffs)


def _rational_upper(v) -> Fraction:
    return v.upper if isinstance(v, RealAlgebraic) else v


def _short_upper(v, bits: int = 48) -> Fraction:
    """A short dyadic >= v (>= 0): Descartes tests on [0, K] stay cheap with a short K."""
    q = _rational_upper(v)
    if q <= 0:
        return Fraction(0) if q == 0 else q
    scale = 1 << max(0, bits - max(q.numerator.bit_length() - q.denominator.bit_length(), 0))
    return Fraction(-((-q.numerator * scale) // q.denominator), scale)


def _infinite_radius_certificate(method: Method, balls, star) -> str | None:
    """Why rho = INF, if a sufficient certificate applies:
    ``product``  -- r = prod (1 - z/p_k)^(-m_k) with all p_k > 0 (each factor and
                    so the product is absolutely monotonic on (-oo, 0]);
    ``termwise`` -- deg g <= deg h, all poles real and positive, every
                    b_{k,m} > 0 and c = lim r >= 0: each c_j is a sum of terms >= 0."""
    if not all(z.imag.is_zero() and z.real > 0 for z, _, _ in balls):
        return None
    if len(method.numerator) == 1:
        return RadiusReason.PRODUCT
    at_infinity = method.numerator[-1] / method.denominator[-1] if len(method.numerator) == len(method.denominator) else 0
    if len(method.numerator) <= len(method.denominator) and at_infinity >= 0 \
            and all(v.real > 0 for _, _, b in balls for v in b):
        return RadiusReason.TERMWISE
    return None
