"""Equal-modulus ties between the poles of r seen from -kappa -- located exactly.

With p* the smallest positive pole, another pole z = a + ib with a < p* is exactly as far from -kappa as p* at
    kappa_z = (a^2 + b^2 - p*^2) / (2 (p* - a)),
farther before it (|z + kappa|^2 - (p* + kappa)^2 = |z|^2 - p*^2 + 2 kappa (a - p*) decreases in kappa) and
closer after it.  Every kappa_z is a root of the tie polynomial
    T(kappa) = Res_x(P2, G) Res_x(G, G'),   G: the roots w_l^2,  P2: the products w_i w_j (i < j),
w_l = z_l + kappa over the distinct poles (non-real z: w w-bar = w*^2 is a root of P2 and of G; negative real z:
w_z^2 = w*^2 is a double root of G).  T is not identically 0 (that would force two poles to coincide).
T is computed by interpolation at integer kappa: at each point the power sums of the w_l (Newton's identities)
give G and P2 exactly, and the resultants are Euclid's (resultants.resultant).

Work budget: T is priced before it is interpolated (``interpolation_cost``): deg T + 1 values, each from
resultants whose numbers grow to about deg T (bits of h + log deg T) bits, and a Newton interpolation with
(deg T + 1)^2 Fraction operations on numbers of that size; over the budget the claim is rejected.

``tie_interval(h, value)`` proves that ``value`` is a root of T and isolates it: (lo, hi) holding exactly one
root of T.  A pole whose rational enclosure of kappa_z lies in (lo, hi) then has kappa_z = value exactly.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Callable, Sequence

from . import poly_arithmetic, polys, resultants
from .budget import FRACTION_WEIGHT, MAX_TIE_DEGREE, within_budget
from .budget import MAX_TIE_ISOLATE as MAX_ISOLATE
from .failure import require
from .reals import Real


def _power_sums(monic: Sequence[Fraction], count: int) -> list[Fraction]:
    d = len(monic) - 1
    e = [(-1) ** k * monic[d - k] for k in range(d + 1)]
    s = [Fraction(0)] * (count + 1)
    for k in range(1, count + 1):
        acc = (-1) ** (k - 1) * k * e[k] if k <= d else Fraction(0)
        for i in range(1, min(k - 1, d) + 1):
            acc += (-1) ** (i - 1) * e[i] * s[k - i]
        s[k] = acc
    return s[1:]


def _from_power_sums(s: Sequence[Fraction], d: int) -> list[Fraction]:
    e = [Fraction(1)]
    for k in range(1, d + 1):
        e.append(sum((-1) ** (i - 1) * e[k - i] * s[i - 1] for i in range(1, k + 1)) / k)
    return [(-1) ** (d - i) * e[d - i] for i in range(d + 1)]


def _shift(p: Sequence[Fraction], t: Fraction) -> list[Fraction]:
    """p(w - t) (coefficients low to high)."""
    out = [Fraction(0)] * len(p)
    for k in range(len(p) - 1, -1, -1):  # Horner in (w - t)
        out = [-t * out[0]] + [out[i - 1] - t * out[i] for i in range(1, len(out))]
        out[0] += p[k]
    return out


def _value(h: Sequence[Fraction], t: Fraction) -> Any:
    q = _shift(h, t)
    c = [x / q[-1] for x in q]
    d = len(c) - 1
    n2 = d * (d - 1) // 2
    s = _power_sums(c, 2 * max(n2, d))
    P2 = _from_power_sums([(s[k - 1] ** 2 - s[2 * k - 1]) / 2 for k in range(1, n2 + 1)], n2)
    G = _from_power_sums([s[2 * k - 1] for k in range(1, d + 1)], d)
    return resultants.resultant(P2, G) * resultants.resultant(G, poly_arithmetic.derivative(G))


def interpolation_cost(degree: int, bits: int) -> int:
    """Estimated word operations of building T of formal degree ``degree`` for an h with ``bits``-bit
    integer coefficients (calibrated: about a second of work per 10^8 on the kernel's Fractions)."""
    linear = (degree + 1) ** 2 * (3 * FRACTION_WEIGHT + degree * (bits + degree.bit_length()) // 2)
    # the resultants' Fraction gcds are quadratic in the words of their numbers (about deg T bits bits): priced
    # linearly only, a deg h = 2 h with 10^5-bit coefficients was priced 3e7 and took 47 s (red team rt-budget)
    w = 1 + degree * (bits + degree.bit_length()) // 64
    return max(linear, (degree + 1) ** 2 * w * w // 8)


def tie_polynomial(h: Any) -> Any:
    """T for the squarefree part of h (degree >= 2), by interpolation; priced first (work budget)."""
    sq = poly_arithmetic.monic(polys.squarefree(h))
    d = len(sq) - 1
    require(d >= 2, "tie: r needs two poles for a tie")
    degree = d * d * (d - 1) + 2 * d * (d - 1)
    require(degree <= MAX_TIE_DEGREE, f"tie: the tie polynomial would exceed degree {MAX_TIE_DEGREE}")
    bits = max(abs(c).bit_length() for c in poly_arithmetic.integer_coefficients(sq))
    within_budget(interpolation_cost(degree, bits), f"the tie polynomial of degree {degree} for {d} poles "
                                                    f"with {bits}-bit coefficients")
    points = [Fraction(t) for t in range(degree + 1)]
    T = resultants.interpolate(points, [_value(sq, t) for t in points])
    require(len(T) > 1 or (T and T[0] != 0), "tie: the tie polynomial vanishes identically")
    return T


def tie_interval(h: Any, value: Any) -> Any:
    """(lo, hi) with value in it and exactly one root of T there (so every root of T in it is value)."""
    require(not value.inf, "tie: the tie value must be finite")
    T = polys.squarefree(tie_polynomial(h))
    require(value.sign_of(T) == 0, "tie: the claimed radius is not a root of the tie polynomial")
    ints = poly_arithmetic.integer_coefficients(T)
    if value.is_rational:
        q, width = value.q, Fraction(1)
        for _ in range(MAX_ISOLATE):
            lo, hi = q - width, q + width
            if polys.sign_at(ints, lo) and polys.sign_at(ints, hi) and polys.count_roots(T, lo, hi) == 1:
                return lo, hi
            width /= 2
    else:
        v = Real(poly=value.poly, lo=value.lo, hi=value.hi)
        for _ in range(MAX_ISOLATE):
            if v.poly is None:
                return tie_interval(h, Real.rational(v.q))
            if polys.sign_at(ints, v.lo) and polys.sign_at(ints, v.hi) and polys.count_roots(T, v.lo, v.hi) == 1:
                return v.lo, v.hi
            v.bisect()
    require(False, "tie: could not isolate the claimed radius among the roots of the tie polynomial")


def kappa_enclosure(z: tuple[Fraction, Fraction, Fraction], P_lo: Fraction, P_hi: Fraction,
                    sqrt_bounds: Callable[..., Any]) -> tuple[Fraction, Fraction] | None:
    """Rationals (lo, hi) around kappa_z for every pole in the disk z = (a, b, rad) and p* in [P_lo, P_hi],
    or None unless Re z < p* is certain."""
    a, b, rad = z
    if not a + rad < P_lo:
        return None
    m_lo, m_hi = sqrt_bounds(a * a + b * b)
    r_lo, r_hi = max(m_lo - rad, Fraction(0)) ** 2, (m_hi + rad) ** 2  # |z|^2
    num_lo, num_hi = r_lo - P_hi ** 2, r_hi - P_lo ** 2
    den_lo, den_hi = 2 * (P_lo - a - rad), 2 * (P_hi - a + rad)  # 0 < den_lo <= 2 (p* - Re z) <= den_hi
    lo = num_lo / (den_hi if num_lo >= 0 else den_lo)
    hi = num_hi / (den_lo if num_hi >= 0 else den_hi)
    return lo, hi


def balanced_tie(g: Any, h: Any) -> Any:
    """kappa* for r = g/h (lowest terms, h(0) > 0) with exactly two simple poles p > 0 > a, |a| > p, whose residues
    balance: |b_a| = b_p > 0 (b = -g(z)/h'(z)).  Then, for j > deg g - 2 and 0 <= kappa <= kappa* = -(a + p)/2,
        c_j(kappa) = b_p (p + kappa)^-(j+1) + b_a (a + kappa)^-(j+1) >= b_p ((p + kappa)^-(j+1) - |a + kappa|^-(j+1)) >= 0
    since |a + kappa| >= p + kappa exactly up to kappa*; beyond it the a-term dominates with alternating sign, so some
    c_j < 0 and rho <= kappa*.  Exact: with s = sqrt(D), D = h1^2 - 4 h0 h2, the roots are (-h1 +- s)/(2 h2) and
    g at them is G0 +- G1 s (rationals), h' = +-s, so b_+- = -+G0/s - G1: |b_+| = |b_-| iff G0 = 0 or G1 = 0."""
    require(len(h) == 3, "balanced tie: r needs exactly two poles (deg h = 2)")
    h0, h1, h2 = h
    D = h1 * h1 - 4 * h0 * h2
    require(D > 0, "balanced tie: the poles are not real and distinct")
    require(h0 / h2 < 0, "balanced tie: the poles do not have opposite signs")
    require(-h1 / h2 < 0, "balanced tie: the negative pole is not farther from 0 than the positive one")
    # g((-h1 + e s)/(2 h2)) = G0 + e G1 s for e = +-1: expand in the field Q(s), s^2 = D
    x, y = Fraction(0), Fraction(0)  # running value x + y s of g at (-h1 + s)/(2 h2), Horner
    zr, zs = -h1 / (2 * h2), 1 / (2 * h2)
    for c in reversed(g):
        x, y = x * zr + y * zs * D + c, x * zs + y * zr
    G0, G1 = x, y
    require(G0 == 0 or G1 == 0, "balanced tie: the residues at the two poles do not balance exactly")
    e = 1 if h2 > 0 else -1  # the positive pole p = (-h1 + e s)/(2 h2)
    # b_p = -g(p)/h'(p), h'(p) = e s: b_p = -(G0 + e G1 s)/(e s) = -e G0/s - G1
    b_p_sign = poly_arithmetic.sign(-e * G0) if G1 == 0 else poly_arithmetic.sign(-G1)
    require(b_p_sign > 0, "balanced tie: the principal part at p* has the wrong sign")
    return h1 / (2 * h2)  # -(a + p)/2
