"""The largest forward-Euler threshold (paper, Section 3.3/3.4, Lemma 3.14):
1/gamma* from the verified LP, cross-checked against the vertex ratio tests
eps^i = max{t : x^i + t A x^i in P} (one per vertex, ray and line)."""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

from ..core.algebraic import Real, exact_lt
from ..core.encode import encode_real
from ..core.latex import latex_real
from ..core.results import ExactValueMixin
from ..core.scalars import INF, Infinity, fmpq_of, fraction_of
from ..core.tags import ClaimType
from ..errors import VerificationFailed
from ..model import LinearSystem, Polyhedron
from ..model.methods import forward_euler
from ..model.record import certificate as make_certificate, generator_record
from ..model.validate import check_problem
from .gamma_star import OptimalGamma, optimal_gamma

__all__ = ["ForwardEulerThreshold", "forward_euler_threshold"]


@dataclass(frozen=True)
class ForwardEulerThreshold(ExactValueMixin):
    """The largest forward-Euler threshold, derived twice (paper, Section 3.4):
    ``by_gamma`` = 1/gamma* (Lemma 3.14) and ``by_vertices`` = min_i eps^i with
    eps^i = max{t : x^i + t A x^i in P} (rays and lines likewise); they must agree.
    ``binding`` = (kind, generator index, facet) of the vertex ratio test that binds."""

    value: Real
    by_gamma: Real
    by_vertices: Real
    binding: tuple[str, int, int] | None
    gamma: OptimalGamma = field(repr=False)
    attained: bool = True

    def claims(self) -> list[dict]:
        """gamma*'s claim and the vertex ratio tests' value.

        >>> from exactinv.model import LinearSystem, Polyhedron
        >>> fe = forward_euler_threshold(LinearSystem([[-1, 1], [-1, -1]]), Polyhedron.box([-1, -1], [1, 1]))
        >>> [str(c['type']) for c in fe.claims()]
        ['gamma_star', 'forward_euler_threshold']
        """
        return self.gamma.claims() + [{
            "type": ClaimType.FORWARD_EULER_THRESHOLD,
            "value": encode_real(self.value),
            **generator_record(self.gamma.polyhedron),
        }]

    def to_latex(self) -> str:
        """The threshold in LaTeX.

        >>> from exactinv.model import LinearSystem, Polyhedron
        >>> print(forward_euler_threshold(LinearSystem([[-2]]), Polyhedron.box([-1], [1])).to_latex())   # gamma* = 1: (1 - 2 dt) x stays in [-1, 1] iff dt <= 1
        \\tau_{FE} = 1/\\gamma^* = 1
        """
        return rf"\tau_{{FE}} = 1/\gamma^* = {latex_real(self.value)}"

    @property
    def certificate(self) -> dict:
        """The JSON certificate for :func:`exactinv.check`."""
        return make_certificate(self.gamma.system, self.gamma.polyhedron, None, [self])


def forward_euler_threshold(system: LinearSystem, polyhedron: Polyhedron) -> ForwardEulerThreshold:
    """The largest forward-Euler steplength, exact, cross-checked: 1/gamma* from
    the verified LP and the vertex ratio tests must coincide.

    >>> from exactinv.model import LinearSystem, Polyhedron
    >>> fe = forward_euler_threshold(LinearSystem([[-1, 1], [-1, -1]]), Polyhedron.box([-1, -1], [1, 1]))
    >>> fe.value, fe.by_gamma, fe.by_vertices   # 1/gamma* with gamma* = 1; the vertex ratio tests agree
    (Fraction(1, 1), Fraction(1, 1), Fraction(1, 1))
    """
    check_problem(system, polyhedron, forward_euler())
    gamma = optimal_gamma(system, polyhedron)
    g = gamma.value
    by_gamma = Fraction(0) if g == INF else (INF if isinstance(g, Infinity) or g <= 0 else 1 / g)
    A = system.A_flint
    G, b = polyhedron.G, polyhedron.b
    best: Real = INF
    binding = None
    for kind, gens in (("vertex", polyhedron.vertices), ("ray", polyhedron.rays), ("line", polyhedron.lines)):
        for i, x in enumerate(gens):
            Ax = [sum(A[r, k] * fmpq_of(x[k]) for k in range(len(x))) for r in range(len(x))]
            Ax = [fraction_of(v) for v in Ax]
            for j, row in enumerate(G):
                rate = sum(gj * v for gj, v in zip(row, Ax))
                if kind == "line":
                    eps = INF if rate == 0 else Fraction(0)
                elif rate <= 0:
                    continue
                else:
                    slack = (b[j] if kind == "vertex" else 0) - sum(gj * v for gj, v in zip(row, x))
                    eps = slack / rate
                if exact_lt(eps, best):
                    best, binding = eps, (kind, i, j)
    if best != by_gamma:
        raise VerificationFailed(f"forward Euler: 1/gamma* = {by_gamma} but the vertex ratio tests give {best}")
    return ForwardEulerThreshold(best, by_gamma, best, binding, gamma)
