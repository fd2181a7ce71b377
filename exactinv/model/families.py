"""Families of methods (paper, Section 3): Taylor and general polynomial
methods r(z) = sum_k sigma_k z^k (Section 3.1); rational methods r = g/h
(Section 3.2) -- backward Euler, the theta-methods, Pade approximants, and the
stability function R(z) = det(I - zA + z e b^T)/det(I - zA) of any rational
Butcher tableau.
"""

from __future__ import annotations

from fractions import Fraction
from math import factorial
from typing import Any, Sequence

import flint

from ..core.flintq import fmpq_matrix, fmpq_of, fraction_of
from ..core.polys import interpolate
from ..core.scalars import to_matrix, to_rational, to_vector
from ..errors import InvalidInput
from .method import Method, make_method, trim_zeros

__all__ = [
    "taylor", "polynomial", "forward_euler", "rational", "theta", "backward_euler", "trapezoid",
    "implicit_midpoint", "pade", "from_butcher",
]


# ------------------------------------------------------------ polynomial methods
def polynomial(sigmas: Sequence[Any], name: str | None = None) -> Method:
    """r(z) = sigma_0 + sigma_1 z + ... + sigma_p z^p with sigma_0 = 1 (Section 3.1).

    >>> polynomial([1, 1, "1/2", 0]).sigmas        # trailing zeros dropped: Heun's r
    (Fraction(1, 1), Fraction(1, 1), Fraction(1, 2))
    """
    s = list(to_vector(sigmas, "sigmas"))
    if s[0] != 1:
        raise InvalidInput(f"sigmas: sigma_0 must be 1 (A_d = I at dt = 0), got sigma_0 = {s[0]}")
    return Method(name or f"polynomial{tuple(str(x) for x in s)}", tuple(trim_zeros(s)), (Fraction(1),))


def taylor(p: int) -> Method:
    """The p-th order Taylor method, sigma_k = 1/k! (paper, eq. (13)).

    >>> taylor(3).numerator                       # 1, 1, 1/2!, 1/3!
    (Fraction(1, 1), Fraction(1, 1), Fraction(1, 2), Fraction(1, 6))
    """
    if not isinstance(p, int) or isinstance(p, bool) or p < 1:
        raise InvalidInput(f"p: the Taylor order must be an int >= 1, got {p!r}")
    return Method(f"taylor({p})", tuple(Fraction(1, factorial(k)) for k in range(p + 1)), (Fraction(1),))


def forward_euler() -> Method:
    """r(z) = 1 + z.

    >>> forward_euler()(-2)                       # 1 + (-2)
    Fraction(-1, 1)
    """
    return Method("forward_euler", (Fraction(1), Fraction(1)), (Fraction(1),))


# -------------------------------------------------------------- rational methods
def rational(num: Sequence[Any], den: Sequence[Any], name: str = "rational") -> Method:
    """r = g/h from coefficient lists (constant term first); r(0) = 1 is checked
    and common factors of g and h are cancelled.

    >>> rational([1, -1], [1, -2, 1]).denominator  # (1 - z)/(1 - z)^2 = 1/(1 - z)
    (Fraction(1, 1), Fraction(-1, 1))
    """
    g = to_vector(num, "num")
    h = to_vector(den, "den")
    return make_method(name, g, h)


def theta(theta_value: Any) -> Method:
    """The theta-method: r(z) = (1 + (1 - theta) z)/(1 - theta z).

    >>> theta("1/2")(-2)                          # (1 - 1)/(1 + 1)
    Fraction(0, 1)
    >>> theta(0).denominator                      # theta = 0 is forward Euler
    (Fraction(1, 1),)
    """
    t = to_rational(theta_value, "theta")
    if not 0 <= t <= 1:
        raise InvalidInput(f"theta: must lie in [0, 1], got {t}")
    return make_method(f"theta({t})", [Fraction(1), 1 - t], [Fraction(1), -t])


def backward_euler() -> Method:
    """r(z) = 1/(1 - z).

    >>> backward_euler()(-1)                      # 1/(1 + 1)
    Fraction(1, 2)
    """
    return make_method("backward_euler", [Fraction(1)], [Fraction(1), Fraction(-1)])


