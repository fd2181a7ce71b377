"""The threshold for rational methods (paper, Theorem 3.12), corrected (erratum E2).

The paper takes H~(dt) = r(dt H) and expands r in its Taylor series at -rho,

    r(dt H) = sum_j c_j(rho) (dt H + rho I)^j,   c_j(rho) = r^(j)(-rho)/j! >= 0,

so r(dt H) >= 0 when dt H + rho I >= 0, i.e. dt <= rho/gamma.  The series
converges only while the spectral radius of dt H + rho I -- for this
nonnegative matrix its Perron root rho + dt alpha(H), alpha(H) the spectral
abscissa of the Metzler matrix H -- stays below the radius of convergence
rho + z_p (z_p the smallest positive real pole of r, which is the pole
nearest to -rho).  The corrected valid threshold is therefore

    tau = min(rho/gamma*, z_p/alpha(H))      (z_p/alpha(H) only when alpha(H) > 0),

valid on [0, tau] when rho/gamma* < z_p/alpha(H) and on [0, tau) otherwise.
For gamma* <= 0 the paper's "tau = infinity" (Theorem 3.13) becomes
z_p/alpha(H) (or infinity when alpha(H) <= 0 or r has no positive pole).
"""

from __future__ import annotations

from fractions import Fraction

import flint

from .algebraic import ExactKey, RealAlgebraic
from .invariance import OptimalGamma
from .methods import Method
from .monotonicity import absolute_monotonicity_radius
from .numbers import INF, Infinity
from .roots import real_roots

__all__ = ["rational_threshold", "spectral_abscissa", "smallest_positive_pole"]


def spectral_abscissa(H: flint.fmpq_mat) -> Fraction | RealAlgebraic:
    """alpha(H) = max Re(lambda) over the eigenvalues of a Metzler matrix H
    (off-diagonal >= 0).  By Perron-Frobenius applied to H + cI >= 0 it is the
    largest real eigenvalue: the largest real root of the characteristic polynomial, exact."""
    roots = real_roots(H.charpoly())
    return roots[-1][0]


def smallest_positive_pole(method: Method) -> Fraction | RealAlgebraic | None:
    """z_p: the smallest positive real root of the denominator h (None if none)."""
    if method.is_polynomial:
        return None
    positive = [z for z, _ in real_roots(method.h) if z > 0]
    return positive[0] if positive else None


def _quotient(a, b):
    """a/b for positive exact reals; exact unless both are irrational, then a
    certified rational lower bound (conservative: still a valid threshold)."""
    if isinstance(a, Infinity):
        return INF
    if isinstance(a, Fraction) or isinstance(b, Fraction):
        return a / b
    return a.lower / b.upper


def rational_threshold(method: Method, gamma: OptimalGamma):
    from .thresholds import SteplengthThreshold

    radius = absolute_monotonicity_radius(method)
    rho, g = radius.value, gamma.value
    notes = []
    if rho == 0:
        return SteplengthThreshold(Fraction(0), True, "Theorem 3.12 (rho = 0)", method, gamma, radius=radius)
    if isinstance(g, Infinity) or g <= 0:
        paper = INF  # Theorem 3.13
    else:
        paper = _quotient(rho, g) if not isinstance(rho, Infinity) else INF
    z_p = smallest_positive_pole(method)
    alpha = spectral_abscissa(gamma.H_flint) if z_p is not None else None
    value, attained, theorem = paper, True, "Theorem 3.12 (rho/gamma*)" if paper != INF else "Theorem 3.13"
    if z_p is not None and alpha > 0:
        pole_bound = _quotient(z_p, alpha)
        if isinstance(z_p, RealAlgebraic) and isinstance(alpha, RealAlgebraic):
            notes.append("z_p/alpha(H) replaced by a certified rational lower bound (both irrational)")
        if paper == INF or not ExactKey(paper) < ExactKey(pole_bound):
            value, attained = pole_bound, False
            theorem = "Theorem 3.12 corrected (erratum E2: convergence needs dt < z_p/alpha(H))"
            notes.append(f"erratum E2: the paper gives {paper}; the Taylor series at -rho diverges for dt >= z_p/alpha(H)")
    return SteplengthThreshold(value, attained, theorem, method, gamma, notes=tuple(notes), radius=radius,
                               pole=z_p, spectral_abscissa=alpha, paper_value=paper)
