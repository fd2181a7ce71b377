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
Any certificate H gives a valid bound; the gamma*-optimal H is tried first and,
when some row LP is unbounded, the unpushed row points as well.

Erratum E2' (our own correction of the above): H only meets the rows of G, so
it does not see the eigenvalues of A along the lineality space of P, and r(hA)
can be singular before that bound.  The threshold is therefore also capped by
the first h > 0 at which h_r(hA) is singular (not attained there).
"""

from __future__ import annotations

from fractions import Fraction

import flint

from ..core.algebraic import ExactKey
from ..core.flintq import fraction_of
from ..core.polys import interpolate
from ..core.real_algebraic import RealAlgebraic
from ..core.roots import real_roots
from ..core.scalars import INF, Infinity
from ..core.sparse import SparseRows
from ..invariance.gamma_star import OptimalGamma
from ..model.methods import Method, matrix_polynomial
from ..monotonicity.radius import absolute_monotonicity_radius
from .polynomial import SteplengthThreshold
from .spectral import abscissa_is_nonpositive, collatz_wielandt_upper, spectral_abscissa

__all__ = ["rational_threshold", "spectral_abscissa", "smallest_positive_pole", "first_singular_steplength"]


def smallest_positive_pole(method: Method) -> Fraction | RealAlgebraic | None:
    """z_p: the smallest positive real root of the denominator h (None if none).

    >>> from exactinv.model import methods
    >>> smallest_positive_pole(methods.trapezoid()), smallest_positive_pole(methods.theta("1/4"))  # 1 - z/2, 1 - z/4
    (Fraction(2, 1), Fraction(4, 1))
    >>> smallest_positive_pole(methods.radau_iia2()) is None   # 1 - 2z/3 + z^2/6: discriminant 4/9 - 4/6 < 0
    True
    """
    if method.is_polynomial:
        return None
    positive = [z for z, _ in real_roots(method.h) if z > 0]
    return positive[0] if positive else None


def _quotient(a, b):
    """a/b for positive exact reals, exactly (for two irrationals: the root of the
    resultant res_y(p_a(t y), p_b(y)) that their quotient's enclosure isolates)."""
    if isinstance(a, Infinity):
        return INF
    if isinstance(a, Fraction) or isinstance(b, Fraction):
        return a / b
    a, b = a._copy(), b._copy()
    pa, pb = a.poly, b.poly
    da, db = pa.degree(), pb.degree()
    points = list(range(1, da * db + 2))  # not t = 0: there p_a(t y) drops degree and the resultant changes form
    values = [flint.fmpz_poly([c * t**k for k, c in enumerate(pa.coeffs())]).resultant(pb) for t in points]
    R = interpolate(points, values)
    roots = [r for r, _ in real_roots(R) if r > 0]
    for _ in range(2000):
        lo, hi = a.lower / b.upper, a.upper / b.lower
        inside = [r for r in roots if lo < r < hi]
        if len(inside) == 1:
            return inside[0]
        a._bisect()
        b._bisect()
    raise ArithmeticError("could not isolate the quotient of two algebraic numbers")


def first_singular_steplength(A: flint.fmpq_mat, method: Method):
    """The first h > 0 at which h_r(hA) is singular (erratum E2'), or None:
    the least positive root of D(h) = det h_r(hA), a polynomial of degree <= n deg h_r.

    >>> from exactinv.model import methods
    >>> first_singular_steplength(flint.fmpq_mat([[2, 0], [0, 1]]), methods.trapezoid())  # (1 - h)(1 - h/2)
    Fraction(1, 1)
    >>> first_singular_steplength(flint.fmpq_mat([[-1]]), methods.backward_euler()) is None  # 1 + h > 0
    True
    """
    if method.is_polynomial:
        return None
    points = list(range(A.nrows() * (len(method.denominator) - 1) + 1))
    D = interpolate(points, [matrix_polynomial(method.denominator, A * t).det() for t in points])
    positive = [z for z, _ in real_roots(D) if z > 0] if D.degree() > 0 else []
    return positive[0] if positive else None


def _certificate_candidates(gamma: OptimalGamma):
    """(H, gamma_H) pairs with H + gamma_H I >= 0, HG = GA, Hb <= 0: the gamma*-optimal H
    and, when some row LP is unbounded, the H of the unpushed row points (its spectral
    abscissa can be smaller; the E2 bound depends on the choice of H)."""
    yield gamma.H_sparse, gamma.value
    if any(row.lp.ray_q is not None for row in gamma.rows):
        m = len(gamma.rows)
        H = SparseRows.of_rows(m, ([(k, v) for k, v in enumerate(row.lp.x_q.entries())] for row in gamma.rows))
        yield H, max(-fraction_of(h) for h in H.diagonal())


def rational_threshold(method: Method, gamma: OptimalGamma) -> SteplengthThreshold:
    """tau = min(rho/gamma_H, z_p/alpha(H)) for the best certificate H tried (module docstring).

    x' = -x on [-1, 1]: gamma* = 1/2 with alpha(H) = 0, so the trapezoid (rho = 2) gets
    rho/gamma* = 4, attained.  x' = x on {x >= 0}: H = (1), gamma* = -1 (the paper: oo), but
    r(dt) = (1 + dt/2)/(1 - dt/2) has its pole at z_p/alpha(H) = 2 (erratum E2): tau = 2, not attained.

    >>> import exactinv as ei
    >>> from exactinv.invariance.gamma_star import optimal_gamma
    >>> decay = optimal_gamma(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]))
    >>> t = rational_threshold(ei.methods.trapezoid(), decay)
    >>> t.value, t.attained
    (Fraction(4, 1), True)
    >>> growth = optimal_gamma(ei.LinearSystem([[1]]), ei.Polyhedron([[-1]], [0]))
    >>> t = rational_threshold(ei.methods.trapezoid(), growth)
    >>> t.value, t.attained, t.paper_value
    (Fraction(2, 1), False, INF)
    """
    radius = absolute_monotonicity_radius(method)
    rho, g = radius.value, gamma.value
    if rho == 0:
        return SteplengthThreshold(Fraction(0), True, "Theorem 3.12 (rho = 0)", method, gamma, radius=radius)
    paper = _rho_over(rho, g)  # the paper, literally (Theorems 3.12, 3.13)
    z_p = smallest_positive_pole(method)
    nonpositive = _NonPositive(gamma)
    best = None
    for H, g_H in _certificate_candidates(gamma):
        value, attained, notes = _rho_over(rho, g_H), True, []
        alpha = spectral_abscissa(H) if _e2_may_bind(H, gamma, z_p, value, nonpositive) else None
        if alpha is not None and alpha > 0:
            pole_bound = _quotient(z_p, alpha)
            if isinstance(z_p, RealAlgebraic) and isinstance(alpha, RealAlgebraic):
                notes.append("z_p/alpha(H) replaced by a certified rational lower bound (both irrational)")
            if value == INF or not ExactKey(value) < ExactKey(pole_bound):
                value, attained = pole_bound, False
        if best is None or ExactKey(best[0]) < ExactKey(value) or (best[0] == value and attained and not best[1]):
            best = (value, attained, notes, H, g_H, alpha)
    value, attained, notes, H, g_H, alpha = best
    if attained:
        theorem = "Theorem 3.12 (rho/gamma)" if value != INF else "Theorem 3.13"
    else:
        theorem = "Theorem 3.12 corrected (erratum E2: convergence needs dt < z_p/alpha(H))"
        notes.append(f"erratum E2: the paper gives {paper}; the Taylor series at -rho diverges for dt >= z_p/alpha(H)")
    singular = first_singular_steplength(gamma.system.A_flint, method)
    if singular is not None and not ExactKey(value) < ExactKey(singular):
        notes.append(f"erratum E2': r(dt A) is singular at dt = {singular}, before the corrected bound {value}")
        if value == singular and attained:
            notes.append("the bound is not attained there")
        value, attained = singular, False
        theorem = "Theorem 3.12 corrected (erratum E2': r(dt A) must exist)"
    certificate_H = None if H is gamma.H_sparse else (H, g_H)
    return SteplengthThreshold(value, attained, theorem, method, gamma, notes=tuple(notes), radius=radius,
                               pole=z_p, spectral_abscissa=alpha, paper_value=paper, certificate_H=certificate_H)


class _NonPositive:
    """Whether alpha(H) <= 0 for every certificate H of gamma's problem (A has no positive real
    eigenvalue and P is full-dimensional: :func:`~exactinv.thresholds.spectral.abscissa_is_nonpositive`),
    decided once, on first use."""

    def __init__(self, gamma: OptimalGamma):
        self.gamma, self.value = gamma, None

    def __bool__(self) -> bool:
        if self.value is None:
            P = self.gamma.polyhedron
            self.value = abscissa_is_nonpositive(self.gamma.system.A_flint, P.dimension == P.n)
        return self.value


def _e2_may_bind(H, gamma: OptimalGamma, z_p, value, nonpositive) -> bool:
    """False when exact bounds show that z_p/alpha(H) cannot be below ``value`` (then alpha(H) is
    not needed, and not computed): no pole; alpha(H) <= U = max_i (Hv)_i / v_i (Collatz-Wielandt,
    v = b when b > 0, else 1, as the kernel does) with U <= 0 or z_p/U > value; or alpha(H) <= 0
    because A has no positive real eigenvalue on a full-dimensional P (thresholds/spectral.py)."""
    if z_p is None or H.m == 0:
        return False
    b = gamma.polyhedron.b
    U = collatz_wielandt_upper(H, b if all(x > 0 for x in b) else [Fraction(1)] * len(b))
    if U <= 0:
        return False
    if not isinstance(value, Infinity) and ExactKey(value) < ExactKey(_quotient(z_p, U)):
        return False
    return not nonpositive


def _rho_over(rho, g):
    """rho/gamma, read as infinity for gamma <= 0 (Theorem 3.13's limit gamma -> 0+)."""
    if isinstance(g, Infinity) or g <= 0 or isinstance(rho, Infinity):
        return INF
    return _quotient(rho, g)
