"""Exact values -> JSON strings, and the one certificate envelope.

>>> encode_real(Fraction(-3, 4)), encode_real(INF)
('-3/4', 'oo')
>>> envelope({"A": [["0"]]}, [])["format"]
'exactinv-certificate'
"""

from __future__ import annotations

import json
from fractions import Fraction
from typing import Any, Iterable

from .algebraic import Real, RealAlgebraic
from .scalars import INF, Infinity  # noqa: F401 (INF: the doctest above)

__all__ = ["FORMAT", "VERSION", "encode_real", "vec", "mat", "envelope", "dumps"]

FORMAT = "exactinv-certificate"
VERSION = 2  # v2 = v1 + optional data (e.g. dt on discrete claims); the kernel checks both

def encode_real(v: Real) -> str | dict:
    """Fraction -> "p/q"; INF -> "oo"; RealAlgebraic -> {"poly", "interval"}.

    >>> encode_real(Fraction(-3, 4)), encode_real(INF)
    ('-3/4', 'oo')
    >>> encode_real(RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2))
    {'poly': ['-2', '0', '1'], 'interval': ['1414213562373/1000000000000', '707106781187/500000000000']}
    """
    if isinstance(v, Infinity):
        return "oo" if v.sign > 0 else "-oo"
    if isinstance(v, RealAlgebraic):
        v.tidy()
        return {"poly": [str(int(c)) for c in v.poly.coeffs()], "interval": [str(v.lower), str(v.upper)]}
    if isinstance(v, (int, Fraction)):
        return str(Fraction(v))
    raise TypeError(f"cannot encode {v!r}")


def vec(v: Iterable[Any]) -> list[str]:
    """A vector of exact values as strings.

    >>> vec([Fraction(1, 2), 3])
    ['1/2', '3']
    """
    return [str(x) for x in v]


def mat(M: Iterable[Iterable[Any]]) -> list[list[str]]:
    """A matrix of exact values as strings.

    >>> mat([[Fraction(1, 2), 0], [0, Fraction(-1, 3)]])
    [['1/2', '0'], ['0', '-1/3']]
    """
    return [vec(r) for r in M]


def envelope(problem: dict, results: Iterable[Any] = ()) -> dict:
    """The certificate: the problem record and the claims of ``results`` (each
    result's ``claims()``), without repeats, in the order the checker needs.

    >>> class R:
    ...     def claims(self): return [{'type': 'gamma_star', 'value': '1'}]
    >>> cert = envelope({'A': [['-1']]}, [R(), R()])   # a repeated claim is kept once
    >>> cert['claims'], cert['problem']
    ([{'type': 'gamma_star', 'value': '1'}], {'A': [['-1']]})
    """
    claims: list[dict] = []
    for r in results:
        for c in r.claims():
            if c not in claims:
                claims.append(c)
    return {"format": FORMAT, "version": VERSION, "problem": problem, "claims": claims}


def dumps(cert: dict) -> str:
    """The certificate as indented JSON text.

    >>> print(dumps({'format': 'x', 'claims': []}))
    {
     "format": "x",
     "claims": []
    }
    """
    return json.dumps(cert, indent=1)
