"""Robust thresholds over a polytope of matrices conv{A_1, ..., A_k} (issue 25, part 2).

With gamma = max_i gamma*(A_i) and H_i the vertices' certificates, every
A = sum_i lambda_i A_i of the hull has H = sum_i lambda_i H_i with H off-diagonal
>= 0, HG = GA, Hb <= 0 and H + gamma I >= 0; so the paper's argument runs with
(H, gamma) for every A of the hull at once, and every step maps P into P, so
the threshold also holds under arbitrary switching (docs/design.md, "Control:
robust thresholds", with the proofs).

* polynomial methods: tau = rho/gamma (gamma > 0), infinity or 0 for gamma <= 0
  (every sigma_k >= 0 or not, erratum E6);
* rational methods: tau = min(rho/gamma, z_p/beta) with beta an exact bound of
  the spectral abscissa over the WHOLE hull (Collatz-Wielandt: beta =
  max_i max_r (H_i v)_r / v_r, v = b if b > 0 else the all-ones vector) -- the
  vertices' own alpha(H_i) are not such a bound; only for a P without lines
  (the bound then also keeps r(hA) nonsingular, erratum E2'); a P with lines
  raises :class:`~exactinv.Undecided`;
* forward Euler: the exact largest robust step is min_i 1/gamma_i = 1/gamma;
* the exact upper bound: the intersection of the vertices' exact valid sets.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from typing import Any, Sequence

from exactinv_check.format import ClaimType

from ..core.algebraic import ExactKey, Real, exact_cmp
from ..core.encode import encode_real, envelope, mat, vec
from ..core.flintq import fraction_of
from ..core.intervals import IntervalUnion
from ..core.latex import latex_real
from ..core.results import ExactValueMixin
from ..core.scalars import INF, Infinity, Matrix
from ..core.sparse import SparseRows
from ..errors import InvalidInput, NotInvariant, Undecided
from ..invariance.gamma_star import OptimalGamma, optimal_gamma
from ..model import LinearSystem, Method, Polyhedron
from ..model.record import method_record
from ..model.sets import expect_set
from ..model.validate import check_method, check_pair
from ..monotonicity.radius import AbsoluteMonotonicityRadius, absolute_monotonicity_radius
from ..thresholds.rational import smallest_positive_pole
from ..validset.engine import valid_steplengths

__all__ = ["RobustThreshold", "robust_threshold", "abscissa_bound"]


@dataclass(frozen=True)
class RobustThreshold(ExactValueMixin):
    """A steplength threshold valid for every A in conv{A_1, ..., A_k} and under
    arbitrary switching between them: every step with 0 <= dt <= ``value``
    (< ``value`` when not ``attained``) maps P into P.

    ``gamma`` = max_i gamma*(A_i) (``gammas`` per vertex, ``vertices`` their
    :class:`~exactinv.OptimalGamma`), ``rho`` the method's radius of absolute
    monotonicity, ``beta`` the hull-wide bound of the spectral abscissa (rational
    methods with a positive pole), ``forward_euler_step`` = 1/gamma, the exact
    largest robust forward-Euler step.  ``upper_bound`` (computed on request)
    is the intersection of the vertices' exact valid sets: no robust step lies
    outside it.
    """

    value: Real
    attained: bool
    gamma: Fraction | Infinity
    gammas: tuple[Fraction | Infinity, ...]
    rho: Real
    beta: Fraction | None
    v: tuple[Fraction, ...] | None = field(repr=False)
    method: Method = field(repr=False)
    polyhedron: Polyhedron = field(repr=False)
    systems: tuple[LinearSystem, ...] = field(repr=False)
    vertices: tuple[OptimalGamma, ...] = field(repr=False)
    radius: AbsoluteMonotonicityRadius = field(repr=False)

    @property
    def forward_euler_step(self) -> Fraction | Infinity:
        """1/gamma = min_i 1/gamma*(A_i): the exact largest robust forward-Euler step (INF for gamma <= 0)."""
        g = self.gamma
        return INF if isinstance(g, Infinity) or g <= 0 else 1 / g

    def vertex_valid_sets(self) -> tuple[Any, ...]:
        """The vertices' exact valid sets (:func:`exactinv.valid_steplengths`), each with its certificate.

        >>> from exactinv.model.methods import taylor
        >>> r = robust_threshold([LinearSystem([[-1]]), LinearSystem([[-2]])], Polyhedron.box([-1], [1]), taylor(1))
        >>> [V.intervals for V in r.vertex_valid_sets()], r.upper_bound    # |1 - h| <= 1, |1 - 2h| <= 1
        ([[0, 2], [0, 1]], [0, 1])
        """
        return self._vertex_sets

    @cached_property
    def _vertex_sets(self) -> tuple[Any, ...]:
        return tuple(valid_steplengths(S, self.polyhedron, self.method) for S in self.systems)

    @cached_property
    def upper_bound(self) -> IntervalUnion:
        """The exact intersection of the vertices' valid sets V(A_1) n ... n V(A_k) (an upper bound:
        a robust step is valid at every vertex)."""
        out = self._vertex_sets[0].intervals
        for V in self._vertex_sets[1:]:
            out = out.intersect(V.intervals)
        return out

    def claims(self) -> list[dict]:
        """The radius claim, then the robust_threshold claim (each vertex's gamma* with H_i and its dual).

        >>> from exactinv.model.methods import taylor
        >>> P = Polyhedron.box([-1], [1])
        >>> r = robust_threshold([LinearSystem([[-1]]), LinearSystem([[-2]])], P, taylor(2))
        >>> c = r.claims()[-1]
        >>> c["type"], c["gamma"], c["value"], [v["value"] for v in c["vertices"]]
        ('robust_threshold', '1', '1', ['1/2', '1'])
        """
        vertices = []
        for g in self.vertices:
            claim = dict(g.claims()[0])
            del claim["type"]
            claim.pop("paths", None)
            vertices.append(claim)
        claim = {"type": ClaimType.ROBUST_THRESHOLD, "value": encode_real(self.value), "attained": self.attained,
                 "gamma": encode_real(self.gamma), "rho": encode_real(self.rho),
                 "forward_euler": encode_real(self.forward_euler_step), "vertices": vertices,
                 "x": vec(self.polyhedron.vertices[0])}  # a point of P: P is nonempty (the kernel checks it)
        if self.beta is not None:
            claim.update(beta=str(self.beta), v=vec(self.v))
        return self.radius.claims() + [claim]

    @property
    def certificate(self) -> dict:
        """The JSON certificate (problem: the hull's vertices A_i, G, b, the method) for :func:`exactinv.check`."""
        return envelope(robust_problem_record(self.systems, self.polyhedron, self.method), [self])

    def to_latex(self) -> str:
        """The robust threshold in LaTeX.

        >>> from exactinv.model.methods import taylor
        >>> print(robust_threshold([LinearSystem([[-1]])], Polyhedron.box([-1], [1]), taylor(1)).to_latex())
        \\tau_{\\mathrm{robust}} = \\rho/\\gamma = 2\\ \\text{(valid on } [0, \\tau])
        """
        end = "]" if self.attained else ")"
        return rf"\tau_{{\mathrm{{robust}}}} = \rho/\gamma = {latex_real(self.value)}\ \text{{(valid on }} [0, \tau{end})"

    def __repr__(self) -> str:
        return (f"RobustThreshold(value={self.value!r}, attained={self.attained}, gamma={self.gamma!r}, "
                f"rho={self.rho!r}, method={self.method.name})")


def robust_problem_record(systems: Sequence[LinearSystem], polyhedron: Polyhedron, method: Method) -> dict:
    """The problem record of a robust certificate: ``hull`` (the A_i), G, b and the method.

    >>> from exactinv.model.methods import taylor
    >>> robust_problem_record([LinearSystem([[-1]])], Polyhedron.box([-1], [1]), taylor(1))["hull"]
    [[['-1']]]
    """
    return {"hull": [mat(S.A) for S in systems], "G": mat(polyhedron.G), "b": vec(polyhedron.b),
            "method": method_record(method)}


def abscissa_bound(Hs: Sequence[Matrix | SparseRows], b: Sequence[Fraction]) -> tuple[Fraction, tuple[Fraction, ...]]:
    """(beta, v): for every H = sum_i lambda_i H_i of the hull (lambda in the simplex),
    alpha(H) <= beta = max_i max_r (H_i v)_r / v_r, with v = b if b > 0 else all ones.

    Collatz-Wielandt: H + cI >= 0 for c large, so alpha(H) + c = rho(H + cI) <= max_r ((H + cI)v)_r / v_r,
    and (H v)_r = sum_i lambda_i (H_i v)_r <= max_i (H_i v)_r v_r / v_r.

    >>> abscissa_bound([[[Fraction(-2), Fraction(1)], [Fraction(1), Fraction(-2)]]], [Fraction(-1), Fraction(1)])
    (Fraction(-1, 1), (Fraction(1, 1), Fraction(1, 1)))
    """
    v = tuple(b) if all(x > 0 for x in b) else tuple(Fraction(1) for _ in b)
    beta = max(fraction_of(hv) / vr for H in Hs for hv, vr in zip(SparseRows.of(H).times(v), v))
    return beta, v


def _systems(systems: Any, n: int) -> tuple[LinearSystem, ...]:
    if isinstance(systems, (LinearSystem, str, bytes)) or not isinstance(systems, Sequence) or not systems:
        raise InvalidInput("systems: expected a nonempty list [S_1, ..., S_k] of exactinv.LinearSystem (the hull's vertices)")
    out = []
    for i, S in enumerate(systems):
        S = S if isinstance(S, LinearSystem) else LinearSystem(S)
        if S.n != n:
            raise InvalidInput(f"systems[{i}]: A is {S.n}x{S.n} but G has {n} columns")
        out.append(S)
    return tuple(out)


def _over(a: Real, g: Fraction) -> Real:
    return a / g


def robust_threshold(systems: Sequence[LinearSystem], polyhedron: Polyhedron, method: Method) -> RobustThreshold:
    """A threshold valid for every A in conv{A_1, ..., A_k} and every switching sequence, exactly.

    ``systems``: the hull's vertices (LinearSystems or matrices); ``polyhedron`` P; ``method``.
    Raises :class:`~exactinv.NotInvariant` when a vertex does not keep P invariant (that
    vertex is in the hull) and :class:`~exactinv.Undecided` for a rational method on a P
    with lines (no hull-wide proof of E2' is implemented) or an undecided radius.

    x' = -x and x' = -2x on [-1, 1], Taylor 2: gamma = max(1/2, 1) = 1, rho = 1, tau = 1:

    >>> from exactinv.model.methods import taylor
    >>> r = robust_threshold([LinearSystem([[-1]]), LinearSystem([[-2]])], Polyhedron.box([-1], [1]), taylor(2))
    >>> r.value, r.attained, r.gammas, r.forward_euler_step
    (Fraction(1, 1), True, (Fraction(1, 2), Fraction(1, 1)), Fraction(1, 1))
    """
    expect_set(polyhedron, "polyhedron", "polyhedron")
    method = check_method(method)
    Ss = _systems(systems, polyhedron.n)
    P = check_pair(Ss[0], polyhedron)[1]
    vertices = tuple(optimal_gamma(S, P) for S in Ss)
    for i, g in enumerate(vertices):
        if g.witness is not None:
            raise NotInvariant(f"systems[{i}]: P is not invariant for the hull's vertex A_{i} (gamma* = oo), "
                               "so no robust threshold exists", g.witness)
    gammas = tuple(g.value for g in vertices)
    gamma = max(gammas, key=ExactKey)
    radius = absolute_monotonicity_radius(method)
    rho = radius.value
    positive = not isinstance(gamma, Infinity) and gamma > 0
    beta = v = None
    if method.is_polynomial:
        if positive:
            value, attained = (INF, True) if isinstance(rho, Infinity) else (_over(rho, gamma), radius.attained)
        else:  # H >= 0: tau = oo iff every sigma_k >= 0 (erratum E6)
            value, attained = (INF, True) if all(s >= 0 for s in method.numerator) else (Fraction(0), True)
    else:
        if P.lines:
            raise Undecided("robust_threshold: a rational method on a P with lines: H does not see A along "
                            "the lineality space and no hull-wide proof that r(hA) exists (erratum E2') is "
                            "implemented; use a P without lines or a polynomial method")
        if rho == 0:
            value, attained = Fraction(0), True
        else:
            candidates = []
            if positive and not isinstance(rho, Infinity):
                candidates.append((_over(rho, gamma), radius.attained))
            pole = smallest_positive_pole(method)
            if pole is not None and P.m:
                beta, v = abscissa_bound([g.H_sparse for g in vertices], P.b)
                if beta > 0:
                    candidates.append((_over(pole, beta), False))
            value, attained = INF, True
            for bound, at in candidates:
                c = exact_cmp(bound, value)
                if c < 0:
                    value, attained = bound, at
                elif c == 0:
                    attained = attained and at
    return RobustThreshold(value, attained, gamma, gammas, rho, beta, v, method, P, Ss, vertices, radius)
