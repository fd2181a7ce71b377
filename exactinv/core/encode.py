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

import flint

from exactinv_check.format import FORMAT, INFINITY, NEG_INFINITY, VERSION

from .algebraic import Real
from .flintq import exact_text
from .real_algebraic import RealAlgebraic
from .scalars import INF, Infinity  # noqa: F401 (INF: the doctest above)

__all__ = ["encode_real", "vec", "mat", "sparse_mat", "sparse_of_dense", "envelope", "dumps"]

# FORMAT and VERSION (the version the engine writes: 3, H and H~ sparse) are the kernel's (exactinv_check.format)

def encode_real(v: Real) -> str | dict:
    """Fraction -> "p/q" (any size); INF -> "oo"; RealAlgebraic -> {"poly", "interval"}.

    >>> encode_real(Fraction(-3, 4)), encode_real(INF)
    ('-3/4', 'oo')
    >>> encode_real(RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2))
    {'poly': ['-2', '0', '1'], 'interval': ['1414213562373/1000000000000', '707106781187/500000000000']}
    """
    if isinstance(v, Infinity):
        return INFINITY if v.sign > 0 else NEG_INFINITY
    if isinstance(v, RealAlgebraic):
        v.tidy()
        return {"poly": [exact_text(c) for c in v.poly.coeffs()], "interval": [exact_text(v.lower), exact_text(v.upper)]}
    if isinstance(v, (int, Fraction)):
        return exact_text(Fraction(v))
    raise TypeError(f"cannot encode {v!r}")


def vec(v: Iterable[Any]) -> list[str]:
    """A vector of exact values as strings.

    >>> vec([Fraction(1, 2), 3])
    ['1/2', '3']
    """
    return [exact_text(x) if isinstance(x, (int, Fraction, flint.fmpz, flint.fmpq)) else str(x) for x in v]


def mat(M: Iterable[Iterable[Any]]) -> list[list[str]]:
    """A matrix of exact values as strings.

    >>> mat([[Fraction(1, 2), 0], [0, Fraction(-1, 3)]])
    [['1/2', '0'], ['0', '-1/3']]
    """
    return [vec(r) for r in M]


def sparse_mat(rows: Iterable[Iterable[tuple[int, Any]]]) -> dict:
    """A square matrix given by its rows of (column, value) pairs, in the version 3 encoding:
    ``{"sparse": [[[k, "value"], ...], ...]}`` -- every row listed, the nonzero entries only, columns
    strictly increasing (docs/certificate-format.md).  Zeros given are dropped; columns are sorted.

    >>> sparse_mat([[(1, Fraction(1, 2)), (0, -1)], [], [(2, 0)]])
    {'sparse': [[[0, '-1'], [1, '1/2']], [], []]}
    """
    out = []
    for row in rows:
        entries = sorted((int(k), v) for k, v in row if v != 0)
        if any(a[0] == b[0] for a, b in zip(entries, entries[1:])):
            raise ValueError("sparse_mat: a column repeats in a row")
        out.append([[k, exact_text(v) if isinstance(v, (int, Fraction, flint.fmpz, flint.fmpq)) else str(v)]
                    for k, v in entries])
    return {"sparse": out}


def sparse_of_dense(M: Iterable[Iterable[Any]]) -> dict:
    """A dense matrix in the version 3 sparse encoding (its nonzero entries, by row).

    >>> sparse_of_dense([[Fraction(1, 2), 0], [0, 0]])
    {'sparse': [[[0, '1/2']], []]}
    """
    return sparse_mat([(k, v) for k, v in enumerate(row)] for row in M)


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
