"""The model (layer ``model``): the system x' = Ax, the polyhedron P = {x : Gx <= b}
(H/V via pplpy), the methods r = g/h, argument validation, the problem record."""

from .methods import Method
from .polyhedron import Polyhedron
from .system import LinearSystem

__all__ = ["LinearSystem", "Polyhedron", "Method"]
