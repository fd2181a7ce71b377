"""The one set of argument validators for the public functions that take a
system, a polyhedron and a method (bad input -> :class:`~exactinv.InvalidInput`).
"""

from __future__ import annotations

from typing import Any

from ..core.scalars import Matrix, to_matrix, to_rational
from ..errors import EmptyPolyhedron, InvalidInput
from .methods import Method
from .polyhedron import Polyhedron
from .sets import expect_set, set_family
from .system import LinearSystem

__all__ = ["check_polyhedron", "check_pair", "check_method", "check_problem", "discrete_map"]


_FOR_ELLIPSOIDS = ("; gamma* and the paper's thresholds are about polyhedra -- on an Ellipsoid use "
                   "continuous_invariance, discrete_invariance, forward_euler_threshold, valid_steplengths "
                   "or largest_threshold")


def check_polyhedron(P: Any) -> Polyhedron:
    """P itself, if it is a nonempty :class:`Polyhedron`.

    >>> from exactinv.model import Polyhedron
    >>> check_polyhedron(Polyhedron.box([-1], [1])).b
    (Fraction(1, 1), Fraction(1, 1))
    """
    if set_family(P) == "ellipsoid":
        raise InvalidInput(f"polyhedron: got an Ellipsoid{_FOR_ELLIPSOIDS}")
    expect_set(P, "polyhedron", "polyhedron")
    if P.is_empty:
        raise EmptyPolyhedron("polyhedron: P = {x : Gx <= b} is empty; invariance questions about it are vacuous")
    return P


def check_method(method: Any) -> Method:
    """method itself, if it is a :class:`Method`.

    >>> from exactinv.model import methods
    >>> check_method(methods.taylor(2)).name
    'taylor(2)'
    """
    if not isinstance(method, Method):
        raise InvalidInput(f"method: expected an exactinv method (exactinv.methods.*), got {type(method).__name__}")
    return method


def check_pair(S: Any, P: Any) -> tuple[LinearSystem, Polyhedron]:
    """(S, P), if S is a :class:`LinearSystem` and P a nonempty polyhedron of its dimension.

    >>> from exactinv.model import LinearSystem, Polyhedron
    >>> S, P = check_pair(LinearSystem([[-1]]), Polyhedron.box([-1], [1]))
    >>> S.n, P.m
    (1, 2)
    """
    if not isinstance(S, LinearSystem):
        raise InvalidInput(f"system: expected an exactinv.LinearSystem, got {type(S).__name__}")
    if set_family(P) == "ellipsoid":
        raise InvalidInput(f"polyhedron: got an Ellipsoid{_FOR_ELLIPSOIDS}")
    expect_set(P, "polyhedron", "polyhedron")
    if S.n != P.n:
        raise InvalidInput(f"system/polyhedron: A is {S.n}x{S.n} but G has {P.n} columns")
    return S, check_polyhedron(P)


def check_problem(S: Any, P: Any, method: Any) -> tuple[LinearSystem, Polyhedron, Method]:
    """(S, P, method), each checked.

    >>> from exactinv.model import LinearSystem, Polyhedron, methods
    >>> S, P, method = check_problem(LinearSystem([[-1]]), Polyhedron.box([-1], [1]), methods.taylor(1))
    >>> method.name
    'taylor(1)'
    """
    S, P = check_pair(S, P)
    return S, P, check_method(method)


def discrete_map(Ad: Any, method: Any, dt: Any, n: int, where: str, allow_float: bool = False) -> tuple[Matrix, dict]:
    """The exact matrix A_d of ``discrete_invariance`` and its origin: ``Ad`` itself
    (a square matrix), or, for a :class:`LinearSystem` with ``method`` and a rational
    ``dt >= 0``, A_d = r(dt A) built exactly (origin names system, method and dt).
    ``n`` is the dimension of the set ``where`` (P or E) lives in.

    >>> from exactinv.model import methods
    >>> discrete_map(LinearSystem([[-1]]), methods.forward_euler(), "1/2", 1, "P")[0]
    ((Fraction(1, 2),),)
    """
    origin: dict = {}
    if isinstance(Ad, LinearSystem):
        if method is None or dt is None:
            raise InvalidInput("discrete_invariance: with a LinearSystem, pass method= and dt= too")
        dt = to_rational(dt, "dt", allow_float=allow_float)
        if dt < 0:
            raise InvalidInput(f"dt: must be >= 0, got {dt}")
        origin = {"system": Ad, "method": method, "dt": dt}
        Ad = method.matrix(Ad, dt)
    elif method is not None or dt is not None:
        raise InvalidInput("discrete_invariance: method= and dt= need a LinearSystem as first argument")
    Adm = to_matrix(Ad, "Ad", square=True, allow_float=allow_float)
    if len(Adm) != n:
        raise InvalidInput(f"Ad: is {len(Adm)}x{len(Adm)} but {where} lives in dimension {n}")
    return Adm, origin
