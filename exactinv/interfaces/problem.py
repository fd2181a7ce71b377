"""Problem files: the JSON format read by ``exactinv certify`` (docs/problem-format.md,
docs/problem.schema.json).

    {"system": {"A": [["-1", "1"], ["-1", "-1"]]},          # or {"A0", "B", "F"}
     "polyhedron": {"G": [[1, 0], ...], "b": [1, ...]},     # or {"vertices", "rays", "lines"}, or {"cdd": "P.ine"}
     "method": {"taylor": 4}}                               # optional

or, instead of "polyhedron", an ellipsoid {x : x^T Q x <= 1}:
    "ellipsoid": {"Q": [["2", "0"], ["0", "1"]]}

or a gain to design (docs/design.md): x' = Ax + Bu, u = Fx with the optimal F,
optionally with inputs U = {u : Eu <= e} (a polyhedron in R^p):
    "system": {"A": ..., "B": ...}, "design": "optimal_gain", "inputs": {"G": ..., "b": ...}

Rationals are strings ("3/4"; "0.1" means exactly 1/10) or integers; JSON
floats are refused like Python floats.  Unknown keys are refused at every
level, with a "did you mean" hint.  Errors name the file and the JSON path.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

from ..core.moved import moved_names
from ..core.scalars import Matrix, to_matrix
from ..errors import InvalidInput
from ..model import Ellipsoid, LinearSystem, Polyhedron
from ..model.methods import Method
from ..validset.families import ELLIPSOIDS, family_of
from .method_format import parse_method
from .strict_json import (
    JsonPath,
    check_keys,
    expect_object,
    json_kind,
    parse_strict_json,
    require_keys,
)

__all__ = ["Problem", "load_problem", "TOP_KEYS"]

# the method parsers live in exactinv.interfaces.method_format, did_you_mean in strict_json; the old spelling warns
__getattr__ = moved_names(__name__, {"METHOD_KINDS": "exactinv.interfaces.method_format",
                                     "method_from_text": "exactinv.interfaces.method_format",
                                     "did_you_mean": "exactinv.interfaces.strict_json"})

TOP_KEYS = ("system", "polyhedron", "ellipsoid", "method", "name", "description", "design", "inputs")
DESIGNS = ("optimal_gain",)
"""The keys a problem file may hold (system and one of polyhedron, ellipsoid are required)."""


@dataclass(frozen=True)
class Problem:
    """A problem: ``polyhedron`` holds the invariant set, a Polyhedron or an Ellipsoid.
    ``design == "optimal_gain"``: ``system`` is the open loop x' = Ax, ``B`` its input
    matrix and ``inputs`` the optional input polyhedron U (:func:`exactinv.optimal_gain`)."""

    system: LinearSystem
    polyhedron: Polyhedron | Ellipsoid
    method: Method | None = None
    name: str = "problem"
    design: str | None = field(default=None, repr=False)
    B: Matrix | None = field(default=None, repr=False)
    inputs: Polyhedron | None = field(default=None, repr=False)

    @property
    def is_ellipsoid(self) -> bool:
        return family_of(self.polyhedron) is ELLIPSOIDS


def _section(data: dict, key: str) -> dict:
    if key not in data:
        raise InvalidInput(f"{key}: missing section (a problem file needs \"system\" and \"polyhedron\" or \"ellipsoid\")")
    return expect_object(data[key], key, "a JSON object")


def _system(data: dict) -> LinearSystem:
    sys_data = _section(data, "system")
    check_keys(sys_data, ("A", "A0", "B", "F"), "system")
    if "A" in sys_data:
        if set(sys_data) != {"A"}:
            raise InvalidInput('system: give "A", or "A0", "B" and "F" -- not both')
        with JsonPath("system", ("A", "A0", "B", "F")):
            return LinearSystem(sys_data["A"])
    if {"A0", "B", "F"} <= set(sys_data):
        with JsonPath("system", ("A", "A0", "B", "F")):
            return LinearSystem.closed_loop(sys_data["A0"], sys_data["B"], sys_data["F"])
    missing = sorted({"A0", "B", "F"} - set(sys_data))
    raise InvalidInput(f'system: give "A", or "A0", "B" and "F" (missing {", ".join(missing)})')


POLYHEDRON_KEYS = ("G", "b", "vertices", "rays", "lines", "cdd")


def _cdd(poly: dict, base: str | None, key: str) -> Polyhedron:
    if set(poly) != {"cdd"}:
        raise InvalidInput(f'{key}: give "cdd" (a cdd file) alone, without "G", "b", "vertices", "rays", "lines"')
    ref = poly["cdd"]
    if not isinstance(ref, str) or not ref.strip():
        raise InvalidInput(f"{key}.cdd: expected the path of a cdd file (.ine or .ext), got {json_kind(ref)}")
    if "\n" in ref.strip():  # the file's text, inline
        source = ref
    else:
        source = ref if os.path.isabs(ref) else os.path.join(base or os.curdir, ref)
    try:
        return Polyhedron.from_cdd(source)
    except InvalidInput as exc:
        raise InvalidInput(f"{key}.cdd: {exc}") from None


def _polyhedron(data: dict, base: str | None = None, key: str = "polyhedron") -> Polyhedron:
    poly = _section(data, key)
    check_keys(poly, POLYHEDRON_KEYS, key)
    if "cdd" in poly:
        return _cdd(poly, base, key)
    h_keys, v_keys = {"G", "b"} & set(poly), {"vertices", "rays", "lines"} & set(poly)
    if h_keys and v_keys:
        raise InvalidInput(f'{key}: give "G" and "b", or "vertices" (with optional "rays", "lines"), '
                           'or "cdd" -- not both')
    if h_keys:
        require_keys(poly, ("G", "b"), key)
        with JsonPath(key, POLYHEDRON_KEYS):
            return Polyhedron(poly["G"], poly["b"])
    if "vertices" in poly:
        with JsonPath(key, POLYHEDRON_KEYS):
            return Polyhedron.from_vertices(poly["vertices"], poly.get("rays", ()), poly.get("lines", ()))
    raise InvalidInput(f'{key}: give "G" and "b", or "vertices" (with optional "rays", "lines"), or "cdd"')


def _design(data: dict, name: str, base: str | None = None) -> Problem:
    """A gain-design problem: "system": {"A", "B"}, "design": "optimal_gain", optional "inputs"."""
    if data["design"] not in DESIGNS:
        raise InvalidInput(f"design: expected one of {', '.join(map(repr, DESIGNS))}, got {data['design']!r}")
    if "ellipsoid" in data:
        raise InvalidInput('design: a gain is designed on a "polyhedron", not an ellipsoid')
    sys_data = _section(data, "system")
    check_keys(sys_data, ("A", "B"), "system")
    if set(sys_data) != {"A", "B"}:
        raise InvalidInput('system: "design": "optimal_gain" needs "A" and "B" (x\' = Ax + Bu)')
    with JsonPath("system", ("A", "B")):
        system = LinearSystem(sys_data["A"])
        B = to_matrix(sys_data["B"], "B", shape=(system.n, None))
    polyhedron = _polyhedron(data, base)
    if system.n != polyhedron.n:
        raise InvalidInput(f"polyhedron: the system has dimension {system.n} "
                           f"but the polyhedron lives in dimension {polyhedron.n}")
    inputs = _polyhedron(data, base, "inputs") if "inputs" in data else None
    if inputs is not None and inputs.n != len(B[0]):
        raise InvalidInput(f"inputs: B has {len(B[0])} columns (inputs) but the input polyhedron lives in dimension {inputs.n}")
    method = parse_method(data["method"]) if data.get("method") is not None else None
    return Problem(system, polyhedron, method, name, "optimal_gain", B, inputs)


def _ellipsoid(data: dict) -> Ellipsoid:
    ell = expect_object(data["ellipsoid"], "ellipsoid", "a JSON object")
    check_keys(ell, ("Q",), "ellipsoid")
    require_keys(ell, ("Q",), "ellipsoid")
    with JsonPath("ellipsoid", ("Q",)):
        return Ellipsoid(ell["Q"])


def _invariant_set(data: dict, base: str | None) -> Polyhedron | Ellipsoid:
    if "ellipsoid" in data:
        if "polyhedron" in data:
            raise InvalidInput('ellipsoid: give "polyhedron" or "ellipsoid" -- not both')
        return _ellipsoid(data)
    return _polyhedron(data, base)


def problem_from_dict(data: Any, name: str = "problem", base: str | None = None) -> Problem:
    """A :class:`Problem` from the parsed JSON of a problem file (every key checked).
    A relative ``{"cdd": path}`` polyhedron is looked up in the folder ``base``
    (the problem file's folder; the working directory when ``None``).

    >>> problem_from_dict({"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, "1/2"]},
    ...                    "method": {"taylor": 2}}, "box")
    Problem(system=LinearSystem(A=[[-1]]), polyhedron=Polyhedron(G=[[1], [-1]], b=[1, 1/2]), method=Method(taylor(2): r(z) = z**2/2 + z + 1), name='box')
    >>> problem_from_dict({"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}, "methd": "rk4"})
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: methd: unknown key; did you mean "method"? (allowed: ...)
    """  # noqa: E501 (doctest output)
    if not isinstance(data, dict):
        raise InvalidInput(f"expected a JSON object with \"system\" and \"polyhedron\", got {json_kind(data)}")
    if {"format", "claims"} & set(data):
        raise InvalidInput("this is a certificate, not a problem file (use `exactinv check` or `exactinv explain`)")
    check_keys(data, TOP_KEYS, "")
    if "name" in data:
        if not isinstance(data["name"], str):
            raise InvalidInput(f"name: expected a string, got {json_kind(data['name'])}")
        name = data["name"]
    if "description" in data and not isinstance(data["description"], str):
        raise InvalidInput(f"description: expected a string, got {json_kind(data['description'])}")
    if "design" in data:
        return _design(data, name, base)
    if "inputs" in data:
        raise InvalidInput('inputs: an input polyhedron belongs to a gain design ("design": "optimal_gain")')
    system = _system(data)
    polyhedron = _invariant_set(data, base)
    if system.n != polyhedron.n:
        what = family_of(polyhedron).name
        raise InvalidInput(f"{what}: the system has dimension {system.n} but the {what} lives in dimension {polyhedron.n}")
    method = parse_method(data["method"]) if data.get("method") is not None else None
    return Problem(system, polyhedron, method, name)


def load_problem(source: Any, base: str | None = None) -> Problem:
    """Read a problem from a dict, a JSON string or a path to a JSON file.
    Errors from a file are prefixed with its path.  A cdd file the problem
    names (``"polyhedron": {"cdd": "P.ine"}``) is found relative to the problem
    file's folder, or to ``base`` (default: the working directory) for a dict or
    JSON text.

    >>> import pathlib, exactinv
    >>> examples = pathlib.Path(exactinv.__file__).parents[1] / "examples"
    >>> p = load_problem(examples / "paper_box_taylor4.json")
    >>> p.name, p.system, p.polyhedron.m, p.method.name
    ('paper_box_taylor4', LinearSystem(A=[[-1, 1], [-1, -1]]), 4, 'taylor(4)')
    >>> load_problem('{"system": {"A": [[-1]]}, "ellipsoid": {"Q": [["1/4"]]}}').polyhedron
    Ellipsoid(Q=[[1/4]])
    >>> load_problem('{"system": {"A": [[-1.0]]}, "ellipsoid": {"Q": [[1]]}}')
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: the JSON number -1.0 is a float; write it as a string ("-1.0") to mean it exactly
    """
    if isinstance(source, dict):
        return problem_from_dict(source, base=base)
    if isinstance(source, str) and source.lstrip().startswith("{"):
        return problem_from_dict(parse_strict_json(source, "problem"), base=base)
    if not isinstance(source, (str, os.PathLike)):
        raise InvalidInput(f"problem: expected a dict, JSON text or a path, got {type(source).__name__}")
    path = str(source)
    name = os.path.splitext(os.path.basename(path))[0]
    if os.path.isdir(path):
        raise InvalidInput(f"{path}: is a directory, not a problem file")
    try:
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
    except OSError as exc:
        raise InvalidInput(f"{path}: cannot read the problem file ({exc.strerror or exc})") from None
    except UnicodeDecodeError:
        raise InvalidInput(f"{path}: not a text file (a problem file is UTF-8 JSON)") from None
    try:
        return problem_from_dict(parse_strict_json(text, path), name, os.path.dirname(os.path.abspath(path)))
    except InvalidInput as exc:
        if str(exc).startswith(path):
            raise
        raise type(exc)(f"{path}: {exc}") from None
