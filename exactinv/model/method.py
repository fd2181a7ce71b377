"""The Method type: an exact stability function r = g/h (paper, Section 3).

A one-step method applied to x' = Ax gives x+ = r(dt A) x; ``Method`` holds g
and h as Fractions, coprime, with h(0) = 1 and r(0) = 1 (:func:`make_method`
normalises them).  The constructors are in :mod:`exactinv.model.families` and
:mod:`exactinv.model.presets`; :mod:`exactinv.model.methods` gathers them all.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any, Sequence

import flint

from ..core.flintq import fmpq_matrix, fmpq_of, fraction_of, matrix_of
from ..core.latex import latex_text
from ..core.scalars import Matrix, Vector, to_matrix, to_rational
from ..errors import InvalidInput
from .system import LinearSystem

__all__ = ["Method", "matrix_polynomial"]


@dataclass(frozen=True)
class Method:
    """A discretization method given by its stability function r = g/h.

    ``numerator`` and ``denominator`` hold the coefficients of g and h from
    the constant term up; they are coprime, h(0) = 1 and g(0) = 1.
    ``butcher`` keeps the (A, b) tableau when the method came from one.
    """

    name: str
    numerator: Vector
    denominator: Vector
    butcher: tuple[Matrix, Vector] | None = field(default=None, repr=False, compare=False)

    @property
    def is_polynomial(self) -> bool:
        return len(self.denominator) == 1

    @property
    def sigmas(self) -> Vector:
        """sigma_0..sigma_p of a polynomial method (its Taylor coefficients)."""
        if not self.is_polynomial:
            raise InvalidInput(f"method {self.name}: a rational method has no finite sigma list")
        return self.numerator

    @property
    def g(self) -> flint.fmpq_poly:
        return flint.fmpq_poly([fmpq_of(c) for c in self.numerator])

    @property
    def h(self) -> flint.fmpq_poly:
        return flint.fmpq_poly([fmpq_of(c) for c in self.denominator])

    def __call__(self, z: Any) -> Fraction:
        """r(z) at a rational z (an error at a pole)."""
        zq = fmpq_of(to_rational(z, "z"))
        den = self.h(zq)
        if den == 0:
            raise InvalidInput(f"method {self.name}: z = {z} is a pole of r")
        return fraction_of(self.g(zq) / den)

    def matrix(self, system: Any, dt: Fraction) -> Matrix:
        """A_d = r(dt A) = h(dt A)^{-1} g(dt A), exactly; an error if h(dt A)
        is singular (dt A has an eigenvalue at a pole of r).

        >>> from exactinv.model.families import backward_euler, forward_euler
        >>> forward_euler().matrix([[-1]], Fraction(1, 2))   # 1 + (1/2)(-1)
        ((Fraction(1, 2),),)
        >>> backward_euler().matrix([[-1]], Fraction(1))     # 1/(1 - (-1))
        ((Fraction(1, 2),),)
        """
        A = system.A_flint if isinstance(system, LinearSystem) else fmpq_matrix(to_matrix(system, "A", square=True))
        M = A * fmpq_of(to_rational(dt, "dt"))
        G = matrix_polynomial(self.numerator, M)
        if self.is_polynomial:
            return matrix_of(G)
        H = matrix_polynomial(self.denominator, M)
        try:
            return matrix_of(H.solve(G))
        except ZeroDivisionError:
            raise InvalidInput(f"method {self.name}: h(dt A) is singular at dt = {dt}; r(dt A) is undefined") from None

    def to_sympy(self, z=None):
        """r(z) = g(z)/h(z) as a sympy expression (in the symbol z unless given).

        >>> from exactinv.model.families import backward_euler
        >>> backward_euler().to_sympy()
        1/(1 - z)
        """
        import sympy

        z = z if z is not None else sympy.Symbol("z")
        g = sum(sympy.Rational(c.numerator, c.denominator) * z**k for k, c in enumerate(self.numerator))
        h = sum(sympy.Rational(c.numerator, c.denominator) * z**k for k, c in enumerate(self.denominator))
        return g / h

    def to_latex(self) -> str:
        """LaTeX: r(z) = g(z)/h(z) and the method's name.

        >>> from exactinv.model.families import backward_euler
        >>> print(backward_euler().to_latex())
        r(z) = \\frac{1}{1 - z} \\quad (\\text{backward}\\_\\text{euler})
        """
        import sympy

        return rf"r(z) = {sympy.latex(self.to_sympy())} \quad ({latex_text(self.name)})"

    def _repr_latex_(self) -> str:
        return "$" + self.to_latex() + "$"

    def __repr__(self) -> str:
        return f"Method({self.name}: r(z) = {self.to_sympy()})"


def matrix_polynomial(coeffs: Sequence[Fraction], M: flint.fmpq_mat) -> flint.fmpq_mat:
    """sum_k coeffs[k] M^k, exactly (Horner).

    >>> M = flint.fmpq_mat(2, 2, [0, 1, 0, 0])     # nilpotent: M^2 = 0
    >>> matrix_polynomial([Fraction(1), Fraction(2), Fraction(5)], M)   # I + 2M
    [1, 2]
    [0, 1]
    """
    n = M.nrows()
    out = flint.fmpq_mat(n, n)
    for c in reversed(coeffs):  # Horner
        out = out * M
        if c:
            for i in range(n):
                out[i, i] += fmpq_of(c)
    return out


def trim_zeros(c: list[Fraction]) -> list[Fraction]:
    """The coefficient list c without its trailing zeros (at least one entry kept); c itself is shortened.

    >>> from fractions import Fraction
    >>> trim_zeros([Fraction(1), Fraction(2), Fraction(0), Fraction(0)])
    [Fraction(1, 1), Fraction(2, 1)]
    """
    while len(c) > 1 and c[-1] == 0:
        c.pop()
    return c


def make_method(name: str, num: Sequence[Fraction], den: Sequence[Fraction], butcher=None) -> Method:
    """The Method r = num/den (coefficients from z^0 up), exact: g and h made coprime with h(0) = 1;
    InvalidInput naming ``name`` when den is zero or vanishes at 0, or r(0) != 1.

    >>> from fractions import Fraction
    >>> m = make_method("backward Euler", [Fraction(2)], [Fraction(2), Fraction(-2)])
    >>> m.numerator, m.denominator
    ((Fraction(1, 1),), (Fraction(1, 1), Fraction(-1, 1)))
    """
    g = flint.fmpq_poly([fmpq_of(c) for c in num])
    h = flint.fmpq_poly([fmpq_of(c) for c in den])
    if h.is_zero():
        raise InvalidInput(f"method {name}: the denominator is the zero polynomial")
    d = h.gcd(g) if not g.is_zero() else h
    if d.degree() > 0:
        g, h = g / d, h / d  # exact division by the common factor
        g, h = flint.fmpq_poly(g), flint.fmpq_poly(h)
    if h(0) == 0:
        raise InvalidInput(f"method {name}: the denominator vanishes at z = 0 (r has a pole at 0)")
    scale = h(0)
    g, h = g / scale, h / scale
    if g(0) != 1:
        raise InvalidInput(f"method {name}: r(0) must be 1 (consistency: dt = 0 gives the identity), "
                           f"got r(0) = {fraction_of(g(0))}")
    numerator = trim_zeros([fraction_of(c) for c in g.coeffs()])
    denominator = trim_zeros([fraction_of(c) for c in h.coeffs()]) or [Fraction(1)]
    return Method(name, tuple(numerator), tuple(denominator), butcher)


