"""Steplength thresholds of the paper (Section 3), corrected where it errs.

Polynomial methods r(z) = sum_k sigma_k z^k (Theorem 3.4 of the paper):
with gamma = gamma* and H^ = H + gamma I >= 0,

    r(dt H) = sum_i f_i(dt) H^i,   f_i(dt) = sum_{k=i}^p (-1)^(k-i) sigma_k C(k,i) gamma^(k-i) dt^k,

so r(dt H) >= 0 while every f_i >= 0.  tau_i is the end of the first interval
[0, tau_i] on which f_i >= 0 -- the first root of *odd* multiplicity, or 0 when
f_i is negative right after 0 (the paper's "first positive zero" is wrong in
both respects: erratum E5 in docs/errata.md) -- and tau = min_i tau_i.

For gamma* <= 0 the paper's Theorem 3.13 gives tau = infinity.  That holds when
every sigma_k >= 0 (then H >= 0 and r(dt H) >= 0 for all dt), but not when
some sigma_k < 0 (erratum E6): then rho = 0 and the theorem yields no positive
threshold, so exactinv reports 0.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from math import comb

from exactinv_check.format import ClaimType

from ..core.algebraic import ExactKey, Real
from ..core.encode import encode_real
from ..core.latex import dt_poly_latex, latex_real, latex_text
from ..core.results import ExactValueMixin
from ..core.roots import nonnegative_until
from ..core.scalars import INF, Infinity
from ..core.sparse import SparseRows
from ..invariance.gamma_star import OptimalGamma
from ..model import Method
from ..model.record import certificate as make_certificate
from ..monotonicity.radius import AbsoluteMonotonicityRadius

__all__ = ["FiRow", "SteplengthThreshold", "f_i", "f_i_symbolic", "polynomial_threshold"]


@dataclass(frozen=True)
class FiRow:
    """One row of the f_i table: f_i at gamma = gamma* (coefficients of dt^0..dt^p)
    and tau_i = sup{T : f_i >= 0 on [0, T]}."""

    i: int
    f: tuple[Fraction, ...]
    tau: Real

    def __repr__(self) -> str:
        return f"FiRow(i={self.i}, tau={self.tau})"


@dataclass(frozen=True)
class SteplengthThreshold(ExactValueMixin):
    """A valid steplength threshold tau: A_d(dt) P subset of P for every dt in
    [0, tau] (``attained``) or [0, tau) (not ``attained``).

    ``value`` is a Fraction, a :class:`~exactinv.RealAlgebraic` or ``INF``;
    ``lower``/``upper`` are rationals enclosing it (``lower`` is itself a
    safe steplength); ``theorem`` names the result that proves it; ``table``
    holds the f_i rows (polynomial methods) and ``binding`` the index i that
    attains the minimum; ``notes`` records where the paper was corrected.
    """

    value: Real
    attained: bool
    theorem: str
    method: Method = field(repr=False)
    gamma: OptimalGamma = field(repr=False)
    table: tuple[FiRow, ...] = field(default=(), repr=False)
    binding: int | None = None
    notes: tuple[str, ...] = field(default=(), repr=False)
    radius: AbsoluteMonotonicityRadius | None = field(default=None, repr=False)
    pole: Real | None = field(default=None, repr=False)
    spectral_abscissa: Real | None = field(default=None, repr=False)
    paper_value: Real | None = field(default=None, repr=False)
    certificate_H: tuple[SparseRows, Real] | None = field(default=None, repr=False)

    @property
    def paper(self) -> Real:
        """What the paper's theorem, taken literally, gives (differs from
        ``value`` where exactinv corrects an erratum)."""
        return self.value if self.paper_value is None else self.paper_value



    def claims(self) -> list[dict]:
        """gamma*'s claim, then the threshold's (with the radius' claim for a rational method).

        >>> import exactinv as ei
        >>> S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
        >>> [str(c['type']) for c in ei.steplength_threshold(S, P, ei.methods.taylor(2)).claims()]
        ['gamma_star', 'polynomial_threshold']
        """
        return self.gamma.claims() + self._own_claims()

    def _own_claims(self) -> list[dict]:
        if self.method.is_polynomial:
            return [{
                "type": ClaimType.POLYNOMIAL_THRESHOLD,
                "value": encode_real(self.value),
                "binding": self.binding,
                "f": [{"i": r.i, "coefficients": [str(c) for c in r.f], "tau": encode_real(r.tau)} for r in self.table],
            }]
        claim = {
            "type": ClaimType.RATIONAL_THRESHOLD,
            "value": encode_real(self.value),
            "attained": self.attained,
            "rho": encode_real(self.radius.value),
            "pole": None if self.pole is None else encode_real(self.pole),
            # alpha(H) is recorded where the E2 bound z_p/alpha(H) is the binding one
            "alpha": encode_real(self.spectral_abscissa) if "erratum E2:" in self.theorem else None,
        }
        if self.certificate_H is not None:  # another H than gamma*'s was better for the E2 bound
            H, g_H = self.certificate_H
            claim["H"] = H.encode()
            claim["gamma_H"] = str(g_H)
        return self.radius.claims() + [claim]

    @property
    def certificate(self) -> dict:
        """The JSON certificate (gamma* and this threshold) for :func:`exactinv.check`."""
        return make_certificate(self.gamma.system, self.gamma.polyhedron, self.method, [self])

    def to_latex(self) -> str:
        """The threshold in LaTeX.

        >>> import exactinv as ei
        >>> S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
        >>> print(ei.steplength_threshold(S, P, ei.methods.taylor(1)).to_latex())
        \\begin{array}{l} \\tau = 1\\ (\\text{Theorem 3.4 (polynomial methods)}) \\\\ \\begin{array}{c|l|l} i & f_i(\\Delta t) & \\tau_i \\\\ \\hline 0 & 1-\\Delta t & 1 \\\\ 1 & \\Delta t & \\infty \\end{array} \\end{array}
        """  # noqa: E501 (doctest output)
        note = latex_text(self.theorem + ("" if self.attained else ", not attained"))
        text = rf"\tau = {latex_real(self.value)}\ ({note})"
        if not self.table:
            return text
        # one array holds the line and the f_i table: a bare \\ breaks inline math in LaTeX
        rows = r" \\ ".join(rf"{r.i} & {dt_poly_latex(r.f)} & {latex_real(r.tau)}" for r in self.table)
        table = rf"\begin{{array}}{{c|l|l}} i & f_i(\Delta t) & \tau_i \\ \hline {rows} \end{{array}}"
        return rf"\begin{{array}}{{l}} {text} \\ {table} \end{{array}}"

    def f_symbolic(self):
        """The f_i as sympy expressions in dt and gamma (the paper's eq. (20)).

        >>> import exactinv as ei
        >>> S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
        >>> ei.steplength_threshold(S, P, ei.methods.taylor(1)).f_symbolic()   # forward Euler: f_0 = 1 - gamma dt, f_1 = dt
        [-Delta_t*gamma + 1, Delta_t]
        """
        return f_i_symbolic(self.method)

    def __repr__(self) -> str:
        return (f"SteplengthThreshold(value={self.value}, attained={self.attained}, "
                f"method={self.method.name}, gamma*={self.gamma.value}, binding={self.binding})")


def f_i(sigmas: tuple[Fraction, ...], gamma: Fraction, i: int) -> tuple[Fraction, ...]:
    """Coefficients (dt^0 .. dt^p) of f_i(dt) = sum_{k=i}^p (-1)^(k-i) sigma_k C(k,i) gamma^(k-i) dt^k.

    >>> sigmas = (Fraction(1), Fraction(1), Fraction(1, 2))   # Taylor-2: 1 + z + z^2/2
    >>> [f_i(sigmas, Fraction(1), i) for i in range(3)]   # 1 - dt + dt^2/2, dt - dt^2, dt^2/2
    [(Fraction(1, 1), Fraction(-1, 1), Fraction(1, 2)), (Fraction(0, 1), Fraction(1, 1), Fraction(-1, 1)), (Fraction(0, 1), Fraction(0, 1), Fraction(1, 2))]
    """  # noqa: E501 (doctest output)
    p = len(sigmas) - 1
    return tuple(
        Fraction(0) if k < i else (-1) ** (k - i) * sigmas[k] * comb(k, i) * gamma ** (k - i)
        for k in range(p + 1)
    )


def f_i_symbolic(method: Method):
    """[f_0, ..., f_p] as sympy expressions in the symbols dt and gamma.

    >>> from exactinv.model import methods
    >>> f_i_symbolic(methods.taylor(2))
    [Delta_t**2*gamma**2/2 - Delta_t*gamma + 1, -Delta_t**2*gamma + Delta_t, Delta_t**2/2]
    """
    import sympy  # for display only

    dt, gamma = sympy.symbols("Delta_t gamma", positive=True)
    s = [sympy.Rational(c.numerator, c.denominator) for c in method.sigmas]
    p = len(s) - 1
    return [
        sum((-1) ** (k - i) * s[k] * sympy.binomial(k, i) * gamma ** (k - i) * dt**k for k in range(i, p + 1))
        for i in range(p + 1)
    ]


def polynomial_threshold(method: Method, gamma: OptimalGamma) -> SteplengthThreshold:
    """The paper's threshold for a polynomial method (Theorems 3.4 and 3.13), gamma = gamma*.

    >>> import exactinv as ei
    >>> S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    >>> polynomial_threshold(ei.methods.taylor(2), ei.optimal_gamma(S, P)).value   # gamma* = 1: min_i tau_i = 1
    Fraction(1, 1)
    """
    sigmas = method.sigmas
    g = gamma.value
    if isinstance(g, Infinity) or g <= 0:
        if all(s >= 0 for s in sigmas):
            return SteplengthThreshold(INF, True, "Theorem 3.13 (gamma* <= 0, all sigma_k >= 0)", method, gamma)
        return SteplengthThreshold(
            Fraction(0), True, "Theorem 3.13 corrected (gamma* <= 0, some sigma_k < 0: rho = 0)", method, gamma,
            notes=("erratum E6: the paper gives infinity here",),
        )
    table = []
    for i in range(len(sigmas)):
        coeffs = f_i(sigmas, g, i)
        table.append(FiRow(i, coeffs, nonnegative_until(coeffs)))
    binding = min(range(len(table)), key=lambda i: ExactKey(table[i].tau))
    value = table[binding].tau
    notes = ()
    if any(s == 0 for s in sigmas[1:]) or any(s < 0 for s in sigmas):
        notes = ("erratum E5: tau_i is where f_i stops being >= 0, not its first positive zero",)
    return SteplengthThreshold(value, True, "Theorem 3.4 (polynomial methods)", method, gamma, tuple(table), binding, notes)
