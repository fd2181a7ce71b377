"""Strict JSON input (problem files and ``--method``): exact numbers only (a JSON
float or NaN/Infinity is refused), no duplicate key, unknown keys refused with a
"did you mean" hint, and every error names its JSON path.
"""

from __future__ import annotations

import difflib
import json
import re
from typing import Any, Callable, Iterable, NoReturn

from ..errors import InvalidInput

__all__ = ["did_you_mean", "check_keys", "JsonPath", "expect_object", "json_kind", "require_keys", "parse_strict_json",
           "float_refuser", "constant_refuser"]


def did_you_mean(word: str, choices: Iterable[str]) -> str:
    """'; did you mean "x"?' for the closest choice, or '' (difflib).

    >>> from exactinv.interfaces.problem import TOP_KEYS
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


class JsonPath:
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


def expect_object(value: Any, path: str, what: str) -> dict:
    """``value`` itself if it is a JSON object, else InvalidInput naming ``path`` and what was expected.

    >>> expect_object({"A": []}, "problem", "an object")
    {'A': []}
    >>> expect_object([1], "problem.A", "an object")
    Traceback (most recent call last):
    exactinv.errors.InvalidInput: problem.A: expected an object, got a JSON list
    """
    if not isinstance(value, dict):
        raise InvalidInput(f"{path}: expected {what}, got {json_kind(value)}")
    return value


def json_kind(value: Any) -> str:
    """What a parsed JSON value is, in words for a message ("a JSON list", "a string", ...).

    >>> json_kind([1]), json_kind(None), json_kind("x")
    ('a JSON list', 'null', 'a string')
    """
    return {dict: "a JSON object", list: "a JSON list", str: "a string", bool: "a boolean", int: "an integer",
            type(None): "null"}.get(type(value), type(value).__name__)


def require_keys(obj: dict, keys: Iterable[str], path: str) -> None:
    """InvalidInput naming the first of ``keys`` missing from the object at ``path``.

    >>> require_keys({"A": 1}, ["A", "G"], "problem")
    Traceback (most recent call last):
    exactinv.errors.InvalidInput: problem: missing key 'G'
    """
    for key in keys:
        if key not in obj:
            raise InvalidInput(f"{path}: missing key {key!r}")


def parse_strict_json(text: str, where: str) -> Any:
    """JSON text parsed strictly: a float, NaN or Infinity, or a duplicate key is InvalidInput (at ``where``).

    >>> parse_strict_json('{"b": ["1/2"]}', "p.json")
    {'b': ['1/2']}
    >>> parse_strict_json('{"b": NaN}', "p.json")
    Traceback (most recent call last):
    exactinv.errors.InvalidInput: NaN is not a number exactinv accepts
    """
    try:
        return json.loads(text, parse_float=float_refuser(), parse_constant=constant_refuser(),
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


def float_refuser(where: str = "") -> Callable[[str], NoReturn]:
    """A ``json.loads(parse_float=...)`` hook refusing every float (numbers are exact strings).

    >>> import json
    >>> json.loads("[1.5]", parse_float=float_refuser("p.json"))
    Traceback (most recent call last):
    exactinv.errors.InvalidInput: p.json: the JSON number 1.5 is a float; write it as a string ("1.5") to mean it exactly
    """
    prefix = f"{where}: " if where else ""

    def refuse(text: str) -> NoReturn:
        raise InvalidInput(f"{prefix}the JSON number {text} is a float; write it as a string (\"{text}\") to mean it exactly")
    return refuse


def constant_refuser(where: str = "") -> Callable[[str], NoReturn]:
    """A ``json.loads(parse_constant=...)`` hook refusing NaN and +-Infinity.

    >>> import json
    >>> json.loads("[NaN]", parse_constant=constant_refuser("p.json"))
    Traceback (most recent call last):
    exactinv.errors.InvalidInput: p.json: NaN is not a number exactinv accepts
    """
    prefix = f"{where}: " if where else ""

    def refuse(text: str) -> NoReturn:
        raise InvalidInput(f"{prefix}{text} is not a number exactinv accepts")
    return refuse
