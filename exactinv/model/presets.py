"""Named Runge-Kutta methods by their exact stability functions, each from its
Butcher tableau (:func:`~exactinv.model.families.from_butcher`): explicit SSP
methods, RK4, Radau IIA, Lobatto IIIC, Gauss, SDIRK and SSP-SDIRK families,
and the :data:`PRESETS` table of names.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from ..core.scalars import to_rational
from ..errors import InvalidInput
from .families import backward_euler, forward_euler, from_butcher, implicit_midpoint, pade, trapezoid
from .method import Method

__all__ = [
    "heun", "ssprk22", "ssprk33", "rk4", "ssprk_s1", "radau_iia2", "lobatto_iiic2", "gauss2",
    "radau_iia1", "radau_iia3", "lobatto_iiic3", "lobatto_iiic4", "sdirk2", "sdirk4", "ssp_sdirk",
    "PRESETS", "preset",
]


# ---------------------------------------------------------------- RK presets
def heun() -> Method:
    """Heun's method (explicit trapezoid), R(z) = 1 + z + z^2/2.

    >>> heun().numerator
    (Fraction(1, 1), Fraction(1, 1), Fraction(1, 2))
    """
    return from_butcher([[0, 0], [1, 0]], ["1/2", "1/2"], name="heun")


def ssprk22() -> Method:
    """SSPRK(2,2) of Shu and Osher (the same tableau as Heun's method).

    >>> ssprk22()(-2)                             # 1 - 2 + 4/2
    Fraction(1, 1)
    """
    return from_butcher([[0, 0], [1, 0]], ["1/2", "1/2"], name="ssprk22")


def ssprk33() -> Method:
    """SSPRK(3,3) of Shu and Osher, R(z) = 1 + z + z^2/2 + z^3/6.

    >>> from exactinv.model.families import taylor
    >>> ssprk33().numerator == taylor(3).numerator
    True
    """
    return from_butcher([[0, 0, 0], [1, 0, 0], ["1/4", "1/4", 0]], ["1/6", "1/6", "2/3"], name="ssprk33")


def rk4() -> Method:
    """The classical fourth-order Runge-Kutta method.

    >>> from exactinv.model.families import taylor
    >>> rk4().numerator == taylor(4).numerator    # R(z) = 1 + z + ... + z^4/24
    True
    """
    return from_butcher(
        [[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]],
        ["1/6", "1/3", "1/3", "1/6"],
        name="rk4",
    )


def ssprk_s1(s: int) -> Method:
    """SSPRK(s,1): s forward-Euler stages of step dt/s, R(z) = (1 + z/s)^s.

    >>> ssprk_s1(2).numerator                     # (1 + z/2)^2 = 1 + z + z^2/4
    (Fraction(1, 1), Fraction(1, 1), Fraction(1, 4))
    """
    if not isinstance(s, int) or isinstance(s, bool) or s < 1:
        raise InvalidInput(f"s: the number of stages must be an int >= 1, got {s!r}")
    A = [[Fraction(1, s) if j < i else Fraction(0) for j in range(s)] for i in range(s)]
    return from_butcher(A, [Fraction(1, s)] * s, name=f"ssprk({s},1)")


def radau_iia2() -> Method:
    """The 2-stage Radau IIA method (order 3), R = (1 + z/3)/(1 - 2z/3 + z^2/6).

    >>> radau_iia2().denominator
    (Fraction(1, 1), Fraction(-2, 3), Fraction(1, 6))
    """
    return from_butcher([["5/12", "-1/12"], ["3/4", "1/4"]], ["3/4", "1/4"], name="radau_iia2")


def lobatto_iiic2() -> Method:
    """The 2-stage Lobatto IIIC method, R = 1/(1 - z + z^2/2).

    >>> lobatto_iiic2().denominator == pade(0, 2).denominator
    True
    """
    return from_butcher([["1/2", "-1/2"], ["1/2", "1/2"]], ["1/2", "1/2"], name="lobatto_iiic2")


def gauss2() -> Method:
    """The 2-stage Gauss method.  Its tableau is irrational (it has sqrt(3)),
    but its stability function is the (2,2) Pade approximant, which is rational.

    >>> gauss2().numerator                        # 1 + z/2 + z^2/12
    (Fraction(1, 1), Fraction(1, 2), Fraction(1, 12))
    """
    m = pade(2, 2)
    return Method("gauss2", m.numerator, m.denominator)


def radau_iia1() -> Method:
    """The 1-stage Radau IIA method: backward Euler, R = 1/(1 - z).

    >>> radau_iia1().denominator
    (Fraction(1, 1), Fraction(-1, 1))
    """
    return from_butcher([[1]], [1], name="radau_iia1")


def radau_iia3() -> Method:
    """The 3-stage Radau IIA method (order 5).  Its tableau has sqrt(6); its stability function is the
    (2,3) Pade approximant (Hairer-Wanner II, IV.5), which is rational.

    >>> radau_iia3()
    Method(radau_iia3: r(z) = (z**2/20 + 2*z/5 + 1)/(-z**3/60 + 3*z**2/20 - 3*z/5 + 1))
    """
    m = pade(2, 3)
    return Method("radau_iia3", m.numerator, m.denominator)


def lobatto_iiic3() -> Method:
    """The 3-stage Lobatto IIIC method (order 4), R = the (1,3) Pade approximant.

    >>> lobatto_iiic3().denominator == pade(1, 3).denominator
    True
    """
    return from_butcher([["1/6", "-1/3", "1/6"], ["1/6", "5/12", "-1/12"], ["1/6", "2/3", "1/6"]],
                        ["1/6", "2/3", "1/6"], name="lobatto_iiic3", c=[0, "1/2", 1])


def lobatto_iiic4() -> Method:
    """The 4-stage Lobatto IIIC method (order 6).  Its tableau has sqrt(5); its stability function is
    the (2,4) Pade approximant, which is rational.

    >>> len(lobatto_iiic4().denominator) - 1
    4
    """
    m = pade(2, 4)
    return Method("lobatto_iiic4", m.numerator, m.denominator)


def sdirk2(gamma: Any = "1/4") -> Method:
    """The 2-stage SDIRK family of order 2 (order 3 for gamma = (3 +- sqrt 3)/6, irrational):
    A = [[gamma, 0], [1 - 2 gamma, gamma]], b = (1/2, 1/2), for a rational gamma.

    >>> sdirk2("1/2")          # A = I/2: the stages decouple and R is the trapezoid's
    Method(sdirk2(1/2): r(z) = (z/2 + 1)/(1 - z/2))
    """
    g = to_rational(gamma, "gamma")
    return from_butcher([[g, 0], [1 - 2 * g, g]], ["1/2", "1/2"], name=f"sdirk2({g})")


def sdirk4() -> Method:
    """The 5-stage, L-stable SDIRK method of order 4 with gamma = 1/4 (Hairer-Wanner II, Table IV.6.5).

    >>> sdirk4().denominator[-1]      # det(I - zA) = (1 - z/4)^5
    Fraction(-1, 1024)
    """
    A = [["1/4", 0, 0, 0, 0], ["1/2", "1/4", 0, 0, 0], ["17/50", "-1/25", "1/4", 0, 0],
         ["371/1360", "-137/2720", "15/544", "1/4", 0], ["25/24", "-49/48", "125/16", "-85/12", "1/4"]]
    return from_butcher(A, A[-1], name="sdirk4", c=["1/4", "3/4", "11/20", "1/2", 1])


def ssp_sdirk(s: int) -> Method:
    """The optimal s-stage second-order SSP SDIRK method (Ketcheson, Macdonald, Gottlieb 2009):
    A_ii = 1/(2s), A_ij = 1/s (j < i), b_j = 1/s -- s implicit-midpoint steps of size dt/s.

    >>> ssp_sdirk(1)
    Method(ssp_sdirk(1): r(z) = (z/2 + 1)/(1 - z/2))
    """
    if not isinstance(s, int) or isinstance(s, bool) or s < 1:
        raise InvalidInput(f"s: the number of stages must be an int >= 1, got {s!r}")
    A = [[Fraction(1, 2 * s) if i == j else Fraction(1, s) if j < i else Fraction(0) for j in range(s)]
         for i in range(s)]
    return from_butcher(A, [Fraction(1, s)] * s, name=f"ssp_sdirk({s})")


PRESETS = {
    "forward_euler": forward_euler,
    "backward_euler": backward_euler,
    "trapezoid": trapezoid,
    "crank_nicolson": trapezoid,
    "implicit_midpoint": implicit_midpoint,
    "heun": heun,
    "ssprk22": ssprk22,
    "ssprk33": ssprk33,
    "rk4": rk4,
    "radau_iia2": radau_iia2,
    "lobatto_iiic2": lobatto_iiic2,
    "gauss2": gauss2,
    "radau_iia1": radau_iia1,
    "radau_iia3": radau_iia3,
    "lobatto_iiic3": lobatto_iiic3,
    "lobatto_iiic4": lobatto_iiic4,
    "sdirk2": sdirk2,
    "sdirk4": sdirk4,
    "ssp_sdirk2": lambda: ssp_sdirk(2),
    "ssp_sdirk3": lambda: ssp_sdirk(3),
}


def preset(name: str) -> Method:
    """A named method from :data:`PRESETS`.

    >>> preset("crank_nicolson")(-2)              # the trapezoid: (1 - 1)/(1 + 1)
    Fraction(0, 1)
    """
    try:
        return PRESETS[name]()
    except KeyError:
        raise InvalidInput(f"preset: unknown method {name!r}; known: {', '.join(sorted(PRESETS))}") from None

