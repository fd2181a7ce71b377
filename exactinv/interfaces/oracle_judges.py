"""The oracle's verdicts and its judges of thresholds, gamma*, roots and radii.

See :mod:`exactinv.interfaces.oracle` for the verdicts' meaning.  A float
claim is taken exactly (``exact_from_float``) and compared with the exact
value; an ``invalid`` threshold or gamma* comes with an exact counterexample.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from enum import StrEnum
from fractions import Fraction
from typing import Any

from ..core.algebraic import Real
from ..core.float_hint import float_hint
from ..core.real_algebraic import RealAlgebraic
from ..core.roots import first_sign_change
from ..core.scalars import INF, Infinity, exact_from_float, to_rational
from ..errors import InvalidInput
from ..invariance.gamma_star import optimal_gamma
from ..model import LinearSystem, Polyhedron
from ..model.methods import Method, forward_euler
from ..monotonicity.radius import absolute_monotonicity_radius
from ..validset.engine import discrete_invariance, largest_threshold, valid_steplengths

__all__ = ["Status", "Verdict", "judge_threshold", "judge_gamma", "judge_root", "judge_radius", "assert_threshold"]


class Status(StrEnum):
    """An oracle verdict (equal to the old strings: ``Status.TIGHT == "tight"``)."""

    VALID = "valid"
    TIGHT = "tight"
    INVALID = "invalid"


VALID, TIGHT, INVALID = Status.VALID, Status.TIGHT, Status.INVALID


@dataclass(frozen=True)
class Verdict:
    """The oracle's judgement of one float result."""

    status: Status
    quantity: str
    claimed: Fraction | Infinity
    exact: Real | None
    relative_gap: Fraction | None = None
    counterexample: dict | None = None
    message: str = ""

    def __bool__(self) -> bool:
        return self.status != INVALID

    def __str__(self) -> str:
        return f"{self.status.upper()}: {self.message}"


def exact_claim(claimed: Any, name: str = "claimed") -> Fraction | Infinity:
    """A claimed value as the exact number it denotes: a float (the one place floats are accepted: judging
    them is the point) exactly, +-inf as +-INF, anything else through the exact input conversion.

    >>> exact_claim(0.5), exact_claim("1/3"), exact_claim(1e999)  # 1e999: the float +inf
    (Fraction(1, 2), Fraction(1, 3), INF)
    """
    if isinstance(claimed, float):
        if math.isnan(claimed):
            raise InvalidInput(f"{name}: NaN is not a claim")
        if math.isinf(claimed):
            return INF if claimed > 0 else -INF
        return exact_from_float(claimed)
    if isinstance(claimed, Infinity):
        return claimed
    return to_rational(claimed, name)


def exact_gap(claimed, exact) -> Fraction | None:
    """(exact - claimed)/exact as an exact rational (bounds for algebraic exact values).

    >>> from fractions import Fraction
    >>> exact_gap(Fraction(1, 2), Fraction(1)), exact_gap(Fraction(1), Fraction(0))
    (Fraction(1, 2), None)
    """
    if isinstance(exact, Infinity) or isinstance(claimed, Infinity) or exact == 0:
        return None
    if isinstance(exact, RealAlgebraic):
        exact.refine_relative(80)  # relative: a tiny exact value keeps its sign and digits
        exact = exact.lower
    return (exact - claimed) / exact


def _within(claimed, exact, tolerance: Fraction) -> bool:
    """claimed (<= exact) is within a relative tolerance of exact."""
    if isinstance(exact, Infinity):
        return claimed == exact
    if isinstance(exact, RealAlgebraic):
        exact.refine_relative(80)  # relative: a tiny exact value keeps its sign and digits
        return claimed >= exact.lower - tolerance * abs(exact.upper)
    return abs(exact - claimed) <= tolerance * abs(exact)