def trapezoid() -> Method:
    """Crank-Nicolson: r(z) = (1 + z/2)/(1 - z/2).

    >>> trapezoid()(-2)                           # (1 - 1)/(1 + 1)
    Fraction(0, 1)
    >>> trapezoid()(-6)                           # (1 - 3)/(1 + 3)
    Fraction(-1, 2)
    """
    return make_method("trapezoid", [Fraction(1), Fraction(1, 2)], [Fraction(1), Fraction(-1, 2)])


def implicit_midpoint() -> Method:
    """The implicit midpoint rule; for linear systems its r equals the trapezoid's.

    >>> implicit_midpoint().denominator == trapezoid().denominator
    True
    >>> implicit_midpoint()(-6)                   # (1 - 3)/(1 + 3)
    Fraction(-1, 2)
    """
    m = trapezoid()
    return Method("implicit_midpoint", m.numerator, m.denominator, ((( Fraction(1, 2),),), (Fraction(1),)))


def pade(k: int, l: int) -> Method:
    """The (k, l) Pade approximant of exp(z): numerator degree k, denominator degree l.

    >>> pade(1, 1).numerator, pade(1, 1).denominator   # the trapezoid (1 + z/2)/(1 - z/2)
    ((Fraction(1, 1), Fraction(1, 2)), (Fraction(1, 1), Fraction(-1, 2)))
    >>> pade(0, 2).denominator                    # 1/(1 - z + z^2/2)
    (Fraction(1, 1), Fraction(-1, 1), Fraction(1, 2))
    """
    for name, v in (("k", k), ("l", l)):
        if not isinstance(v, int) or isinstance(v, bool) or v < 0:
            raise InvalidInput(f"{name}: must be an int >= 0, got {v!r}")
    n = k + l
    num = [Fraction(factorial(n - j) * factorial(k), factorial(n) * factorial(j) * factorial(k - j)) for j in range(k + 1)]
    den = [Fraction((-1) ** j * factorial(n - j) * factorial(l), factorial(n) * factorial(j) * factorial(l - j))
           for j in range(l + 1)]
    return make_method(f"pade({k},{l})", num, den)


def from_butcher(A: Any, b: Any, name: str = "butcher", c: Any = None) -> Method:
    """The stability function R(z) = det(I - zA + z e b^T)/det(I - zA) of a
    rational Butcher tableau, by exact interpolation of both determinants
    at s + 1 rational points (both have degree <= s).  The nodes ``c`` do not
    enter R; if given they are checked: c = A 1 exactly (the row-sum condition).

    >>> from_butcher([[1]], [1]).denominator      # backward Euler: det(1 - z) = 1 - z
    (Fraction(1, 1), Fraction(-1, 1))
    >>> from_butcher([["1/2"]], [1])(-2)          # midpoint: (1 - 1)/(1 + 1)
    Fraction(0, 1)
    """
    Am = to_matrix(A, "A", square=True)
    s = len(Am)
    bv = to_vector(b, "b", length=s)
    if c is not None:
        cv = to_vector(c, "c", length=s)
        for i, (ci, row) in enumerate(zip(cv, Am)):
            if ci != sum(row):
                raise InvalidInput(f"c[{i}]: the nodes must be the row sums of A (c = A 1), "
                                   f"but c[{i}] = {ci} and row {i} of A sums to {sum(row)}")
    Aq = fmpq_matrix(Am)
    ebT = flint.fmpq_mat(s, s, [fmpq_of(bv[j]) for i in range(s) for j in range(s)])
    I = flint.fmpq_mat(s, s, [int(i == j) for i in range(s) for j in range(s)])
    points = list(range(s + 1))
    num_vals = [(I - Aq * z + ebT * z).det() for z in points]
    den_vals = [(I - Aq * z).det() for z in points]
    num = interpolate(points, num_vals)
    den = interpolate(points, den_vals)
    return make_method(name, [fraction_of(c) for c in num.coeffs()] or [Fraction(0)],
                 [fraction_of(c) for c in den.coeffs()] or [Fraction(0)], butcher=(Am, bv))


