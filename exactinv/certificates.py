"""Certificates: every result as a versioned JSON document of exact strings.

A certificate holds the problem (A, G, b and the method's r = g/h) and a list
of *claims*, each carrying every object a skeptic needs to re-verify it with
:mod:`exactinv.check` -- which shares no code with this module.  The format
is documented in docs/certificate-format.md.
"""

from __future__ import annotations

import json
from fractions import Fraction
from typing import Any

from .algebraic import RealAlgebraic
from .numbers import Infinity

__all__ = ["encode_real", "problem_record", "certificate", "claims_of", "dumps"]

FORMAT = "exactinv-certificate"
VERSION = 2  # v2 = v1 + optional data (e.g. dt on discrete claims); the kernel checks both


def encode_real(v: Any) -> Any:
    """Fraction -> "p/q"; INF -> "oo"; RealAlgebraic -> {"poly", "interval"}."""
    if isinstance(v, Infinity):
        return "oo" if v.sign > 0 else "-oo"
    if isinstance(v, RealAlgebraic):
        v.tidy()
        return {"poly": [str(int(c)) for c in v.poly.coeffs()], "interval": [str(v.lower), str(v.upper)]}
    if isinstance(v, (int, Fraction)):
        return str(Fraction(v))
    raise TypeError(f"cannot encode {v!r}")


def _vec(v) -> list[str]:
    return [str(x) for x in v]


def _mat(M) -> list[list[str]]:
    return [_vec(r) for r in M]


def problem_record(system, polyhedron, method=None) -> dict:
    record = {"A": _mat(system.A), "G": _mat(polyhedron.G), "b": _vec(polyhedron.b)}
    if method is not None:
        record["method"] = {"name": method.name, "numerator": _vec(method.numerator), "denominator": _vec(method.denominator)}
    return record


def _witness(w) -> dict:
    return {"x": _vec(w.x), "facet": w.facet, "value": str(w.value)}


def _gamma_claim(g) -> dict:
    claim = {"type": "gamma_star", "value": encode_real(g.value), "paths": g.paths}
    if g.witness is not None:
        claim["witness"] = _witness(g.witness)
    elif isinstance(g.value, Infinity):  # -oo: a point and a ray per row
        claim["rows"] = [{"h": _vec(r.h), "ray": _vec(r.ray)} for r in g.rows]
        claim["H"] = _mat(g.H)
    else:
        y, lam = g.dual
        m = g.H_flint.nrows()
        H = g.H_flint.entries()
        claim.update(H=[[str(v) for v in H[i * m:(i + 1) * m]] for i in range(m)], binding_row=g.binding_row,
                     dual={"y": _vec(y), "lambda": str(lam)})
    return claim


def claims_of(result: Any) -> list[dict]:
    """The claims a result makes, in the order the checker needs them."""
    from .invariance import ContinuousInvariance, DiscreteInvariance, OptimalGamma
    from .thresholds import SteplengthThreshold

    if isinstance(result, OptimalGamma):
        return [_gamma_claim(result)]
    if isinstance(result, ContinuousInvariance):
        claim = {"type": "continuous_invariance", "holds": result.holds}
        if result.holds:
            claim["H"] = _mat(result.certificate)
        else:
            claim["witness"] = _witness(result.witness)
        return [claim]
    if isinstance(result, DiscreteInvariance):
        claim = {"type": "discrete_invariance", "holds": result.holds, "Ad": _mat(result.Ad)}
        if result.holds:
            claim["H"] = _mat(result.certificate)
        else:
            claim["witness"] = _witness(result.witness)
        return [claim]
    if isinstance(result, SteplengthThreshold):
        return [_gamma_claim(result.gamma)] + result._claims()
    extra = getattr(result, "_claims", None)
    if extra is not None:
        return extra()
    raise TypeError(f"no certificate for {type(result).__name__}")


def certificate(system, polyhedron, method=None, results=()) -> dict:
    """One certificate for a problem and the results computed on it."""
    claims: list[dict] = []
    for r in results:
        for c in claims_of(r):
            if c not in claims:
                claims.append(c)
    return {
        "format": FORMAT,
        "version": VERSION,
        "problem": problem_record(system, polyhedron, method),
        "claims": claims,
    }


def dumps(cert: dict) -> str:
    return json.dumps(cert, indent=1)
