"""Certificates: every result as a versioned JSON document of exact strings.

A certificate holds the problem (A, G, b and the method's r = g/h) and a list
of *claims*, each carrying every object a skeptic needs to re-verify it with
:mod:`exactinv.check` -- which shares no code with this module.  Each result
type owns its claims (``result.claims()``); this module is the envelope that
joins them.  The format is documented in docs/certificate-format.md.
"""

from __future__ import annotations

from typing import Any

from exactinv_check.format import FORMAT, VERSION

from .core.encode import dumps, encode_real, envelope
from .model.record import certificate, method_record, problem_record

__all__ = ["FORMAT", "VERSION", "encode_real", "problem_record", "method_record", "certificate", "claims_of",
           "envelope", "dumps"]


def claims_of(result: Any) -> list[dict]:
    """The claims a result makes, in the order the checker needs them (its own ``claims()``).

    >>> import exactinv as ei
    >>> S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
    >>> [str(c['type']) for c in claims_of(ei.forward_euler_threshold(S, P))]
    ['gamma_star', 'forward_euler_threshold']
    """
    claims = getattr(result, "claims", None)
    if claims is None:
        raise TypeError(f"no certificate for {type(result).__name__}")
    return claims()
