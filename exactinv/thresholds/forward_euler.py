"""The largest forward-Euler threshold (paper, Section 3.3/3.4, Lemma 3.14): the result of
:func:`exactinv.forward_euler_threshold` on a polyhedron -- 1/gamma* from the verified LP,
cross-checked against the largest threshold of r(z) = 1 + z computed by the one valid-set
engine (:mod:`exactinv.validset.engine`, any route)."""

from __future__ import annotations

from dataclasses import dataclass, field

from exactinv_check.format import ClaimType

from ..core.algebraic import Real
from ..core.encode import encode_real
from ..core.latex import latex_real
from ..core.results import ExactValueMixin
from ..invariance.gamma_star import OptimalGamma
from ..model.record import certificate as make_certificate
from ..model.record import generator_record

__all__ = ["ForwardEulerThreshold"]


@dataclass(frozen=True)
class ForwardEulerThreshold(ExactValueMixin):
    """The largest forward-Euler threshold, derived twice (paper, Section 3.4):
    ``by_gamma`` = 1/gamma* (Lemma 3.14) and ``by_vertices`` = the largest threshold of
    r(z) = 1 + z by the valid-set engine's ``route`` (on the vertex route: min_i eps^i,
    eps^i = max{t : x^i + t A x^i in P}, rays and lines likewise); they must agree.
    ``binding`` = (kind, generator index in the route's own list, facet) of the condition
    that binds (None when nothing binds)."""

    value: Real
    by_gamma: Real
    by_vertices: Real
    binding: tuple[str, int, int] | None
    gamma: OptimalGamma = field(repr=False)
    attained: bool = True
    route: str = field(default="vertex", repr=False)

    def claims(self) -> list[dict]:
        """gamma*'s claim and the forward-Euler value (the kernel redoes the vertex ratio tests).

        >>> import exactinv as ei
        >>> from exactinv.model import LinearSystem, Polyhedron
        >>> fe = ei.forward_euler_threshold(LinearSystem([[-1, 1], [-1, -1]]), Polyhedron.box([-1, -1], [1, 1]))
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

        >>> import exactinv as ei
        >>> from exactinv.model import LinearSystem, Polyhedron
        >>> print(ei.forward_euler_threshold(LinearSystem([[-2]]), Polyhedron.box([-1], [1])).to_latex())   # gamma* = 1: (1 - 2 dt) x stays in [-1, 1] iff dt <= 1
        \\tau_{FE} = 1/\\gamma^* = 1
        """  # noqa: E501 (doctest output)
        return rf"\tau_{{FE}} = 1/\gamma^* = {latex_real(self.value)}"

    @property
    def certificate(self) -> dict:
        """The JSON certificate for :func:`exactinv.check`."""
        return make_certificate(self.gamma.system, self.gamma.polyhedron, None, [self])
