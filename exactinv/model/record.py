"""The problem record of a certificate (A, G, b and the method's r = g/h; Q for an ellipsoid) and
the certificate of results computed on a problem (the one envelope)."""

from __future__ import annotations

from typing import Any, Iterable

from ..core.encode import envelope, mat, vec
from .methods import Method
from .polyhedron import Polyhedron
from .sets import set_family
from .system import LinearSystem

__all__ = ["method_record", "problem_record", "generator_record", "certificate"]


def method_record(method: Method) -> dict:
    """The method's name and the coefficients of r = g/h.

    >>> from exactinv.model import methods
    >>> method_record(methods.taylor(2))
    {'name': 'taylor(2)', 'numerator': ['1', '1', '1/2'], 'denominator': ['1']}
    """
    return {"name": method.name, "numerator": vec(method.numerator), "denominator": vec(method.denominator)}


def problem_record(system: LinearSystem, polyhedron: Polyhedron, method: Method | None = None) -> dict:
    """A, G, b (or Q for an ellipsoid) and (optionally) the method, as exact strings.

    >>> from exactinv.model import LinearSystem, Polyhedron
    >>> problem_record(LinearSystem([['-1/2']]), Polyhedron.box([-1], [1]))
    {'A': [['-1/2']], 'G': [['1'], ['-1']], 'b': ['1', '1']}
    """
    if set_family(polyhedron) == "ellipsoid":
        record = {"A": mat(system.A), "Q": mat(polyhedron.Q)}
    else:
        record = {"A": mat(system.A), "G": mat(polyhedron.G), "b": vec(polyhedron.b)}
    if method is not None:
        record["method"] = method_record(method)
    return record


def generator_record(polyhedron: Polyhedron) -> dict:
    """P's vertices, rays and lines (the kernel proves the list complete).

    >>> from exactinv.model import Polyhedron
    >>> generator_record(Polyhedron.box([0], [1]))
    {'vertices': [['0'], ['1']], 'rays': [], 'lines': []}
    """
    return {"vertices": mat(polyhedron.vertices), "rays": mat(polyhedron.rays), "lines": mat(polyhedron.lines)}


def certificate(system: LinearSystem, polyhedron: Polyhedron, method: Method | None = None,
                results: Iterable[Any] = ()) -> dict:
    """One certificate for a problem and the results computed on it (each result owns ``claims()``).

    >>> from exactinv.model import LinearSystem, Polyhedron
    >>> cert = certificate(LinearSystem([[-1]]), Polyhedron.box([-1], [1]))
    >>> cert['problem'], cert['claims']
    ({'A': [['-1']], 'G': [['1'], ['-1']], 'b': ['1', '1']}, [])
    """
    return envelope(problem_record(system, polyhedron, method), results)
