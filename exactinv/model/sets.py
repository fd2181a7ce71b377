"""The invariant-set types of the model, and the one test of which type a value is.

A set S of the problem "is S invariant for x' = Ax (x+ = A_d x), and for which steps?" is a
:class:`~exactinv.model.polyhedron.Polyhedron` P = {x : Gx <= b} (the paper) or an
:class:`~exactinv.model.ellipsoid.Ellipsoid` E = {x : x^T Q x <= 1} (beyond the paper).  Each set
type names its ``family``; :func:`set_family` is the one place that looks at a value's type, and
:func:`expect_set` turns a value of the wrong type into an :class:`~exactinv.errors.InvalidInput`
naming the argument.  (Which algorithm runs on which family is decided once, by the route
protocol: exactinv.validset.families.)
"""

from __future__ import annotations

from typing import Any

from ..errors import InvalidInput
from .ellipsoid import Ellipsoid
from .polyhedron import Polyhedron

__all__ = ["SET_TYPES", "set_family", "expect_set"]

SET_TYPES = {"polyhedron": Polyhedron, "ellipsoid": Ellipsoid}


def set_family(value: Any) -> str | None:
    """``"polyhedron"``, ``"ellipsoid"``, or None for a value that is no set of the model
    (a subclass counts as its family).

    >>> set_family(Polyhedron.box([0], [1])), set_family(Ellipsoid([[1]])), set_family([[1]])
    ('polyhedron', 'ellipsoid', None)
    """
    return value.family if isinstance(value, (Polyhedron, Ellipsoid)) else None


def expect_set(value: Any, family: str, argument: str) -> Any:
    """``value`` itself if it is a set of ``family``; else InvalidInput naming ``argument``.

    >>> expect_set(Ellipsoid([[1]]), "polyhedron", "polyhedron")
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: polyhedron: expected an exactinv.Polyhedron, got Ellipsoid
    """
    if set_family(value) != family:
        raise InvalidInput(f"{argument}: expected an exactinv.{SET_TYPES[family].__name__}, got {type(value).__name__}")
    return value
