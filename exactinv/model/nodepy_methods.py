"""Runge-Kutta methods from NodePy (``nodepy.runge_kutta_method``): the exact
stability function R(z) = det(I - zA + z e b^T)/det(I - zA) of a NodePy
method object (``ei.methods.from_nodepy``).

NodePy stores its Butcher coefficients as sympy numbers when they are exact
(Rationals, Integers, and for Gauss-Legendre, Lobatto, ... algebraic numbers
such as sqrt(3)) and as numpy floats otherwise.  Rational tableaux go through
:func:`~exactinv.model.families.from_butcher` (FLINT, exact).  Exact
irrational tableaux are expanded with sympy and accepted when R(z) has rational
coefficients (as for every Gauss-Legendre method: R is a Pade approximant);
otherwise they are refused, naming the coefficient.  Float tableaux are refused
unless ``allow_float=True``: each float is then taken as the exact value of the
double (:func:`~exactinv.exact_from_float`), so R is the exact stability
function *of the rounded tableau*, not of the method the floats approximate.

NodePy itself is optional (the ``nodepy`` extra): it is imported only here,
only when a method is converted.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from ..core.scalars import to_rational
from ..errors import InvalidInput
from .families import from_butcher, rational
from .method import Method

__all__ = ["from_nodepy"]


def from_nodepy(rkm: Any, name: str | None = None, *, allow_float: bool = False) -> Method:
    """The exact stability function of a NodePy Runge-Kutta method (the main
    weights ``b`` of an embedded pair), named after NodePy's ``name`` unless
    ``name`` is given.

    >>> from nodepy import runge_kutta_method as rk
    >>> from_nodepy(rk.SSPRK2(3)).numerator          # 1/3 + 2/3 (1 + z/2)^3
    (Fraction(1, 1), Fraction(1, 1), Fraction(1, 2), Fraction(1, 12))
    >>> from_nodepy(rk.loadRKM("GL2")).denominator     # Gauss-Legendre: sqrt(3) in A, R = Pade(2, 2)
    (Fraction(1, 1), Fraction(-1, 2), Fraction(1, 12))
    """
    try:
        from nodepy.runge_kutta_method import RungeKuttaMethod
    except ImportError:  # pragma: no cover - the extra is missing
        raise InvalidInput("from_nodepy: NodePy is not installed (pip install 'exactinv[nodepy]')") from None
    if not isinstance(rkm, RungeKuttaMethod):
        raise InvalidInput(f"rkm: expected a NodePy Runge-Kutta method (nodepy.runge_kutta_method.RungeKuttaMethod), "
                           f"got {type(rkm).__name__}")
    label = name or str(getattr(rkm, "name", None) or "nodepy")
    A, b = rkm.A, rkm.b
    s = len(b)
    if getattr(A, "shape", None) != (s, s):
        raise InvalidInput(f"rkm: {label}: A has shape {getattr(A, 'shape', None)} but b has {s} entries")
    entries = [(f"A[{i}][{j}]", A[i, j]) for i in range(s) for j in range(s)] + [(f"b[{j}]", b[j]) for j in range(s)]
    exact: dict[str, Fraction] = {}
    irrational = []
    for where, x in entries:
        if _is_sympy_irrational(x):
            irrational.append(where)
            continue
        exact[where] = to_rational(x, f"rkm ({label}): {where}", allow_float=allow_float)
    if not irrational:
        Aq = [[exact[f"A[{i}][{j}]"] for j in range(s)] for i in range(s)]
        bq = [exact[f"b[{j}]"] for j in range(s)]
        return from_butcher(Aq, bq, label)
    return _from_algebraic(A, b, s, label, irrational[0])


def _is_sympy_irrational(x: Any) -> bool:
    """An exact sympy number that is not rational (sqrt(3)/6, ...); sympy Floats are not exact."""
    return (getattr(x, "is_number", False) and getattr(x, "is_Rational", None) is False
            and not getattr(x, "is_Float", False) and not x.atoms(_sympy_float()))


def _sympy_float():
    import sympy

    return sympy.Float


def _from_algebraic(A: Any, b: Any, s: int, label: str, first: str) -> Method:
    """R = det(I - zA + z e b^T)/det(I - zA) over Q(algebraic numbers), with sympy;
    accepted only when both numerator and denominator come out rational."""
    import sympy

    z = sympy.Symbol("z")
    Am = sympy.Matrix(s, s, lambda i, j: sympy.sympify(A[i, j]))
    bm = sympy.Matrix(1, s, lambda i, j: sympy.sympify(b[j]))
    e = sympy.ones(s, 1)
    I = sympy.eye(s)
    num = sympy.expand((I - z * Am + z * e * bm).det(method="berkowitz"))
    den = sympy.expand((I - z * Am).det(method="berkowitz"))
    num_c = [sympy.simplify(c) for c in sympy.Poly(num, z).all_coeffs()[::-1]]
    den_c = [sympy.simplify(c) for c in sympy.Poly(den, z).all_coeffs()[::-1]]
    for which, coeffs in (("numerator", num_c), ("denominator", den_c)):
        for k, c in enumerate(coeffs):
            if not c.is_Rational:
                raise InvalidInput(f"rkm ({label}): the coefficients are irrational ({first} = {_entry(A, b, first)}) "
                                   f"and so is the {which} of R(z) at z^{k} ({c}); exactinv's methods are rational")
    return rational([Fraction(int(c.p), int(c.q)) for c in num_c], [Fraction(int(c.p), int(c.q)) for c in den_c], label)


def _entry(A: Any, b: Any, where: str) -> Any:
    if where.startswith("b"):
        return b[int(where[2:-1])]
    i, j = where[2:-1].split("][")
    return A[int(i), int(j)]
