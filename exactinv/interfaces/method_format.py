"""Methods in JSON: the ``method`` object of a problem file (docs/problem-format.md,
"Methods"), e.g. {"taylor": 4}, {"pade": [2, 2]}, {"rational": {"num": [...], "den": [...]}},
a Butcher tableau or a preset name, and the ``--method`` text of the command line.
"""

from __future__ import annotations

import json
from typing import Any

from ..errors import InvalidInput
from ..model import methods as _methods
from ..model.methods import Method
from .strict_json import (
    JsonPath,
    check_keys,
    constant_refuser,
    did_you_mean,
    expect_object,
    float_refuser,
    json_kind,
    require_keys,
)

__all__ = ["parse_method", "method_from_text", "METHOD_KINDS"]

METHOD_KINDS = ("taylor", "polynomial", "rational", "theta", "pade", "butcher", "preset", "ssprk_s1")
"""The keys of a method object ({"taylor": 4}, ...); a bare string is a preset name."""


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
        got = f"keys {sorted(spec)}" if isinstance(spec, dict) else json_kind(spec)
        raise InvalidInput(f"{path}: expected one key such as {{\"taylor\": 4}} or a preset name, got {got}")
    (kind, arg), = spec.items()
    where = f"{path}.{kind}"
    if kind not in METHOD_KINDS:
        raise InvalidInput(f"{where}: unknown kind of method{did_you_mean(kind, METHOD_KINDS)} "
                           f"(known: {', '.join(METHOD_KINDS)})")
    if kind == "preset":
        if not isinstance(arg, str):
            raise InvalidInput(f"{where}: expected a preset name (a string), got {json_kind(arg)}")
        return _preset(arg, where)
    with JsonPath(where):
        if kind == "taylor":
            return _methods.taylor(arg)
        if kind == "polynomial":
            return _methods.polynomial(arg)
        if kind == "theta":
            return _methods.theta(arg)
        if kind == "ssprk_s1":
            return _methods.ssprk_s1(arg)
    with JsonPath(where, ("k", "l")):
        if kind == "pade":
            if not isinstance(arg, list) or len(arg) != 2:
                raise InvalidInput("expected [k, l] (numerator and denominator degrees)")
            return _methods.pade(*arg)
    if kind == "rational":
        expect_object(arg, where, '{"num": [...], "den": [...]}')
        check_keys(arg, ("num", "den"), where)
        require_keys(arg, ("num", "den"), where)
        with JsonPath(where, ("num", "den")):
            return _methods.rational(arg["num"], arg["den"])
    expect_object(arg, where, '{"A": [[...]], "b": [...]} (and optionally "c": [...])')
    check_keys(arg, ("A", "b", "c"), where)
    require_keys(arg, ("A", "b"), where)
    with JsonPath(where, ("A", "b", "c")):
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
            spec = json.loads(text, parse_float=float_refuser(where), parse_constant=constant_refuser(where))
        except json.JSONDecodeError as exc:
            raise InvalidInput(f"{where}: not valid JSON ({exc}); "
                               f"give e.g. '{{\"taylor\": 4}}' or a preset name such as rk4") from None
        return parse_method(spec, where)
    return _preset(text, where)
