"""Exact valid steplength sets and largest thresholds on an ellipsoid (beyond the paper).

V = {h >= 0 : A_d(h) E subset of E} = {0} union {h > 0 : q_k(h) >= 0 for
k = 1..n, det h(hA) != 0}, with q_k the coefficient polynomials of
:mod:`.ellipsoid_conditions` -- a finite union of intervals with exact
algebraic ends, computed by the same machinery as the polyhedral valid set:
each q_k is negative exactly on the open segments between its positive roots
where its sign (from the sign right of 0, flipped at odd multiplicities) is
negative.  The largest threshold is the end of the first interval.

Forward Euler, r(z) = 1 + z: M(h)/h = K - h B with K = -(A^T Q + Q A) and
B = A^T Q A, affine in h, so V is an interval [0, tau] and
tau = sup{h : K - hB >= 0} is a generalised eigenvalue: with
range(B) in range(K) (else tau = 0) and W a basis of range(K),
tau = 1 / lambda_max((W^T K W)^{-1} W^T B W) (INF if that is <= 0).  Both
routes are computed and must agree.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

import flint

from ..core.algebraic import Real, exact_eq, upper_bound
from ..core.encode import encode_real, vec
from ..core.intervals import complement_of_open
from ..core.latex import latex_real
from ..core.psd import psd_decision
from ..core.results import ExactValueMixin
from ..core.polys import no_positive_root_below, positive_right_of_zero
from ..core.roots import negative_segments, positive_roots, real_roots
from ..core.scalars import INF, Infinity, fraction_of, matrix_of
from ..core.tags import ClaimType
from ..errors import VerificationFailed
from ..model import Ellipsoid, LinearSystem, Method
from ..model.methods import forward_euler
from ..model.record import certificate as make_certificate
from ..model.validate import check_method
from .ellipsoid_conditions import psd_polynomials
from .ellipsoid_invariance import check_ellipsoid_pair
from .largest import LargestThreshold, ValidSteplengths

__all__ = ["EllipsoidValidSteplengths", "EllipsoidLargestThreshold", "EllipsoidForwardEulerThreshold",
           "ellipsoid_valid_steplengths", "ellipsoid_largest_threshold", "ellipsoid_forward_euler_threshold"]


@dataclass(frozen=True, repr=False)
class EllipsoidValidSteplengths(ValidSteplengths):
    """The exact set {h >= 0 : A_d(h) E subset of E} (a :class:`ValidSteplengths`;
    ``polyhedron`` holds the ellipsoid).  ``polynomials`` are the q_k."""

    polynomials: tuple[tuple[Fraction, ...], ...] = field(default=(), repr=False)

    @property
    def ellipsoid(self) -> Ellipsoid:
        return self.polyhedron

    def claims(self) -> list[dict]:
        """The certificate claim: the intervals with exact ends and D(h) = det h(hA).

        Forward Euler, A = [[-1, -2], [2, -1]], Q = I: M'(h) = (2 - 5h) I >= 0 iff h <= 2/5.

        >>> from exactinv.model import methods
        >>> E = Ellipsoid([[1, 0], [0, 1]])
        >>> ellipsoid_valid_steplengths(LinearSystem([[-1, -2], [2, -1]]), E, methods.forward_euler()).claims()
        [{'type': 'ellipsoid_valid_steplengths', 'intervals': [{'lo': '0', 'hi': '2/5', 'lo_closed': True, 'hi_closed': True}], 'determinant': ['1']}]
        """
        return [{
            "type": ClaimType.ELLIPSOID_VALID_STEPLENGTHS,
            "intervals": [{"lo": encode_real(iv.lo), "hi": encode_real(iv.hi), "lo_closed": iv.lo_closed,
                           "hi_closed": iv.hi_closed} for iv in self.intervals],
            "determinant": vec(self.determinant),
        }]

    def __repr__(self) -> str:
        return f"EllipsoidValidSteplengths({self.intervals!r}, method={self.method.name})"


@dataclass(frozen=True, repr=False)
class EllipsoidLargestThreshold(LargestThreshold):
    """The exact largest threshold on an ellipsoid (a :class:`LargestThreshold`;
    ``polyhedron`` holds the ellipsoid): the end of the first interval of the
    valid set.  ``coefficient`` is the k of the q_k whose sign change ends it
    (None when a pole of r(hA) or nothing ends it)."""

    coefficient: int | None = None

    @property
    def ellipsoid(self) -> Ellipsoid:
        return self.polyhedron

    def claims(self) -> list[dict]:
        """The certificate claim: the value, whether attained, D(h) and the binding q_k.

        Taylor(2) on x' = -x, Q = I: r(-h) = 1 - h + h^2/2 and
        1 - r(-h)^2 = h (1 - h/2)(2 - h + h^2/2) >= 0 iff h <= 2 (q_1 binds).

        >>> from exactinv.model import methods
        >>> E = Ellipsoid([[1, 0], [0, 1]])
        >>> ellipsoid_largest_threshold(LinearSystem([[-1, 0], [0, -1]]), E, methods.taylor(2)).claims()
        [{'type': 'ellipsoid_largest_threshold', 'value': '2', 'attained': True, 'determinant': ['1'], 'binding': 1}]
        """
        return [{"type": ClaimType.ELLIPSOID_LARGEST_THRESHOLD, "value": encode_real(self.value), "attained": self.attained,
                 "determinant": vec(self.determinant), "binding": self.coefficient}]

    def __repr__(self) -> str:
        return (f"EllipsoidLargestThreshold(value={self.value}, attained={self.attained}, "
                f"method={self.method.name}, coefficient={self.coefficient})")


@dataclass(frozen=True)
class EllipsoidForwardEulerThreshold(ExactValueMixin):
    """The largest forward-Euler step on an ellipsoid, derived twice: ``by_eigenvalue``
    (the generalised eigenvalue, module docstring) and ``by_valid_set`` (the
    coefficient polynomials); they must agree.  The valid set is [0, value]."""

    value: Real
    by_eigenvalue: Real
    by_valid_set: Real
    system: LinearSystem = field(repr=False)
    ellipsoid: Ellipsoid = field(repr=False)
    attained: bool = True

    def claims(self) -> list[dict]:
        """The certificate claim: the exact value (the checker recomputes both routes).

        A = [[-a, -b], [b, -a]], Q = I: K = 2a I, B = (a^2 + b^2) I, tau = 2a/(a^2 + b^2).

        >>> E = Ellipsoid([[1, 0], [0, 1]])
        >>> ellipsoid_forward_euler_threshold(LinearSystem([[-1, -2], [2, -1]]), E).claims()
        [{'type': 'ellipsoid_forward_euler_threshold', 'value': '2/5'}]
        """
        return [{"type": ClaimType.ELLIPSOID_FORWARD_EULER_THRESHOLD, "value": encode_real(self.value)}]

    @property
    def certificate(self) -> dict:
        """The JSON certificate for :func:`exactinv.check`."""
        return make_certificate(self.system, self.ellipsoid, None, [self])

    def to_latex(self) -> str:
        """LaTeX: tau_FE = the exact value.

        >>> E = Ellipsoid([[1, 0], [0, 1]])
        >>> print(ellipsoid_forward_euler_threshold(LinearSystem([[-1, -2], [2, -1]]), E).to_latex())
        \\tau_{FE} = \\frac{2}{5}
        """
        return rf"\tau_{{FE}} = {latex_real(self.value)}"


def _problem(system, ellipsoid, method):
    S, E = check_ellipsoid_pair(system, ellipsoid)
    m = check_method(method)
    qs, D = psd_polynomials(S, E.Q_flint, m)
    return S, E, m, qs, D


def ellipsoid_valid_steplengths(system: LinearSystem, ellipsoid: Ellipsoid, method: Method) -> EllipsoidValidSteplengths:
    """The exact set {h >= 0 : A_d(h) E subset of E}: intervals with exact ends, poles of r(hA) excluded.

    >>> from exactinv.model import methods
    >>> E = Ellipsoid([[1, 0], [0, 1]])
    >>> ellipsoid_valid_steplengths(LinearSystem([[-1, -2], [2, -1]]), E, methods.forward_euler())
    EllipsoidValidSteplengths([0, 2/5], method=forward_euler)
    """
    S, E, m, qs, D = _problem(system, ellipsoid, method)
    union, singular, _ = _valid_set(qs, D)
    return EllipsoidValidSteplengths(union, m, tuple(singular), len(qs), len(qs), system=S, polyhedron=E,
                                     determinant=tuple(fraction_of(c) for c in D.coeffs()),
                                     polynomials=tuple(tuple(fraction_of(c) for c in q.coeffs()) for q in qs))


def _valid_set(qs: list[flint.fmpq_poly], D: flint.fmpq_poly):
    """(the valid set, the poles, owner): ``owner`` maps each bad segment's left end to its k.

    Pruning, exact: the valid set lies in that of q_1 alone; if that is bounded by T,
    a q_k >= 0 right of 0 with no root in (0, T] (Descartes) cannot change it."""
    singular = [r for r, _ in positive_roots(D)]
    bad: list[tuple[Real, Real]] = []
    owner: list[tuple[Real, int]] = []
    T: Real = INF
    for k, q in enumerate(qs, start=1):
        if q.is_zero() or all(c >= 0 for c in q.coeffs()):
            continue  # q_k >= 0 on [0, oo)
        if (not isinstance(T, Infinity) and positive_right_of_zero(q)
                and no_positive_root_below(q, upper_bound(T))):
            continue
        segments = negative_segments(q)
        bad += segments
        owner += [(a, k) for a, _ in segments]
        if k == 1:
            first = complement_of_open(bad, singular).intervals
            T = first[-1].hi if first else Fraction(0)
    return complement_of_open(bad, singular), singular, owner


def ellipsoid_largest_threshold(system: LinearSystem, ellipsoid: Ellipsoid, method: Method) -> EllipsoidLargestThreshold:
    """The exact largest threshold sup{T : A_d(h) E subset of E for all h in [0, T)}: the end
    of the first interval of the valid set (the first sign change of some q_k, 0 if some q_k < 0
    right of 0, or the first pole of r(hA), then not attained).

    >>> from exactinv.model import methods
    >>> E = Ellipsoid([[1, 0], [0, 1]])
    >>> ellipsoid_largest_threshold(LinearSystem([[-1, 0], [0, -1]]), E, methods.taylor(2)).value
    Fraction(2, 1)
    """
    S, E, m, qs, D = _problem(system, ellipsoid, method)
    union, singular, owner = _valid_set(qs, D)
    first = union.intervals[0]
    best, attained = first.hi, first.hi_closed or isinstance(first.hi, Infinity)
    binding = next((k for a, k in owner if not isinstance(best, Infinity) and exact_eq(a, best)), None)
    if not attained:
        binding = None
    return EllipsoidLargestThreshold(best, attained, m, None, singular[0] if singular else None, system=S,
                                     polyhedron=E, determinant=tuple(fraction_of(c) for c in D.coeffs()),
                                     coefficient=binding)


def ellipsoid_forward_euler_threshold(system: LinearSystem, ellipsoid: Ellipsoid) -> EllipsoidForwardEulerThreshold:
    """The largest forward-Euler step on E, exact, by the generalised eigenvalue and by
    the valid set (they must agree).

    >>> E = Ellipsoid([[1, 0], [0, 1]])
    >>> ellipsoid_forward_euler_threshold(LinearSystem([[-1, -2], [2, -1]]), E).value   # 2a/(a^2+b^2)
    Fraction(2, 5)
    """
    S, E = check_ellipsoid_pair(system, ellipsoid)
    by_eigenvalue = _generalised_eigenvalue_step(S.A_flint, E.Q_flint)
    by_set = ellipsoid_largest_threshold(S, E, forward_euler()).value
    if by_set != by_eigenvalue:
        raise VerificationFailed(f"forward Euler on E: the eigenvalue route gives {by_eigenvalue}, the valid set {by_set}")
    return EllipsoidForwardEulerThreshold(by_set, by_eigenvalue, by_set, S, E)


def _generalised_eigenvalue_step(A: flint.fmpq_mat, Q: flint.fmpq_mat) -> Real:
    """sup{h >= 0 : K - hB >= 0}, K = -(A^T Q + Q A), B = A^T Q A (module docstring)."""
    K = -(A.transpose() * Q + Q * A)
    B = A.transpose() * Q * A
    if not psd_decision(matrix_of(K)).psd:
        return Fraction(0)
    n = K.nrows()
    rank_K = K.rank()
    if flint.fmpq_mat(n, 2 * n, [v for i in range(n) for v in [K[i, j] for j in range(n)] + [B[i, j] for j in range(n)]]).rank() > rank_K:
        return Fraction(0)  # some v in ker K has v^T B v > 0: K - hB fails for every h > 0
    if rank_K == 0:
        return INF
    _, pivots = _pivot_columns(K)
    W = flint.fmpq_mat(n, len(pivots), [K[i, j] for i in range(n) for j in pivots])
    C = (W.transpose() * K * W).inv() * (W.transpose() * B * W)
    mu = C.charpoly()  # eigenvalues real and >= 0 (similar to a PSD matrix); tau = 1/mu_max
    h_poly = flint.fmpq_poly(list(reversed(mu.coeffs())))  # roots 1/mu for mu != 0
    if h_poly.degree() < 1:
        return INF
    roots = [r for r, _ in real_roots(h_poly) if r > 0]
    return roots[0] if roots else INF


def _pivot_columns(K: flint.fmpq_mat) -> tuple[flint.fmpq_mat, list[int]]:
    R, rank = K.rref()
    pivots, row = [], 0
    for j in range(K.ncols()):
        if row < rank and R[row, j] != 0:
            pivots.append(j)
            row += 1
    return R, pivots
