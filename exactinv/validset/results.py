"""The results of the valid-set engine: valid steplength sets and largest thresholds
(on a polyhedron, any route; on an ellipsoid) and the ellipsoid's forward-Euler step.

Immutable, exact (every end a Fraction, an exact algebraic number or INF),
each with its certificate claim; ``route`` names the route of
:mod:`exactinv.validset` that found the conditions (the certificate shows it
by its record: ``box``, ``lp``, or the generator lists of the vertex route).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from exactinv_check.format import ClaimType

from ..conditions.box import BoxRoute
from ..conditions.polyhedron import Condition
from ..conditions.pruning import Pruning
from ..core.algebraic import Real
from ..core.encode import encode_real, vec
from ..core.intervals import IntervalUnion
from ..core.latex import latex_real
from ..core.results import ExactValueMixin
from ..model import Ellipsoid, LinearSystem, Method, Polyhedron
from ..model.record import certificate as make_certificate
from ..model.record import generator_record
from .lp_route import LPRoute

__all__ = ["ValidSteplengths", "LargestThreshold", "EllipsoidValidSteplengths", "EllipsoidLargestThreshold",
           "EllipsoidForwardEulerThreshold"]


@dataclass(frozen=True)
class ValidSteplengths:
    """The exact set {dt >= 0 : A_d(dt) P subset of P}.  Iterate for the
    intervals; ``dt in V`` for a rational dt."""

    intervals: IntervalUnion
    method: Method = field(repr=False)
    singular: tuple[Real, ...] = field(default=(), repr=False)
    conditions: int = field(default=0, repr=False)
    distinct: int = field(default=0, repr=False)

    system: LinearSystem | None = field(default=None, repr=False)
    polyhedron: Polyhedron | None = field(default=None, repr=False)
    determinant: tuple[Fraction, ...] = field(default=(Fraction(1),), repr=False)
    pruning: Pruning | None = field(default=None, repr=False)
    box: BoxRoute | None = field(default=None, repr=False)
    lp: LPRoute | None = field(default=None, repr=False)
    route: str = field(default="vertex", repr=False)
    """Which route of :mod:`exactinv.validset` found the conditions: "vertex", "box", "lp" or "ellipsoid"."""

    def __iter__(self):
        return iter(self.intervals)

    def __len__(self) -> int:
        return len(self.intervals)

    def claims(self) -> list[dict]:
        """The certificate's claim: the intervals and the generators they were decided on.

        x' = -x on [-1, 1], forward Euler: 1 - dt in [-1, 1] iff dt in [0, 2].

        >>> import exactinv as ei
        >>> V = ei.valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1))
        >>> [(c["intervals"], c["box"]) for c in V.claims()]       # P is a box: no vertex list
        [([{'lo': '0', 'hi': '2', 'lo_closed': True, 'hi_closed': True}], {'lo': ['-1'], 'hi': ['1']})]
        >>> V = ei.valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1),
        ...                       box=False)
        >>> V.claims()[0]["vertices"]
        [['-1'], ['1']]
        """
        return [{
            "type": ClaimType.VALID_STEPLENGTHS,
            "intervals": [{"lo": encode_real(iv.lo), "hi": encode_real(iv.hi), "lo_closed": iv.lo_closed,
                           "hi_closed": iv.hi_closed} for iv in self.intervals],
            **_generators(self.polyhedron, self.box, self.lp),
            "determinant": vec(self.determinant),
            **({} if self.pruning is None or not self.pruning.applied else {"pruning": self.pruning.record()}),
        }]

    @property
    def certificate(self) -> dict:
        """The JSON certificate for :func:`exactinv.check`."""
        return make_certificate(self.system, self.polyhedron, self.method, [self])

    def __contains__(self, t: Any) -> bool:
        return t in self.intervals

    def __repr__(self) -> str:
        return f"ValidSteplengths({self.intervals!r}, method={self.method.name})"

    def _repr_latex_(self) -> str:
        return self.intervals._repr_latex_()

    def to_latex(self) -> str:
        """The intervals in LaTeX (x' = -x on [-1, 1], forward Euler: [0, 2]).

        >>> import exactinv as ei
        >>> V = ei.valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1))
        >>> V.to_latex()
        '[0, 2]'
        """
        return self.intervals._repr_latex_().strip("$")


@dataclass(frozen=True)
class LargestThreshold(ExactValueMixin):
    """The exact largest threshold: the end of the first interval of the valid
    set, ``attained`` if that end is itself valid.  ``binding`` is the
    condition (vertex/ray, facet, polynomial) whose sign change ends the
    interval, or None when a pole of r(dt A) (``singular``) ends it."""

    value: Real
    attained: bool
    method: Method = field(repr=False)
    binding: Condition | None = None
    singular: Real | None = None
    system: LinearSystem | None = field(default=None, repr=False)
    polyhedron: Polyhedron | None = field(default=None, repr=False)
    checked: tuple[Condition, ...] = field(default=(), repr=False)
    determinant: tuple[Fraction, ...] = field(default=(Fraction(1),), repr=False)
    pruning: Pruning | None = field(default=None, repr=False)
    box: BoxRoute | None = field(default=None, repr=False)
    lp: LPRoute | None = field(default=None, repr=False)
    route: str = field(default="vertex", repr=False)
    """Which route of :mod:`exactinv.validset` found the conditions: "vertex", "box", "lp" or "ellipsoid"."""

    def claims(self) -> list[dict]:
        """The certificate's claim: the value, whether attained, and the binding condition.

        x' = -x on [-1, 1], Taylor(2): r(dt) = 1 - dt + dt^2/2 >= 1/2 > -1, and r <= 1 iff
        dt - dt^2/2 >= 0 (vertex 1 on the facet x <= 1) iff dt <= 2: tau = 2, attained.

        >>> import exactinv as ei
        >>> L = ei.largest_threshold(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(2))
        >>> claim = L.claims()[0]
        >>> claim["value"], claim["attained"], claim["binding"]["generator"], claim["binding"]["poly"]
        ('2', True, 1, ['0', '1', '-1/2'])
        """
        return [{
            "type": ClaimType.LARGEST_THRESHOLD,
            "value": encode_real(self.value),
            "attained": self.attained,
            **_generators(self.polyhedron, self.box, self.lp),
            "determinant": vec(self.determinant),
            "binding": None if self.binding is None else {
                "kind": self.binding.kind, "generator": self.binding.generator, "facet": self.binding.facet,
                "poly": vec(self.binding.poly)},
            **({} if self.pruning is None or not self.pruning.applied else {"pruning": self.pruning.record()}),
        }]

    @property
    def certificate(self) -> dict:
        """The JSON certificate for :func:`exactinv.check`."""
        return make_certificate(self.system, self.polyhedron, self.method, [self])

    def to_latex(self) -> str:
        """tau_max in LaTeX with whether it is attained (Taylor(2), x' = -x on [-1, 1]: 2, attained).

        >>> import exactinv as ei
        >>> L = ei.largest_threshold(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(2))
        >>> print(L.to_latex())
        \\tau_{\\max} = 2\\ (\\text{attained})
        """
        return rf"\tau_{{\max}} = {latex_real(self.value)}\ (\text{{{'attained' if self.attained else 'not attained'}}})"

    def __repr__(self) -> str:
        return f"LargestThreshold(value={self.value}, attained={self.attained}, method={self.method.name})"


def _generators(polyhedron: Polyhedron, box: BoxRoute | None, lp: LPRoute | None = None) -> dict:
    """The claim's record of P: the box (proved from G, b by the kernel), the LP route's
    pieces (proved by the kernel: no vertex list) or the generator lists."""
    if box is not None:
        return {"box": box.box.record()}
    if lp is not None:
        return {"lp": lp.record()}
    return generator_record(polyhedron)


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

        >>> import exactinv as ei
        >>> from exactinv.model import methods
        >>> E = Ellipsoid([[1, 0], [0, 1]])
        >>> ei.valid_steplengths(ei.LinearSystem([[-1, -2], [2, -1]]), E, methods.forward_euler()).claims()
        [{'type': 'ellipsoid_valid_steplengths', 'intervals': [{'lo': '0', 'hi': '2/5', 'lo_closed': True, 'hi_closed': True}], 'determinant': ['1']}]
        """  # noqa: E501 (doctest output)
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

        >>> import exactinv as ei
        >>> from exactinv.model import methods
        >>> E = Ellipsoid([[1, 0], [0, 1]])
        >>> ei.largest_threshold(ei.LinearSystem([[-1, 0], [0, -1]]), E, methods.taylor(2)).claims()
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
    (the generalised eigenvalue, :mod:`exactinv.thresholds.ellipsoid_forward_euler`) and ``by_valid_set``
    (the one engine on the ellipsoid route's coefficient polynomials); they must agree.  The valid set is [0, value]."""

    value: Real
    by_eigenvalue: Real
    by_valid_set: Real
    system: LinearSystem = field(repr=False)
    ellipsoid: Ellipsoid = field(repr=False)
    attained: bool = True

    def claims(self) -> list[dict]:
        """The certificate claim: the exact value (the checker recomputes both routes).

        A = [[-a, -b], [b, -a]], Q = I: K = 2a I, B = (a^2 + b^2) I, tau = 2a/(a^2 + b^2).

        >>> import exactinv as ei
        >>> E = Ellipsoid([[1, 0], [0, 1]])
        >>> ei.forward_euler_threshold(ei.LinearSystem([[-1, -2], [2, -1]]), E).claims()
        [{'type': 'ellipsoid_forward_euler_threshold', 'value': '2/5'}]
        """
        return [{"type": ClaimType.ELLIPSOID_FORWARD_EULER_THRESHOLD, "value": encode_real(self.value)}]

    @property
    def certificate(self) -> dict:
        """The JSON certificate for :func:`exactinv.check`."""
        return make_certificate(self.system, self.ellipsoid, None, [self])

    def to_latex(self) -> str:
        """LaTeX: tau_FE = the exact value.

        >>> import exactinv as ei
        >>> E = Ellipsoid([[1, 0], [0, 1]])
        >>> print(ei.forward_euler_threshold(ei.LinearSystem([[-1, -2], [2, -1]]), E).to_latex())
        \\tau_{FE} = \\frac{2}{5}
        """
        return rf"\tau_{{FE}} = {latex_real(self.value)}"
