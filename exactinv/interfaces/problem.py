"""Problem files: the JSON format read by ``exactinv certify`` (docs/problem-format.md,
docs/problem.schema.json).

    {"system": {"A": [["-1", "1"], ["-1", "-1"]]},          # or {"A0", "B", "F"}
     "polyhedron": {"G": [[1, 0], ...], "b": [1, ...]},     # or {"vertices", "rays", "lines"}
     "method": {"taylor": 4}}                               # optional

or, instead of "polyhedron", an ellipsoid {x : x^T Q x <= 1}:
    "ellipsoid": {"Q": [["2", "0"], ["0", "1"]]}

Rationals are strings ("3/4"; "0.1" means exactly 1/10) or integers; JSON
floats are refused like Python floats.  Unknown keys are refused at every
level, with a "did you mean" hint.  Errors name the file and the JSON path.
"""

from __future__ import annotations

import difflib
import json
import os
import re
from dataclasses import dataclass
from typing import Any, Iterable

from ..errors import InvalidInput
from ..model import methods as _methods
from ..model import Ellipsoid, LinearSystem, Polyhedron
from ..model.methods import Method

__all__ = ["Problem", "load_problem", "parse_method", "method_from_text", "METHOD_KINDS", "TOP_KEYS"]

TOP_KEYS = ("system", "polyhedron", "ellipsoid", "method", "name", "description")
"""The keys a problem file may hold (system and one of polyhedron, ellipsoid are required)."""

METHOD_KINDS = ("taylor", "polynomial", "rational", "theta", "pade", "butcher", "preset", "ssprk_s1")
"""The keys of a method object ({"taylor": 4}, ...); a bare string is a preset name."""


@dataclass(frozen=True)
class Problem:
    """A problem: ``polyhedron`` holds the invariant set, a Polyhedron or an Ellipsoid."""

    system: LinearSystem
    polyhedron: Polyhedron | Ellipsoid
    method: Method | None = None
    name: str = "problem"

    @property
    def is_ellipsoid(self) -> bool:
        return isinstance(self.polyhedron, Ellipsoid)


def did_you_mean(word: str, choices: Iterable[str]) -> str:
    """'; did you mean "x"?' for the closest choice, or '' (difflib).

    >>> did_you_mean("polyhedra", TOP_KEYS), did_you_mean("zzz", TOP_KEYS)
    ('; did you mean "polyhedron"?', '')
    """
    close = difflib.get_close_matches(str(word), list(choices), n=1, cutoff=0.6)
    return f'; did you mean "{close[0]}"?' if close else ""


def check_keys(obj: dict, allowed: Iterable[str], path: str) -> None:
    """Refuse a key of ``obj`` outside ``allowed``, naming its JSON path and the closest allowed key.

    >>> check_keys({"G": [[1]], "b": [1]}, ("G", "b"), "polyhedron")   # all allowed: no error
    >>> check_keys({"G": [[1]], "bb": [1]}, ("G", "b"), "polyhedron")
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: polyhedron.bb: unknown key; did you mean "b"? (allowed: G, b)
    """
    allowed = list(allowed)
    for key in obj:
        if key not in allowed:
            raise InvalidInput(f"{path + '.' if path else ''}{key}: unknown key{did_you_mean(key, allowed)} "
                               f"(allowed: {', '.join(allowed)})")


