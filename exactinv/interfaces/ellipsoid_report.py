"""The stages of :func:`exactinv.interfaces.pipeline.certify` on an ellipsoid
E = {x : x^T Q x <= 1}: invariance, the largest forward-Euler step and, with a
method, the exact valid set and largest threshold -- results and report lines."""

from __future__ import annotations

from typing import Any, Callable

from ..core.text import exact_text, safe_step_text
from ..invariance.ellipsoids import ellipsoid_continuous_invariance
from ..model import Ellipsoid, LinearSystem, Method
from ..validset.engine import forward_euler_threshold, largest_threshold, valid_steplengths

__all__ = ["ellipsoid_results"]


def ellipsoid_results(S: LinearSystem, E: Ellipsoid, method: Method | None, lines: list[str],
                      step: Callable[[str], None]) -> list[Any]:
    """The results on E, in certificate order; appends the report lines.

    >>> import exactinv as ei
    >>> lines = []
    >>> _ = ellipsoid_results(ei.LinearSystem([[-1, -2], [2, -1]]), ei.Ellipsoid([[1, 0], [0, 1]]), None,
    ...                       lines, lambda s: None)
    >>> lines[-1]     # the double 0.4 is above 2/5: the safe float is the one below
    'largest forward-Euler step on E: 2/5; use dt <= 0.39999999999999996  (generalised eigenvalue and valid set agree)'
    """
    step("continuous invariance (exact LDL^T)")
    inv = ellipsoid_continuous_invariance(S, E)
    if inv.holds:
        lines.append("continuous invariance: holds (-(A^T Q + Q A) = L D L^T with D >= 0, exact)")
    else:
        w = inv.witness
        lines.append(f"continuous invariance: FAILS -- v = [{', '.join(map(str, w.v))}] has "
                     f"v^T (A^T Q + Q A) v = {w.value} > 0: the boundary point v/||v||_Q leaves E")
    step("forward Euler (generalised eigenvalue)")
    fe = forward_euler_threshold(S, E)
    lines.append(f"largest forward-Euler step on E: {exact_text(fe.value)}{safe_step_text(fe)}  "
                 "(generalised eigenvalue and valid set agree)")
    results: list[Any] = [inv, fe]
    if method is not None:
        step("exact valid steplengths")
        V = valid_steplengths(S, E, method)
        step("exact largest threshold")
        L = largest_threshold(S, E, method)
        lines.append(f"exact valid steplengths for {method.name}: {V.intervals!r}")
        lines.append(f"exact largest threshold: {exact_text(L.value)}" + ("" if L.attained else "  (not attained)")
                     + safe_step_text(L))
        results += [L, V]
    return results
