"""Problem files: the JSON format read by ``exactinv certify``.

    {"system": {"A": [["-1", "1"], ["-1", "-1"]]},          # or {"A0", "B", "F"}
     "polyhedron": {"G": [[1, 0], ...], "b": [1, ...]},     # or {"vertices", "rays", "lines"}
     "method": {"taylor": 4}}                               # optional

Rationals are strings ("3/4"; "0.1" means exactly 1/10) or integers; JSON
floats are refused like Python floats.  Errors name the JSON path.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from typing import Any

from ..model import methods as _methods
from ..errors import InvalidInput
from ..model.methods import Method
from ..model import LinearSystem, Polyhedron

__all__ = ["Problem", "load_problem", "parse_method"]


@dataclass(frozen=True)
class Problem:
    system: LinearSystem
    polyhedron: Polyhedron
    method: Method | None = None
    name: str = "problem"


def parse_method(spec: Any) -> Method:
    """A method from its JSON form, e.g. {"taylor": 4} or {"preset": "backward_euler"}."""
    if isinstance(spec, str):
        return _methods.preset(spec)
    if not isinstance(spec, dict) or len(spec) != 1:
        raise InvalidInput(f"method: expected one key such as {{\"taylor\": 4}}, got {spec!r}")
    (kind, arg), = spec.items()
    if kind == "taylor":
        return _methods.taylor(arg)
    if kind == "polynomial":
        return _methods.polynomial(arg)
    if kind == "rational":
        if not isinstance(arg, dict) or set(arg) != {"num", "den"}:
            raise InvalidInput('method.rational: expected {"num": [...], "den": [...]}')
        return _methods.rational(arg["num"], arg["den"])
    if kind == "theta":
        return _methods.theta(arg)
    if kind == "pade":
        if not isinstance(arg, list) or len(arg) != 2:
            raise InvalidInput("method.pade: expected [k, l]")
        return _methods.pade(*arg)
    if kind == "butcher":
        if not isinstance(arg, dict) or set(arg) != {"A", "b"}:
            raise InvalidInput('method.butcher: expected {"A": [[...]], "b": [...]}')
        return _methods.from_butcher(arg["A"], arg["b"])
    if kind == "preset":
        return _methods.preset(arg)
    if kind == "ssprk_s1":
        return _methods.ssprk_s1(arg)
    raise InvalidInput(f"method: unknown kind {kind!r} (taylor, polynomial, rational, theta, pade, butcher, preset)")


def _section(data: dict, key: str) -> dict:
    value = data.get(key)
    if not isinstance(value, dict):
        raise InvalidInput(f"problem: missing or malformed section {key!r}")
    return value


def load_problem(source: Any) -> Problem:
    """Read a problem from a dict, a JSON string or a path to a JSON file."""
    name = "problem"
    if isinstance(source, (str, os.PathLike)) and not str(source).lstrip().startswith("{"):
        name = os.path.splitext(os.path.basename(str(source)))[0]
        try:
            with open(source) as fh:
                source = json.load(fh, parse_float=_refuse_float)
        except OSError as exc:
            raise InvalidInput(f"problem: cannot read {source}: {exc.strerror}") from None
        except json.JSONDecodeError as exc:
            raise InvalidInput(f"problem: {name} is not valid JSON ({exc})") from None
    elif isinstance(source, str):
        source = json.loads(source, parse_float=_refuse_float)
    if not isinstance(source, dict):
        raise InvalidInput("problem: expected a JSON object")
    sys_data = _section(source, "system")
    if "A" in sys_data:
        system = LinearSystem(sys_data["A"])
    elif {"A0", "B", "F"} <= set(sys_data):
        system = LinearSystem.closed_loop(sys_data["A0"], sys_data["B"], sys_data["F"])
    else:
        raise InvalidInput('problem.system: give "A", or "A0", "B" and "F"')
    poly = _section(source, "polyhedron")
    if "G" in poly:
        polyhedron = Polyhedron(poly["G"], poly.get("b", ()))
    elif "vertices" in poly:
        polyhedron = Polyhedron.from_vertices(poly["vertices"], poly.get("rays", ()), poly.get("lines", ()))
    else:
        raise InvalidInput('problem.polyhedron: give "G" and "b", or "vertices" (with optional "rays", "lines")')
    method = parse_method(source["method"]) if source.get("method") is not None else None
    return Problem(system, polyhedron, method, name)


def _refuse_float(text: str):
    raise InvalidInput(f"problem: the JSON number {text} is a float; write it as a string (\"{text}\") to mean it exactly")