def judge_threshold(system: LinearSystem, polyhedron: Polyhedron, method: Method, claimed: Any,
                    tolerance: Any = "1e-9") -> Verdict:
    """Judge a claimed steplength threshold: is every dt in [0, claimed] valid?
    Compared with the exact largest threshold (attained or not).

    >>> import exactinv as ei; S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    >>> judge_threshold(S, P, ei.methods.taylor(1), 1.0).status   # the largest forward-Euler step is 1
    <Status.TIGHT: 'tight'>
    >>> v = judge_threshold(S, P, ei.methods.taylor(1), 1.25)
    >>> v.status, v.counterexample['dt'] <= Fraction(5, 4)
    (<Status.INVALID: 'invalid'>, True)
    """
    tol = to_rational(tolerance, "tolerance")
    c = exact_claim(claimed)
    L = largest_threshold(system, polyhedron, method)
    tau = L.value
    too_big = (not isinstance(c, Infinity) and not isinstance(tau, Infinity)
               and (tau < c if isinstance(tau, RealAlgebraic) else c > tau)) \
        or (isinstance(c, Infinity) and not isinstance(tau, Infinity)) \
        or (not L.attained and c == tau)
    if c < 0 if not isinstance(c, Infinity) else c.sign < 0:
        raise InvalidInput(f"claimed: a steplength threshold cannot be negative, got {claimed}")
    if too_big and not L.attained and c == tau:
        return Verdict(INVALID, "threshold", c, tau, Fraction(0), {"dt": tau, "singular": True},
                       f"claimed {claimed} equals the exact largest threshold, which is not attained: "
                       f"r(dt A) is singular at dt = {tau}")
    if too_big:
        dt = _invalid_step(system, polyhedron, method, c)
        result = discrete_invariance(system, polyhedron, method, dt)
        w = result.witness
        if not hasattr(w, "facet"):  # an ellipsoid: a direction v whose boundary point is mapped outside E
            return Verdict(INVALID, "threshold", c, tau, exact_gap(c, tau), {"dt": dt, "v": w.v, "value": w.value},
                           f"claimed {claimed} exceeds the exact largest threshold {tau}"
                           f"{'' if L.attained else ' (not attained)'}: at dt = {dt} the boundary point along "
                           f"v = [{', '.join(map(str, w.v))}] is mapped outside E")
        return Verdict(INVALID, "threshold", c, tau, exact_gap(c, tau),
                       {"dt": dt, "x": w.x, "facet": w.facet, "value": w.value},
                       f"claimed {claimed} exceeds the exact largest threshold {tau}"
                       f"{'' if L.attained else ' (not attained)'}: at dt = {dt} the point [{', '.join(map(str, w.x))}] "
                       f"leaves P through facet {w.facet}")
    gap = exact_gap(c, tau)
    if _within(c, tau, tol):
        return Verdict(TIGHT, "threshold", c, tau, gap, None, f"claimed {claimed} is within {tol} of the exact {tau}")
    return Verdict(VALID, "threshold", c, tau, gap, None,
                   f"claimed {claimed} is safe; the exact largest threshold is {tau}"
                   + ("" if gap is None else f" (relative gap {float_hint(gap):.3g})"))


def _invalid_step(system, polyhedron, method, claimed) -> Fraction:
    """A rational dt <= claimed at which A_d(dt) P is not inside P (and r(dt A) is defined):
    bisect towards the end of the first valid interval inside the first gap."""
    V = valid_steplengths(system, polyhedron, method)
    end = V.intervals[0].hi
    lo = end.upper if isinstance(end, RealAlgebraic) else end
    top = lo + 1 if isinstance(claimed, Infinity) else claimed
    if len(V.intervals) > 1:
        nxt = V.intervals[1].lo
        nxt = nxt.lower if isinstance(nxt, RealAlgebraic) else nxt
        top = min(top, nxt)
    short = _simplest_between(lo, top)  # a short rational counterexample where one exists
    if short is not None and short not in V:
        try:
            if not discrete_invariance(system, polyhedron, method, short).holds:
                return short
        except InvalidInput:
            pass
    for k in range(1, 200):
        dt = lo + (top - lo) / 2**k
        if dt <= 0 or dt in V:
            continue
        try:
            if not discrete_invariance(system, polyhedron, method, dt).holds:
                return dt
        except InvalidInput:  # r(dt A) singular at this dt
            continue
    raise InvalidInput("no invalid rational step found below the claim")


