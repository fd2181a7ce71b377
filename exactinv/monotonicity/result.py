"""The radius of absolute monotonicity as a result: rho(r) exactly, the argument
that decides it, and its certificate claim (computed by
:func:`exactinv.monotonicity.radius.absolute_monotonicity_radius`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction

from exactinv_check.format import ClaimType, RadiusReason

from ..core.algebraic import Real
from ..core.encode import encode_real, envelope
from ..core.latex import latex_real, latex_text
from ..core.real_algebraic import RealAlgebraic
from ..core.results import ExactValueMixin
from ..model.methods import Method
from ..model.record import method_record

__all__ = ["AbsoluteMonotonicityRadius"]


@dataclass(frozen=True)
class AbsoluteMonotonicityRadius(ExactValueMixin):
    """rho(r), exactly, with the argument that decides it.

    ``reason`` is one of ``"coefficient"`` (c_binding changes sign at rho),
    ``"no-positive-pole"``, ``"principal-part-sign"``, ``"dominance-at-0"``
    (rho = 0 with ``witness_j``: c_j(0) < 0), ``"all-coefficients"`` (a
    polynomial whose c_j are >= 0 for all kappa), ``"termwise"`` / ``"product"``
    (rho = INF: all partial-fraction terms are absolutely monotonic on
    (-oo, 0], resp. r is a positive multiple of prod (1 - z/p_k)^(-m_k)),
    ``"bernstein"`` (rho = INF: r(-x) is completely monotone), ``"bernstein-root"``
    (c = lim r < 0 while f >= 0: rho is the one positive root of g(-kappa), attained).
    ``tail_index`` is the N beyond which the tail is certified positive;
    ``poles`` every pole exactly (x, y) = x + iy for a balanced tie of several poles (``"balanced-tie"``);
    ``pole`` the smallest positive real pole p* (None for polynomials).
    ``attained``: is rho itself in the set (r absolutely monotonic at -rho).
    """

    value: Real
    attained: bool
    reason: RadiusReason
    method: Method = field(repr=False)
    binding: int | None = None
    witness_j: int | None = None
    tail_index: int | None = None
    pole: Fraction | RealAlgebraic | None = None
    coefficients: tuple[tuple[Fraction, ...], ...] = field(default=(), repr=False)
    poles: tuple[tuple[Fraction, Fraction], ...] = field(default=(), repr=False)  # a balanced tie's poles x + iy


    @property
    def certificate(self) -> dict:
        """A certificate with the method only (no system or polyhedron)."""
        return envelope({"method": method_record(self.method)}, [self])

    def to_latex(self) -> str:
        """rho and its reason in LaTeX (the trapezoid: rho = 2).

        >>> from exactinv.model import methods
        >>> from exactinv.monotonicity.radius import absolute_monotonicity_radius
        >>> print(absolute_monotonicity_radius(methods.trapezoid()).to_latex())
        \\rho = 2\\ (\\text{bernstein-root})
        """
        return rf"\rho = {latex_real(self.value)}\ ({latex_text(self.reason)})"

    def claims(self) -> list[dict]:
        """The certificate's claim: rho, its reason and the coefficient polynomials d_j.

        Taylor(2): c_0 = 1 - k + k^2/2 > 0, c_1 = 1 - k >= 0 iff k <= 1, c_2 = 1/2: rho = 1 (binding j = 1).

        >>> from exactinv.model import methods
        >>> from exactinv.monotonicity.radius import absolute_monotonicity_radius
        >>> claim = absolute_monotonicity_radius(methods.taylor(2)).claims()[0]
        >>> claim["value"], claim["binding"], claim["d"]
        ('1', 1, [['1', '-1', '1/2'], ['1', '-1'], ['1/2']])
        """
        claim = {"type": ClaimType.ABSOLUTE_MONOTONICITY_RADIUS, "value": encode_real(self.value), "reason": self.reason,
                 "attained": self.attained}
        if self.binding is not None:
            claim["binding"] = self.binding
        if self.witness_j is not None:
            claim["witness_j"] = self.witness_j
        if self.tail_index is not None:
            claim["tail_index"] = self.tail_index
        if self.coefficients:
            claim["d"] = [[str(c) for c in d] for d in self.coefficients]
        if self.pole is not None:
            claim["pole"] = encode_real(self.pole)
        if self.poles:
            claim["poles"] = [[str(x), str(y)] for x, y in self.poles]
        return [claim]