_LEAD = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)(?=[\[:])")


class _At:
    """Prefix the message of an InvalidInput raised inside the block with a JSON path:
    an argument name that is one of ``keys`` becomes ``path.key``; any other leading
    argument name (the value itself, e.g. ``p`` of taylor) is replaced by ``path``."""

    def __init__(self, path: str, keys: Iterable[str] = ()):
        self.path, self.keys = path, set(keys)

    def __enter__(self):
        return self

    def __exit__(self, kind, exc, tb):
        if isinstance(exc, InvalidInput):
            msg = str(exc)
            lead = _LEAD.match(msg)
            if lead and lead.group(1) in self.keys:
                msg = f"{self.path}.{msg}"
            elif lead:
                msg = self.path + msg[lead.end():]
            else:
                msg = f"{self.path}: {msg}"
            raise type(exc)(msg) from None
        return False


def _object(value: Any, path: str, what: str) -> dict:
    if not isinstance(value, dict):
        raise InvalidInput(f"{path}: expected {what}, got {_kind(value)}")
    return value


def _kind(value: Any) -> str:
    return {dict: "a JSON object", list: "a JSON list", str: "a string", bool: "a boolean", int: "an integer",
            type(None): "null"}.get(type(value), type(value).__name__)


def parse_method(spec: Any, path: str = "method") -> Method:
    """A method from its JSON form, e.g. {"taylor": 4}, {"preset": "rk4"} or the preset name "rk4".

    Taylor(2) is r(z) = 1 + z + z^2/2; backward Euler, r(z) = 1/(1 - z), as a rational method:

    >>> parse_method({"taylor": 2}).numerator
    (Fraction(1, 1), Fraction(1, 1), Fraction(1, 2))
    >>> m = parse_method({"rational": {"num": [1], "den": [1, -1]}}); m.numerator, m.denominator
    ((Fraction(1, 1),), (Fraction(1, 1), Fraction(-1, 1)))
    >>> parse_method({"tailor": 2})
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: method.tailor: unknown kind of method; did you mean "taylor"? (known: ...)
    """
    if isinstance(spec, str):
        return _preset(spec, path)
    if not isinstance(spec, dict) or len(spec) != 1:
        got = f"keys {sorted(spec)}" if isinstance(spec, dict) else _kind(spec)
        raise InvalidInput(f"{path}: expected one key such as {{\"taylor\": 4}} or a preset name, got {got}")
    (kind, arg), = spec.items()
    where = f"{path}.{kind}"
    if kind not in METHOD_KINDS:
        raise InvalidInput(f"{where}: unknown kind of method{did_you_mean(kind, METHOD_KINDS)} "
                           f"(known: {', '.join(METHOD_KINDS)})")
    if kind == "preset":
        if not isinstance(arg, str):
            raise InvalidInput(f"{where}: expected a preset name (a string), got {_kind(arg)}")
        return _preset(arg, where)
    with _At(where):
        if kind == "taylor":
            return _methods.taylor(arg)
        if kind == "polynomial":
            return _methods.polynomial(arg)
        if kind == "theta":
            return _methods.theta(arg)
        if kind == "ssprk_s1":
            return _methods.ssprk_s1(arg)
    with _At(where, ("k", "l")):
        if kind == "pade":
            if not isinstance(arg, list) or len(arg) != 2:
                raise InvalidInput("expected [k, l] (numerator and denominator degrees)")
            return _methods.pade(*arg)
    if kind == "rational":
        _object(arg, where, '{"num": [...], "den": [...]}')
        check_keys(arg, ("num", "den"), where)
        _require(arg, ("num", "den"), where)
        with _At(where, ("num", "den")):
            return _methods.rational(arg["num"], arg["den"])
    _object(arg, where, '{"A": [[...]], "b": [...]} (and optionally "c": [...])')
    check_keys(arg, ("A", "b", "c"), where)
    _require(arg, ("A", "b"), where)
    with _At(where, ("A", "b", "c")):
        return _methods.from_butcher(arg["A"], arg["b"], c=arg.get("c"))


def _preset(name: str, where: str) -> Method:
    if name not in _methods.PRESETS:
        raise InvalidInput(f"{where}: unknown preset {name!r}{did_you_mean(name, _methods.PRESETS)} "
                           f"(known: {', '.join(sorted(_methods.PRESETS))})")
    return _methods.preset(name)


def method_from_text(text: str, where: str = "--method") -> Method:
    """A method from command-line text: JSON (``{"taylor": 4}``) or a preset name (``rk4``).

    Pade(1,1) is the trapezoid rule, r(z) = (1 + z/2)/(1 - z/2); rk4 is Taylor(4).

    >>> m = method_from_text('{"pade": [1, 1]}'); m.numerator, m.denominator
    ((Fraction(1, 1), Fraction(1, 2)), (Fraction(1, 1), Fraction(-1, 2)))
    >>> method_from_text("rk4").numerator == parse_method({"taylor": 4}).numerator
    True
    >>> method_from_text('{"theta": 0.5}')
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: --method: the JSON number 0.5 is a float; write it as a string ("0.5") to mean it exactly
    """
    text = text.strip()
    if text[:1] in "{[\"":
        try:
            spec = json.loads(text, parse_float=_refuse_float(where), parse_constant=_refuse_constant(where))
        except json.JSONDecodeError as exc:
            raise InvalidInput(f"{where}: not valid JSON ({exc}); give e.g. '{{\"taylor\": 4}}' or a preset name such as rk4") from None
        return parse_method(spec, where)
    return _preset(text, where)


def _require(obj: dict, keys: Iterable[str], path: str) -> None:
    for key in keys:
        if key not in obj:
            raise InvalidInput(f"{path}: missing key {key!r}")


def _section(data: dict, key: str) -> dict:
    if key not in data:
        raise InvalidInput(f"{key}: missing section (a problem file needs \"system\" and \"polyhedron\" or \"ellipsoid\")")
    return _object(data[key], key, "a JSON object")


def _system(data: dict) -> LinearSystem:
    sys_data = _section(data, "system")
    check_keys(sys_data, ("A", "A0", "B", "F"), "system")
    if "A" in sys_data:
        if set(sys_data) != {"A"}:
            raise InvalidInput('system: give "A", or "A0", "B" and "F" -- not both')
        with _At("system", ("A", "A0", "B", "F")):
            return LinearSystem(sys_data["A"])
    if {"A0", "B", "F"} <= set(sys_data):
        with _At("system", ("A", "A0", "B", "F")):
            return LinearSystem.closed_loop(sys_data["A0"], sys_data["B"], sys_data["F"])
    missing = sorted({"A0", "B", "F"} - set(sys_data))
    raise InvalidInput(f'system: give "A", or "A0", "B" and "F" (missing {", ".join(missing)})')


def _polyhedron(data: dict) -> Polyhedron:
    poly = _section(data, "polyhedron")
    check_keys(poly, ("G", "b", "vertices", "rays", "lines"), "polyhedron")
    h_keys, v_keys = {"G", "b"} & set(poly), {"vertices", "rays", "lines"} & set(poly)
    if h_keys and v_keys:
        raise InvalidInput('polyhedron: give "G" and "b", or "vertices" (with optional "rays", "lines") -- not both')
    if h_keys:
        _require(poly, ("G", "b"), "polyhedron")
        with _At("polyhedron", ("G", "b", "vertices", "rays", "lines")):
            return Polyhedron(poly["G"], poly["b"])
    if "vertices" in poly:
        with _At("polyhedron", ("G", "b", "vertices", "rays", "lines")):
            return Polyhedron.from_vertices(poly["vertices"], poly.get("rays", ()), poly.get("lines", ()))
    raise InvalidInput('polyhedron: give "G" and "b", or "vertices" (with optional "rays", "lines")')


def _ellipsoid(data: dict) -> Ellipsoid:
    ell = _object(data["ellipsoid"], "ellipsoid", "a JSON object")
    check_keys(ell, ("Q",), "ellipsoid")
    _require(ell, ("Q",), "ellipsoid")
    with _At("ellipsoid", ("Q",)):
        return Ellipsoid(ell["Q"])


def _invariant_set(data: dict) -> Polyhedron | Ellipsoid:
    if "ellipsoid" in data:
        if "polyhedron" in data:
            raise InvalidInput('ellipsoid: give "polyhedron" or "ellipsoid" -- not both')
        return _ellipsoid(data)
    return _polyhedron(data)


def problem_from_dict(data: Any, name: str = "problem") -> Problem:
    """A :class:`Problem` from the parsed JSON of a problem file (every key checked).

    >>> problem_from_dict({"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, "1/2"]},
    ...                    "method": {"taylor": 2}}, "box")
    Problem(system=LinearSystem(A=[[-1]]), polyhedron=Polyhedron(G=[[1], [-1]], b=[1, 1/2]), method=Method(taylor(2): r(z) = z**2/2 + z + 1), name='box')
    >>> problem_from_dict({"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}, "methd": "rk4"})
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: methd: unknown key; did you mean "method"? (allowed: ...)
    """
    if not isinstance(data, dict):
        raise InvalidInput(f"expected a JSON object with \"system\" and \"polyhedron\", got {_kind(data)}")
    if {"format", "claims"} & set(data):
        raise InvalidInput("this is a certificate, not a problem file (use `exactinv check` or `exactinv explain`)")
    check_keys(data, TOP_KEYS, "")
    if "name" in data:
        if not isinstance(data["name"], str):
            raise InvalidInput(f"name: expected a string, got {_kind(data['name'])}")
        name = data["name"]
    if "description" in data and not isinstance(data["description"], str):
        raise InvalidInput(f"description: expected a string, got {_kind(data['description'])}")
    system = _system(data)
    polyhedron = _invariant_set(data)
    if system.n != polyhedron.n:
        what = "ellipsoid" if isinstance(polyhedron, Ellipsoid) else "polyhedron"
        raise InvalidInput(f"{what}: the system has dimension {system.n} but the {what} lives in dimension {polyhedron.n}")
    method = parse_method(data["method"]) if data.get("method") is not None else None
    return Problem(system, polyhedron, method, name)


def load_problem(source: Any) -> Problem:
    """Read a problem from a dict, a JSON string or a path to a JSON file.
    Errors from a file are prefixed with its path.

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
        return problem_from_dict(source)
    if isinstance(source, str) and source.lstrip().startswith("{"):
        return problem_from_dict(_parse(source, "problem"))
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
        return problem_from_dict(_parse(text, path), name)
    except InvalidInput as exc:
        if str(exc).startswith(path):
            raise
        raise type(exc)(f"{path}: {exc}") from None


def _parse(text: str, where: str) -> Any:
    try:
        return json.loads(text, parse_float=_refuse_float(), parse_constant=_refuse_constant(),
                          object_pairs_hook=_no_duplicates)
    except json.JSONDecodeError as exc:
        raise InvalidInput(f"{where}: not valid JSON ({exc})") from None
    except RecursionError:
        raise InvalidInput(f"{where}: nested too deeply") from None


def _no_duplicates(pairs):
    keys = [k for k, _ in pairs]
    dup = sorted({k for k in keys if keys.count(k) > 1})
    if dup:
        raise InvalidInput(f"duplicate key {dup[0]!r} in one JSON object (ambiguous)")
    return dict(pairs)


def _refuse_float(where: str = ""):
    prefix = f"{where}: " if where else ""

    def refuse(text: str):
        raise InvalidInput(f"{prefix}the JSON number {text} is a float; write it as a string (\"{text}\") to mean it exactly")
    return refuse


def _refuse_constant(where: str = ""):
    prefix = f"{where}: " if where else ""

    def refuse(text: str):
        raise InvalidInput(f"{prefix}{text} is not a number exactinv accepts")
    return refuse
