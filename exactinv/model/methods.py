"""Discretization methods as exact stability functions r = g/h (paper, Section 3).

A one-step method applied to x' = Ax gives x+ = r(dt A) x.  For Taylor and
general polynomial methods r(z) = sum_k sigma_k z^k (sigma_0 = 1, Section
3.1); for rational methods r = g/h with r(0) = 1 (Section 3.2) -- backward
Euler, the theta-methods, Pade approximants and Runge-Kutta stability
functions R(z) = det(I - zA + z e b^T)/det(I - zA) of rational Butcher
tableaux.  Coefficients are Fractions; g and h are stored coprime with
h(0) = 1.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from math import factorial
from typing import Any, Sequence

import flint

from ..core.latex import latex_text
from ..core.polys import interpolate
from ..core.scalars import Matrix, Vector, fmpq_matrix, fmpq_of, fraction_of, matrix_of, to_matrix, to_rational, to_vector
from ..errors import InvalidInput
from .system import LinearSystem

__all__ = [
    "matrix_polynomial",
    "Method",
    "taylor",
    "polynomial",
    "forward_euler",
    "rational",
    "theta",
    "backward_euler",
    "trapezoid",
    "implicit_midpoint",
    "pade",
    "from_butcher",
    "heun",
    "ssprk22",
    "ssprk33",
    "rk4",
    "ssprk_s1",
    "radau_iia2",
    "lobatto_iiic2",
    "gauss2",
    "radau_iia1",
    "radau_iia3",
    "lobatto_iiic3",
    "lobatto_iiic4",
    "sdirk2",
    "sdirk4",
    "ssp_sdirk",
    "PRESETS",
    "preset",
]


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


def _trim(c: list[Fraction]) -> list[Fraction]:
    while len(c) > 1 and c[-1] == 0:
        c.pop()
    return c


def _make(name: str, num: Sequence[Fraction], den: Sequence[Fraction], butcher=None) -> Method:
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
        raise InvalidInput(f"method {name}: r(0) must be 1 (consistency: dt = 0 gives the identity), got r(0) = {fraction_of(g(0))}")
    numerator = _trim([fraction_of(c) for c in g.coeffs()])
    denominator = _trim([fraction_of(c) for c in h.coeffs()]) or [Fraction(1)]
    return Method(name, tuple(numerator), tuple(denominator), butcher)


# ------------------------------------------------------------ polynomial methods
def polynomial(sigmas: Sequence[Any], name: str | None = None) -> Method:
    """r(z) = sigma_0 + sigma_1 z + ... + sigma_p z^p with sigma_0 = 1 (Section 3.1).

    >>> polynomial([1, 1, "1/2", 0]).sigmas        # trailing zeros dropped: Heun's r
    (Fraction(1, 1), Fraction(1, 1), Fraction(1, 2))
    """
    s = list(to_vector(sigmas, "sigmas"))
    if s[0] != 1:
        raise InvalidInput(f"sigmas: sigma_0 must be 1 (A_d = I at dt = 0), got sigma_0 = {s[0]}")
    return Method(name or f"polynomial{tuple(str(x) for x in s)}", tuple(_trim(s)), (Fraction(1),))


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
    return _make(name, g, h)


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
    return _make(f"theta({t})", [Fraction(1), 1 - t], [Fraction(1), -t])


def backward_euler() -> Method:
    """r(z) = 1/(1 - z).

    >>> backward_euler()(-1)                      # 1/(1 + 1)
    Fraction(1, 2)
    """
    return _make("backward_euler", [Fraction(1)], [Fraction(1), Fraction(-1)])


def trapezoid() -> Method:
    """Crank-Nicolson: r(z) = (1 + z/2)/(1 - z/2).

    >>> trapezoid()(-2)                           # (1 - 1)/(1 + 1)
    Fraction(0, 1)
    >>> trapezoid()(-6)                           # (1 - 3)/(1 + 3)
    Fraction(-1, 2)
    """
    return _make("trapezoid", [Fraction(1), Fraction(1, 2)], [Fraction(1), Fraction(-1, 2)])


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
    den = [Fraction((-1) ** j * factorial(n - j) * factorial(l), factorial(n) * factorial(j) * factorial(l - j)) for j in range(l + 1)]
    return _make(f"pade({k},{l})", num, den)


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
    return _make(name, [fraction_of(c) for c in num.coeffs()] or [Fraction(0)],
                 [fraction_of(c) for c in den.coeffs()] or [Fraction(0)], butcher=(Am, bv))


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

    >>> ssprk33().numerator == taylor(3).numerator
    True
    """
    return from_butcher([[0, 0, 0], [1, 0, 0], ["1/4", "1/4", 0]], ["1/6", "1/6", "2/3"], name="ssprk33")


def rk4() -> Method:
    """The classical fourth-order Runge-Kutta method.

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
