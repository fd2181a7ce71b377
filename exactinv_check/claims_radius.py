"""The radius of absolute monotonicity (paper, Definition 3.11, erratum E1).

rho(r) = sup{kappa >= 0 : r has no pole in [-kappa, 0] and c_j(kappa) >= 0 for
all j >= 0}, c_j(kappa) = r^(j)(-kappa)/j!.  With h(0) > 0 and
d_j(kappa) = c_j(kappa) h(-kappa)^(j+1), a polynomial in kappa with the sign of
c_j wherever h(-kappa) > 0, the kernel proves rho by recomputation:

* rho = 0 (not attained) by an index j with c_j(0) < 0: then kappa = 0 itself
  fails (exact series of g/h at 0);
* rho = oo for r = c / prod (1 - z/p_k)^(m_k), c > 0, every p_k real and
  positive: a product of absolutely monotonic factors (exact root counts);
* rho = oo by Bernstein's theorem (reason "bernstein"): r(-x) = c + int e^(-xt) f(t) dt
  with c >= 0 and the exponential polynomial f >= 0 on (0, oo), proved by
  :func:`exactinv_check.bernstein.prove_completely_monotone` (exact Sturm count for one
  pole; Taylor at 0, disk-arithmetic steps and a dominance bound otherwise);
* rho = the one positive root of g(-kappa) (reason "bernstein-root", attained): c = lim r < 0 and f >= 0
  proved as for "bernstein", so every c_j, j >= 1, is >= 0 for every kappa >= 0 and c_0 = r(-kappa) decreases
  from 1 to c (no tail, no coefficient scan: e.g. the trapezoid, rho = 2);
* otherwise: the tail j >= N is proved positive on [0, K] (K >= the claimed
  rho, or all kappa >= 0 for rho = oo) by :func:`exactinv_check.tail.prove_tail`,
  and rho is recomputed as the least of sup{T : d_j >= 0 on [0, T]} (j < N)
  and the first kappa > 0 where h(-kappa) = 0.  For a polynomial method only
  c_0 .. c_p are nonzero, so no tail exists (N = p + 1).
The set of admissible kappa is the interval [0, rho], closed unless a pole sits
at -rho or rho = 0 is itself inadmissible.
"""

from __future__ import annotations

from fractions import Fraction
from math import comb, gcd, isqrt
from typing import Any, Sequence

from . import poly_arithmetic, polys
from .balanced_tie import prove_balanced_tie
from .bernstein import prove_completely_monotone, prove_density_nonnegative
from .budget import (
    FRACTION_WEIGHT,
    MAX_COEFFICIENTS,
    MAX_POLES,
    PYTHON_OP,
    SCAN_BUDGET,
    charge,
    within_budget,
    within_sturm_budget,
    words,
)
from .claims_thresholds import smallest_positive_root
from .failure import require, require_budget
from .format import RadiusReason
from .rationals import describe, integer, vector
from .reals import Real
from .tail import prove_tail, reduced
from .tie import balanced_tie
from .validset import first_end

REASONS = frozenset(RadiusReason)  # the format's radius reasons (exactinv_check.format)
SERIES_DISCOUNT = 8  # step_cost counts schoolbook word products; measured 2.4e8 to 3.4e8 of them a second (CPython
# multiplies large numbers by Karatsuba): / 8 gives the budget's 3e7 to 4e7 word operations a second
ZERO_REASONS = {"no-positive-pole", "principal-part-sign", "dominance-at-0", "negative-at-0"}


