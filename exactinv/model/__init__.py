"""The model (layer ``model``): the system x' = Ax, the polyhedron P = {x : Gx <= b}
(H/V via pplpy), the ellipsoid E = {x : x^T Q x <= 1}, the methods r = g/h, argument validation, the problem record."""

from .ellipsoid import Ellipsoid
from .methods import Method
from .polyhedron import Polyhedron
from .system import LinearSystem

__all__ = ["LinearSystem", "Polyhedron", "Ellipsoid", "Method"]
