"""The radius of absolute monotonicity of a stability function (paper, Section 3.2).

    rho(r) = sup{ kappa >= 0 : r has no pole in [-kappa, 0] and
                               c_j(kappa) = r^(j)(-kappa)/j! >= 0 for all j = 0, 1, 2, ... }

with j = 0 included (erratum E1: the paper starts at j = 1, which would give
r(z) = 1 + 2z the radius infinity).  The set of such kappa is an interval
[0, rho] (re-expanding the Taylor series at -kappa shows that absolute
monotonicity at -kappa implies it on [-kappa, 0]).

*Polynomials*: only c_0 .. c_p are not identically 0; each is a polynomial in
kappa and rho = min_j (end of the first interval where c_j >= 0), exactly.

*Rational functions with poles*: infinitely many c_j matter; the argument
(Pringsheim, the principal part's sign, dominance, the certified tail, the
tie) is :mod:`exactinv.monotonicity.tail`.  The result and its
certificate claim: :mod:`exactinv.monotonicity.result`.

The value is exact (Fraction, RealAlgebraic, 0 or INF) and the result
records the argument; the kernel re-proves it (exactinv_check.tail, .tie).
"""

from __future__ import annotations

import time
from itertools import islice

import flint

from exactinv_check.format import RadiusReason

from ..core.algebraic import ExactKey
from ..core.flintq import fraction_of
from ..core.roots import nonnegative_until
from ..core.scalars import INF
from ..model.methods import Method
from ..model.validate import check_method
from .kernel_price import kernel_tried, priced
from .result import AbsoluteMonotonicityRadius
from .tail import coefficient_polynomials, rational_radius

__all__ = ["AbsoluteMonotonicityRadius", "absolute_monotonicity_radius", "taylor_coefficient_polynomials"]


def taylor_coefficient_polynomials(method: Method, count: int) -> list[flint.fmpq_poly]:
    """d_0 .. d_{count-1}: polynomials in kappa with d_j = c_j(kappa) h(-kappa)^(j+1),
    c_j(kappa) = r^(j)(-kappa)/j! (for a polynomial method h = 1 and d_j = c_j).

    The trapezoid r = -1 + 2/(1 - z/2), h(-k) = 1 + k/2: d_0 = g(-k) = 1 - k/2 and, for j >= 1,
    c_j = 2^(1-j) (1 + k/2)^-(j+1), so d_j = 2^(1-j).

    >>> from exactinv.model import methods
    >>> [[str(c) for c in d.coeffs()] for d in taylor_coefficient_polynomials(methods.trapezoid(), 3)]
    [['1', '-1/2'], ['1'], ['1/2']]
    """
    return list(islice(coefficient_polynomials(method), count))


def absolute_monotonicity_radius(method: Method) -> AbsoluteMonotonicityRadius:
    """The exact radius of absolute monotonicity (with j = 0, erratum E1).

    Forward Euler: c_0 = 1 - k, c_1 = 1, so rho = 1.  The trapezoid: d_0 = 1 - k/2, rho = 2.
    Backward Euler: 1/(1 - z) is absolutely monotonic on (-oo, 0], rho = oo.

    >>> from exactinv.model import methods
    >>> absolute_monotonicity_radius(methods.forward_euler()).value
    Fraction(1, 1)
    >>> absolute_monotonicity_radius(methods.trapezoid()).value
    Fraction(2, 1)
    >>> r = absolute_monotonicity_radius(methods.backward_euler())
    >>> r.value, r.reason
    (INF, 'product')
    """
    check_method(method)
    start = time.process_time()
    result = _polynomial_radius(method) if method.is_polynomial else rational_radius(method)
    return kernel_tried(result, time.process_time() - start)


def _polynomial_radius(method: Method) -> AbsoluteMonotonicityRadius:
    d = taylor_coefficient_polynomials(method, len(method.numerator))
    ends = [nonnegative_until(p) for p in d]
    binding = min(range(len(ends)), key=lambda j: ExactKey(ends[j]))
    value = ends[binding]
    coeffs = tuple(tuple(fraction_of(c) for c in p.coeffs()) for p in d)
    reason = RadiusReason.ALL_COEFFICIENTS if value == INF else RadiusReason.COEFFICIENT
    attained = value != 0 or all(c[0] >= 0 if c else True for c in coeffs)  # rho = 0 may fail at kappa = 0 itself
    return priced(AbsoluteMonotonicityRadius(value, attained, reason, method, None if value == INF else binding,
                                             coefficients=coeffs))