def _simplest_between(a: Fraction, b: Fraction) -> Fraction | None:
    """The rational with the smallest denominator in the open interval (a, b), 0 <= a < b
    (Stern-Brocot descent by continued fractions); None if a >= b.

    >>> _simplest_between(Fraction(14142, 10000), Fraction(2))
    Fraction(3, 2)
    """
    if not a < b:
        return None
    fl = a.numerator // a.denominator
    if fl + 1 < b:
        return Fraction(fl + 1)
    if fl == a:  # a is an integer and b <= a + 1: fl + 1/q with the least q > 1/(b - fl)
        r = 1 / (b - fl)
        return fl + Fraction(1, r.numerator // r.denominator + 1)
    # fl < a < b <= fl + 1: recurse on the reciprocals of the fractional parts
    x = _simplest_between(1 / (b - fl), 1 / (a - fl))
    return None if x is None or x == 0 else fl + 1 / x


def judge_gamma(system: LinearSystem, polyhedron: Polyhedron, claimed: Any, tolerance: Any = "1e-9") -> Verdict:
    """Judge a claimed gamma*.  A claim below gamma* is invalid (its forward-Euler step
    1/claimed is too large: counterexample given); above it, it is safe but conservative.

    >>> import exactinv as ei; S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    >>> [judge_gamma(S, P, c).status for c in (1.0, 1.5, 0.75)]   # gamma* = 1
    [<Status.TIGHT: 'tight'>, <Status.VALID: 'valid'>, <Status.INVALID: 'invalid'>]
    """
    tol = to_rational(tolerance, "tolerance")
    c = exact_claim(claimed)
    g = optimal_gamma(system, polyhedron).value
    if isinstance(g, Infinity) or isinstance(c, Infinity):
        ok = c == g
        return Verdict(TIGHT if ok else INVALID, "gamma", c, g, None, None, f"claimed {claimed}, exact gamma* = {g}")
    if c < g:
        cex = None
        if c > 0:
            dt = 1 / c
            w = discrete_invariance(system, polyhedron, forward_euler(), dt).witness
            cex = {"dt": dt, "x": w.x, "facet": w.facet, "value": w.value} if w else None
        return Verdict(INVALID, "gamma", c, g, None, cex, f"claimed {claimed} is below the exact gamma* = {g}")
    status = TIGHT if abs(c - g) <= tol * max(abs(g), Fraction(1)) else VALID
    return Verdict(status, "gamma", c, g, c - g, None, f"claimed {claimed}; exact gamma* = {g}")


def judge_root(f: Any, claimed: Any, tolerance: Any = "1e-9") -> Verdict:
    """Judge a claimed first sign change of the polynomial f (coefficients, constant first).

    >>> [judge_root([2, -3, 1], c).status for c in (1.0, 0.5, 1.5)]   # (1 - t)(2 - t): first sign change at 1
    [<Status.TIGHT: 'tight'>, <Status.VALID: 'valid'>, <Status.INVALID: 'invalid'>]
    """
    tol = to_rational(tolerance, "tolerance")
    c = exact_claim(claimed)
    r = first_sign_change(f)
    if isinstance(r, Infinity) or isinstance(c, Infinity):
        ok = c == r
        return Verdict(TIGHT if ok else INVALID, "root", c, r, None, None, f"claimed {claimed}, exact first sign change {r}")
    if r < c if isinstance(r, RealAlgebraic) else c > r:
        return Verdict(INVALID, "root", c, r, exact_gap(c, r), None, f"claimed {claimed} lies beyond the first sign change {r}")
    status = TIGHT if _within(c, r, tol) else VALID
    return Verdict(status, "root", c, r, exact_gap(c, r), None, f"claimed {claimed}; exact first sign change {r}")


def judge_radius(method: Method, claimed: Any, tolerance: Any = "1e-9") -> Verdict:
    """Judge a claimed radius of absolute monotonicity.

    >>> from exactinv.model import methods
    >>> [judge_radius(methods.taylor(1), c).status for c in (1.0, 0.5, 2.0)]   # 1 + z: rho = 1
    [<Status.TIGHT: 'tight'>, <Status.VALID: 'valid'>, <Status.INVALID: 'invalid'>]
    """
    tol = to_rational(tolerance, "tolerance")
    c = exact_claim(claimed)
    rho = absolute_monotonicity_radius(method).value
    if isinstance(rho, Infinity) or isinstance(c, Infinity):
        ok = c == rho or (isinstance(rho, Infinity) and not isinstance(c, Infinity))
        status = TIGHT if c == rho else (VALID if ok else INVALID)
        return Verdict(status, "radius", c, rho, None, None, f"claimed {claimed}; exact rho = {rho}")
    if rho < c if isinstance(rho, RealAlgebraic) else c > rho:
        return Verdict(INVALID, "radius", c, rho, exact_gap(c, rho), None, f"claimed {claimed} exceeds the exact rho = {rho}")
    status = TIGHT if _within(c, rho, tol) else VALID
    return Verdict(status, "radius", c, rho, exact_gap(c, rho), None, f"claimed {claimed}; exact rho = {rho}")


def assert_threshold(system: LinearSystem, polyhedron: Polyhedron, method: Method, claimed: Any,
                     tolerance: Any = "1e-9", require_tight: bool = False) -> Verdict:
    """pytest helper: fail (AssertionError with the counterexample) unless the claim is valid
    (and, with ``require_tight``, within ``tolerance`` of the exact largest threshold).

    >>> import exactinv as ei; S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    >>> assert_threshold(S, P, ei.methods.taylor(1), 0.5).status
    <Status.VALID: 'valid'>
    >>> try:
    ...     assert_threshold(S, P, ei.methods.taylor(1), 1.5)
    ... except AssertionError as exc:
    ...     print(str(exc).split(':')[0])
    INVALID
    """
    v = judge_threshold(system, polyhedron, method, claimed, tolerance)
    if v.status == INVALID or (require_tight and v.status != TIGHT):
        raise AssertionError(str(v))
    return v