def scan_cost(num: Sequence[Fraction], den: Sequence[Fraction], count: int) -> Any:
    """Estimated word operations of d_0 .. d_{count-1}: d_j has degree about (j + 1) d, d = max(deg g, deg h), and
    numbers of about j d (bits of g, h) bits; the series division by h costs about j (deg h)^3 products of them
    (calibrated on Pade(2, 3) and Pade(6, 5): 10^8 is a few seconds of work), the shifts G_j of g about deg g + 1
    products each.  (Charging the division by deg g too priced a polynomial method of degree 25, NodePy's
    SSPRK3(25), at 4.8e10 where its d_j take 0.06 s; a polynomial has no division, only its shifts.)"""
    dg, dh = len(num) - 1, len(den) - 1
    bits = max(abs(c).bit_length() for c in poly_arithmetic.integer_coefficients(num) + poly_arithmetic.integer_coefficients(den))
    division = count * count * dh ** 3 * (FRACTION_WEIGHT + count * max(dg, dh, 1) * bits // 8) // 2
    shifts = count * (dg + 1) * (FRACTION_WEIGHT + words(bits + count))
    return division + shifts


def d_polynomials(num: Any, den: Any, count: Any) -> Any:
    """d_0 .. d_{count-1}, d_j(kappa) = c_j(kappa) h(-kappa)^(j+1), by series division at -kappa, in integers:
    with G = L g, H = L h integral (L the common denominator), D_j = c_j H(-kappa)^(j+1) = L^(j+1) d_j satisfies
    D_j = G_j P^j - sum_{i=1..j} H_i D_(j-i) P^(i-1), P = H_0 = H(-kappa), G_i, H_i = [w^i] of G, H at w - kappa
    (integer polynomials in kappa: binomials), so no Fraction gcd runs until the d_j are formed.  Products are
    Kronecker substitutions (CPython's Karatsuba), each charged by its size as it runs (:func:`kronecker_cost`).
    Gated first by scan_cost <= SCAN_BUDGET (absurd sizes; the old Fraction algorithm's price, an over-estimate)."""
    require(count <= MAX_COEFFICIENTS, f"more than {MAX_COEFFICIENTS} coefficients requested")
    estimate = scan_cost(num, den, count)
    require_budget(estimate <= SCAN_BUDGET, f"over the kernel's work budget: the coefficient polynomials d_0 .. "
                   f"d_{count - 1} (estimated {estimate:.2e} word operations > {SCAN_BUDGET:.0e})")
    L = 1
    for x in [*num, *den]:
        L = L * x.denominator // gcd(L, x.denominator)
    Gi, Hi = [int(x * L) for x in num], [int(x * L) for x in den]
    G = [_shift_integers(Gi, i) for i in range(max(len(num), count))]
    H = [_shift_integers(Hi, i) for i in range(len(den))]
    powers: list[list[int]] = [[1]]
    D: list[Any] = []
    for j in range(count):
        while len(powers) <= j:
            powers.append(kronecker_mul(powers[-1], H[0]))
        value = kronecker_mul(G[j], powers[j]) if j < len(G) else []
        for i in range(1, min(j, len(H) - 1) + 1):
            if H[i] and D[j - i]:
                value = _sub_integers(value, kronecker_mul(kronecker_mul(H[i], D[j - i]), powers[i - 1]))
        D.append(poly_arithmetic.trim(value))
    out, scale = [], 1
    for Dj in D:
        scale *= L
        charge(len(Dj) * (FRACTION_WEIGHT + 2 * words(max((abs(c).bit_length() for c in Dj), default=0)) ** 2),
               "a coefficient polynomial d_j (its Fractions)")
        out.append([Fraction(c, scale) for c in Dj])
    return out


def _shift_integers(p: Sequence[int], i: int) -> Any:
    """[w^i] p(w - kappa) as an integer polynomial in kappa: sum_k p_k C(k, i) (-kappa)^(k-i)."""
    return poly_arithmetic.trim([p[k] * comb(k, i) * (-1) ** (k - i) for k in range(i, len(p))])


def _sub_integers(a: Sequence[int], b: Sequence[int]) -> Any:
    n = max(len(a), len(b))
    return poly_arithmetic.trim([(a[k] if k < len(a) else 0) - (b[k] if k < len(b) else 0) for k in range(n)])


def kronecker_cost(words_a: int, words_b: int) -> int:
    """Word operations of a product of integers of ``words_a`` <= ``words_b`` words (CPython's Karatsuba: about
    27 ns times words^1.585, measured; 6 words_b isqrt(words_a) bounds it at RATE) plus packing and unpacking."""
    small, large = sorted((max(1, words_a), max(1, words_b)))
    return PYTHON_OP + 6 * large * isqrt(small) + 8 * (small + large)


def _pack(a: Sequence[int], size: int) -> int:
    """sum a_i 256^(size i) for integers |a_i| < 256^size / 2 (the positive and negative parts packed apart)."""
    pos = b"".join((c if c > 0 else 0).to_bytes(size, "little") for c in a)
    neg = b"".join((-c if c < 0 else 0).to_bytes(size, "little") for c in a)
    return int.from_bytes(pos, "little") - int.from_bytes(neg, "little")


def kronecker_mul(a: Sequence[int], b: Sequence[int]) -> list[int]:
    """a b for integer polynomials (lists from x^0 up), by Kronecker substitution: pack each into one integer at
    2^k per coefficient (k bits hold every coefficient of the product and its sign), multiply once, unpack the
    signed digits.  Charged by the sizes (:func:`kronecker_cost`)."""
    if not a or not b:
        return []
    bits = max(abs(c).bit_length() for c in a) + max(abs(c).bit_length() for c in b) + min(len(a), len(b)).bit_length() + 2
    charge(kronecker_cost(len(a) * bits // 64, len(b) * bits // 64) + PYTHON_OP * (len(a) + len(b)),
           "a product of integer polynomials")
    size = (bits + 7) // 8  # bytes per coefficient: packing and unpacking are linear (bytes, not shifts)
    n = len(a) + len(b) - 1
    half = 1 << (8 * size - 1)
    z = _pack(a, size) * _pack(b, size) + int.from_bytes(half.to_bytes(size, "little") * n, "little")
    data = z.to_bytes(size * n, "little")  # every digit offset by half: nonnegative, below 2 half
    out = [int.from_bytes(data[i * size:(i + 1) * size], "little") - half for i in range(n)]
    return out


def sign_at_zero(num: Any, den: Any, j: Any) -> Any:
    """The exact sign of c_j(0) = [z^j] g/h, in integers (no Fraction gcds: a witness index up to
    MAX_COEFFICIENTS costs well under a second).  With G = L g, H = L h integral, c_k = u_k / H_0^(k+1) where
    u_k = G_k H_0^k - sum_{i=1..k} H_i u_{k-i} H_0^(i-1)  (multiply H_0 c_k = G_k - sum H_i c_{k-i} by H_0^k).
    Priced first: (j + 1)^2 deg h (bits of G, H) / 128 word operations."""
    L = 1
    for x in [*num, *den]:
        L = L * x.denominator // gcd(L, x.denominator)
    G, H = [int(x * L) for x in num], [int(x * L) for x in den]
    bits = max(abs(c).bit_length() for c in G + H) + len(H).bit_length()  # u_k has about k bits bits
    # the products H_i u_(k-i) H_0^(i-1) multiply numbers of up to (j + 1) bits bits by H_0^(i-1), of up to deg h bits
    # bits: the price grows with deg h bits too (measured: 1.5e7 to 9e7 of these word operations a second).  The old
    # price, (j + 1)^2 deg h bits / 128, was 5 to 15 times low: a 12 KB certificate (deg h 64, 300-bit coefficients,
    # j = 796; priced 7e7) ran two minutes.
    terms = min(j + 1, len(H) - 1)
    within_budget((j + 1) ** 2 * len(H) * bits // 128 * (4096 + terms * bits) // 4096,
                  f"the series coefficients c_0(0) .. c_{j}(0)")
    H0 = [H[0] ** i for i in range(len(H))]
    h_words = [words(abs(x).bit_length()) for x in H]
    p_words = [words(abs(x).bit_length()) for x in H0]
    u: list[Any] = []
    u_words: list[int] = []
    power = 1  # power = H_0^k, kept (not recomputed at every k)
    for k in range(j + 1):
        # charged as it runs (the up-front price was 4 to 5 times low: 1e8 ran 10 s of CPU, deg h = 3 with
        # 1660-digit coefficients, j = 369; no charge inside the loop, so the clock could not stop it either)
        charge(step_cost(k, h_words, p_words, u_words, words(power.bit_length())), "a series coefficient c_k(0)")
        v = G[k] * power if k < len(G) else 0
        for i in range(1, min(k, len(H) - 1) + 1):
            v -= H[i] * u[k - i] * H0[i - 1]
        u.append(v)
        u_words.append(words(abs(v).bit_length()))
        power *= H[0]
    return poly_arithmetic.sign(u[j]) * poly_arithmetic.sign(H[0]) ** (j + 1)


def step_cost(k: int, h_words: list[int], p_words: list[int], u_words: list[int], power_words: int) -> int:
    """Word operations of step k of :func:`sign_at_zero`: the products H_i u_(k-i) and their products by
    H_0^(i-1) (schoolbook, the words of both factors; CPython's Karatsuba does less on large numbers, so an
    upper estimate), G_k H_0^k and H_0^(k+1)."""
    cost = PYTHON_OP + 2 * power_words * h_words[0]
    for i in range(1, min(k, len(h_words) - 1) + 1):
        cost += PYTHON_OP + h_words[i] * u_words[k - i] + (h_words[i] + u_words[k - i]) * p_words[i - 1]
    return cost // SERIES_DISCOUNT


def _all_roots_real_positive(h: Any) -> Any:
    """Every root of h (with multiplicity) is real and positive."""
    p = poly_arithmetic.trim(h)
    total, k = 0, 1
    a = poly_arithmetic.gcd(p, poly_arithmetic.derivative(p))
    b = poly_arithmetic.divmod_(p, a)[0]
    d = poly_arithmetic.sub(poly_arithmetic.divmod_(poly_arithmetic.derivative(p), a)[0], poly_arithmetic.derivative(b))
    while len(b) > 1:
        factor = poly_arithmetic.gcd(b, d)
        if len(factor) > 1:
            total += k * len(polys.positive_roots(factor))
        b = poly_arithmetic.divmod_(b, factor)[0]
        d = poly_arithmetic.sub(poly_arithmetic.divmod_(d, factor)[0], poly_arithmetic.derivative(b))
        k += 1
    return total == len(p) - 1


def _positive_up_to(p: Sequence[Fraction], K: Fraction) -> bool:
    """True proves p > 0 on (0, K] (its first end lies beyond K): positive right of 0 and at K, and no
    root in (0, K) by Descartes' rule.  False says nothing."""
    return polys.sign_right_of(p, Fraction(0)) > 0 and polys.sign_at(poly_arithmetic.integer_coefficients(p), K) > 0 \
        and polys.no_root_in(p, K, depth=1)


def recompute(num: Any, den: Any, count: Any, K_is_infinite: bool, K: Fraction | None = None,
              binding: int | None = None) -> Any:
    """(rho, attained, ends) from d_0 .. d_{count-1} and the poles on the negative axis.  With a finite K
    the caller requires rho <= K: d_j proved positive on (0, K] cannot end the interval first and are set
    aside, and a guard 2K + 1 - kappa (ending beyond K) bounds the root isolation of the others.  ``binding``
    (the claim's, untrusted) only orders the work: d_binding is isolated first, so the others are mostly cleared
    by one Descartes test against its tight end (the minimum is the same in any order)."""
    d = d_polynomials(num, den, count)
    live = [p for p in d if p]
    if K is not None:
        guard = [2 * K + 1, Fraction(-1)]
        live = [guard] + [p for p in live if not (K > 0 and _positive_up_to(p, K))]
    early = live[:1] if K is not None else []
    if binding is not None and 0 <= binding < len(d) and d[binding]:
        early.append(d[binding])
    rho, _ = first_end([Fraction(1)], live, [], first=early, remember=True)
    attained = True
    if rho.is_zero():  # kappa = 0 is admissible iff every c_j(0) >= 0
        attained = all(poly_arithmetic.evaluate(p, Fraction(0)) >= 0 for p in d)
    h_minus = [c * (-1) ** k for k, c in enumerate(den)]  # h(-kappa)
    if len(poly_arithmetic.trim(h_minus)) > 1:
        roots = polys.positive_roots(h_minus)
        if roots:
            pole = Real.root_in(h_minus, *roots[0])
            if pole.compare(rho) <= 0:
                rho, attained = pole, False
    return rho, attained, d


def _tie(num: Any, den: Any, value: Any, claim: Any) -> Any:
    """(rho, attained, d, N, count) for a tie claim: kappa* = value > 0 (rho is a sup over kappa >= 0, and
    rho = 0 has its own reasons), proved a tie (tail.prove_tail(tie=...)), the tail positive on [0, kappa*],
    no c_j (j < count) ending and no pole on the negative axis before kappa*: rho = kappa*, attained unless a
    pole sits at -kappa*."""
    require(not value.inf and value.compare(Real.rational(0)) > 0,
            "a tie radius is a positive kappa* (rho = 0 is certified by a witness c_j(0) < 0)")
    hint = claim.get("tail_index")
    hint = 0 if hint is None else integer(hint, "tail_index", 0, MAX_COEFFICIENTS)
    N = prove_tail(num, den, None, hint, tie=value)
    count = max(N, len(num), len(den), 1)
    first, attained, d = recompute(num, den, count, False, value.bounds()[1])
    if first.compare(value) < 0:  # the message only on failure: an algebraic number's text costs bisections
        require(False, f"a coefficient c_j (j < {count}) or a pole ends before the tie {value}")
    return value, attained if first.compare(value) == 0 else True, d, N, count


def short_above(q: Any, bits: Any=16) -> Any:
    """A rational >= q >= 0 with about ``bits`` significant bits (q itself when it is that short).  The coefficient
    route proves the tail and the d_j's signs on [0, K] for this K instead of the claimed rho's isolating bound: a
    larger K only asks more (sound), and Descartes tests on [0, K] cost with the bits of K (a genuine certificate,
    rho of degree 33 with a 150-bit bound, was rejected over the certificate's budget by those tests alone)."""
    if q <= 0:
        return Fraction(0)
    e = bits - (q.numerator.bit_length() - q.denominator.bit_length())
    short = Fraction(-(-q.numerator * 2 ** e // q.denominator), 2 ** e) if e >= 0 else \
        Fraction(-(-q.numerator // (q.denominator * 2 ** -e)) * 2 ** -e)
    return q if short.numerator.bit_length() + short.denominator.bit_length() >= \
        q.numerator.bit_length() + q.denominator.bit_length() else short


def _bernstein_root(num: Any, den: Any) -> Any:
    """(rho, sentence) for reason bernstein-root: c = lim r < 0, f >= 0 proved (prove_density_nonnegative; every
    pole then has Re z > 0), so c_j(kappa) = int t^j e^(-kappa t) f(t) dt/j! >= 0 for j >= 1 and every kappa >= 0,
    while c_0(kappa) = r(-kappa) = c + int e^(-kappa t) f(t) dt decreases strictly (f >= 0, not 0: r has a pole)
    from r(0) = 1 to c < 0.  So c_0 has exactly one zero on (0, oo), the only positive root of g(-kappa)
    (h(-kappa) > 0 there), and rho is that root, attained.  Cheap tests first: deg g <= deg h and c < 0 before the
    proof of f >= 0, and that before the root of g(-kappa) is isolated (priced by its Sturm sequence)."""
    g, h = reduced(num, den)
    require(len(g) <= len(h), "bernstein-root: deg g > deg h, so r(-x) has no finite limit c")
    c = g[-1] / h[-1] if len(g) == len(h) else Fraction(0)
    require(c < 0, f"bernstein-root: c = lim r(-x) = {describe(c)} >= 0, so c_0 never ends (a bernstein claim, rho = oo)")
    c_again, how = prove_density_nonnegative(g, h)
    require(c_again == c, "bernstein-root: inconsistent limit at infinity (internal)")
    g_minus = poly_arithmetic.trim([x * (-1) ** k for k, x in enumerate(g)])  # g(-kappa)
    ints = poly_arithmetic.integer_coefficients(g_minus)
    within_sturm_budget(len(ints) - 1, max(abs(x).bit_length() for x in ints), "bernstein-root: the root of g(-kappa)")
    rho = smallest_positive_root(g_minus)
    require(rho is not None, "bernstein-root: g(-kappa) has no positive root (internal: c < 0 < r(0) forces one)")
    return rho, (f"c = {describe(c)} < 0 and {how}: c_j >= 0 for j >= 1 and every kappa, c_0 = r(-kappa) decreases, "
                 f"so rho is the one positive root of g(-kappa)")


def absolute_monotonicity_radius(problem: Any, claim: Any, context: Any) -> Any:
    method = problem.method
    require(method is not None, "a method is needed")
    num, den = method.numerator, method.denominator
    attained = claim["attained"]
    reason = claim["reason"]
    require(isinstance(reason, str) and reason in REASONS, f"unknown reason {reason!r}")
    require(claim.get("witness_j") is None or reason in ZERO_REASONS, "witness_j belongs to the rho = 0 reasons only")
    require(claim.get("binding") is None or reason not in ZERO_REASONS | {"product", "tie", "bernstein", "balanced-tie",
                                                                           "bernstein-root"},
            "binding belongs to the coefficient reasons only")
    require(claim.get("poles") is None or reason == "balanced-tie", "poles belongs to the balanced-tie reason only")
    require(not method.is_polynomial or reason in ("coefficient", "all-coefficients"),
            f"{reason!r} is not a reason for a polynomial")
    value = Real.parse(claim["value"], "rho")  # after the cheap tests: parsing may isolate a root
    if method.is_polynomial:
        require(reason in ("coefficient", "all-coefficients"), f"{reason!r} is not a reason for a polynomial")
        rho, rho_attained, d = recompute(num, den, len(num), True)
        how = f"recomputed from c_0 .. c_{len(num) - 1}"
    elif reason in ZERO_REASONS:
        j = integer(claim["witness_j"], "witness_j", 0, MAX_COEFFICIENTS)
        require(sign_at_zero(num, den, j) < 0, f"c_{j}(0) is not negative")
        rho, rho_attained, d = Real.rational(0), False, []
        how = f"c_{j}(0) < 0, so r is not absolutely monotonic at 0"
    elif reason == "product":
        require(len(num) == 1 and num[0] > 0, "the product form needs a positive constant numerator")
        require(_all_roots_real_positive(den), "h has a root that is not real and positive")
        rho, rho_attained, d = Real(inf=1), True, []
        how = "r = c prod (1 - z/p_k)^(-m_k) with every p_k > 0: a product of absolutely monotonic factors"
    elif reason == "bernstein":
        require(claim.get("tail_index") is None, "a bernstein claim has no tail index")
        hint = claim.get("pole")  # only a candidate modulus for Q(p*): bernstein._line_modulus tests it exactly
        how = prove_completely_monotone(num, den, None if hint is None else Real.parse(hint, "pole").poly)
        rho, rho_attained, d = Real(inf=1), True, []
    elif reason == "bernstein-root":
        require(claim.get("tail_index") is None and claim.get("d") is None, "a bernstein-root claim has no tail index and no d")
        rho, how = _bernstein_root(num, den)
        rho_attained, d = True, []
    elif reason == "balanced-tie":
        require(claim.get("tail_index") is None, "a balanced-tie claim has no tail index")
        g, h = reduced(num, den)
        poles = claim.get("poles")
        if poles is None:  # two simple real poles, proved in Q(sqrt D)
            kappa = balanced_tie(g, h)
        else:  # every pole listed exactly in Q(i), several tied poles (exactinv_check.balanced_tie)
            require(isinstance(poles, list) and len(poles) <= MAX_POLES, f"'poles' lists at most {MAX_POLES} poles")
            kappa = prove_balanced_tie(g, h, [vector(z, "poles", 2) for z in poles])
        require(not value.inf and value.compare(Real.rational(kappa)) == 0, f"the balanced tie is at {describe(kappa)}")
        count = max(len(num), len(den), 1)  # c_j for j > deg g - deg h are >= 0 on [0, kappa*] by the identity
        first, first_attained, d = recompute(num, den, count, False, kappa)  # not `attained`: the claim's flag
        require(first.compare(value) >= 0, f"a coefficient c_j (j < {count}) or a pole ends before the tie {describe(kappa)}")
        rho, rho_attained = value, first_attained if first.compare(value) == 0 else True
        how = (f"{'two simple real poles p* > 0 > a' if poles is None else f'{len(poles)} simple poles in Q(i)'} "
               f"with balanced residues (sum of the tied |b_k| <= b_*): c_j >= 0 on [0, {describe(kappa)}] "
               f"for j > deg q by the closed form, c_0 .. c_{count - 1} recomputed")
    elif reason == "tie":
        rho, rho_attained, d, N, count = _tie(num, den, value, claim)
        how = (f"a pole reaches p*'s distance from -kappa at kappa* = {value} (tie polynomial), so rho <= kappa*; "
               f"the tail j >= {N} is proved positive on [0, kappa*] with the tied poles at ratio 1, "
               f"c_0 .. c_{count - 1} recomputed")
    else:
        require(value.inf != -1, "rho >= 0")
        K = None if value.inf == 1 else short_above(value.bounds()[1])
        hint = claim.get("tail_index")
        hint = 0 if hint is None else integer(hint, "tail_index", 0, MAX_COEFFICIENTS)
        N = prove_tail(num, den, K, hint)
        count = max(N, len(num), len(den), 1)
        binding = claim.get("binding")
        rho, rho_attained, d = recompute(num, den, count, K is None, K, binding if type(binding) is int else None)
        require(K is None and rho.inf == 1 or K is not None and rho.compare(Real.rational(K)) <= 0,
                "the recomputed radius lies beyond the range where the tail is proved")
        how = f"tail j >= {N} proved positive on [0, {'oo' if K is None else K}], c_0 .. c_{count - 1} recomputed"
    if value.compare(rho) != 0:  # the message only on failure: an algebraic number's text costs bisections
        require(False, f"rho is {rho}, not {value}")
    consistent = {"coefficient": not rho.inf, "bernstein-root": not rho.inf, "tie": not rho.inf,
                  "balanced-tie": not rho.inf, "all-coefficients": method.is_polynomial and rho.inf == 1,
                  "termwise": not method.is_polynomial and rho.inf == 1}.get(reason, True)
    if not consistent:
        require(False, f"the reason {reason!r} does not describe rho = {rho}")
    require(attained is rho_attained, "the attained flag is wrong")
    if claim.get("d") is not None:
        require(isinstance(claim["d"], list) and len(claim["d"]) <= len(d), "more d_j listed than were needed")
        for j, dj in enumerate(claim["d"]):
            require(poly_arithmetic.trim(vector(dj, f"d_{j}")) == d[j], f"d_{j} does not match r")
    if claim.get("binding") is not None and d:
        j = integer(claim["binding"], "binding", 0, len(d))
        guard = [] if rho.inf else [[2 * rho.bounds()[1] + 1, Fraction(-1)]]  # bounds the isolation
        end, _ = first_end([Fraction(1)], guard + ([d[j]] if d[j] else []), [], first=guard + [d[j]], remember=True)
        require(end.compare(rho) == 0, f"c_{j} does not end the interval at rho")
    if claim.get("pole") is not None:
        pole = smallest_positive_root(den)
        require(pole is not None and Real.parse(claim["pole"], "pole").compare(pole) == 0,
                f"the recorded pole is not the smallest positive pole {pole}")
    context["rho"], context["rho_attained"] = rho, rho_attained
    return f"rho = {rho}: {how}"
