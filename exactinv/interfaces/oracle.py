"""A regression oracle for floating-point implementations.

A float implementation of the paper (or of anything computing the same
quantities) outputs a number; the oracle turns that float into the exact
rational it denotes (``exact_from_float``: this is the one place where a float
is accepted, because judging it is the point) and compares it with the exact
result:

* ``valid``   -- on the safe side of the exact value; ``relative_gap`` says by how much;
* ``tight``   -- on the safe side and within ``tolerance`` (relative) of it;
* ``invalid`` -- on the wrong side; for thresholds and gamma* the verdict carries
  an exact counterexample: a rational steplength dt <= claimed and a point x of P
  whose image A_d(dt) x leaves P through ``facet``.

For pytest: ``assert_threshold(system, polyhedron, method, claimed)``.
"""

from __future__ import annotations

import csv
import json
import math
import os
from dataclasses import dataclass
from enum import StrEnum
from fractions import Fraction
from typing import Any

from ..beyond.largest import largest_threshold, valid_steplengths
from ..core.algebraic import RealAlgebraic
from ..core.roots import first_sign_change
from ..core.scalars import INF, Infinity, exact_from_float, to_rational
from ..errors import ExactinvException, InvalidInput
from ..model.methods import Method, forward_euler
from ..paper.invariance import discrete_invariance, optimal_gamma
from ..paper.monotonicity import absolute_monotonicity_radius
from .problem import did_you_mean, load_problem, method_from_text, parse_method

__all__ = ["Status", "Verdict", "BatchRow", "judge_threshold", "judge_gamma", "judge_root", "judge_radius", "assert_threshold",
           "judge_batch"]

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
    exact: Any
    relative_gap: Fraction | None = None
    counterexample: dict | None = None
    message: str = ""

    def __bool__(self) -> bool:
        return self.status != INVALID

    def __str__(self) -> str:
        return f"{self.status.upper()}: {self.message}"


def _exact_claim(claimed: Any, name: str = "claimed") -> Fraction | Infinity:
    if isinstance(claimed, float):
        if math.isnan(claimed):
            raise InvalidInput(f"{name}: NaN is not a claim")
        if math.isinf(claimed):
            return INF if claimed > 0 else -INF
        return exact_from_float(claimed)
    if isinstance(claimed, Infinity):
        return claimed
    return to_rational(claimed, name)


def _gap(claimed, exact) -> Fraction | None:
    """(exact - claimed)/exact as an exact rational (bounds for algebraic exact values)."""
    if isinstance(exact, Infinity) or isinstance(claimed, Infinity) or exact == 0:
        return None
    if isinstance(exact, RealAlgebraic):
        exact.refine(80)
        exact = exact.lower
    return (exact - claimed) / exact


def _within(claimed, exact, tolerance: Fraction) -> bool:
    """claimed (<= exact) is within a relative tolerance of exact."""
    if isinstance(exact, Infinity):
        return claimed == exact
    if isinstance(exact, RealAlgebraic):
        exact.refine(80)
        return claimed >= exact.lower - tolerance * abs(exact.upper)
    return abs(exact - claimed) <= tolerance * abs(exact)


def judge_threshold(system, polyhedron, method: Method, claimed: Any, tolerance: Any = "1e-9") -> Verdict:
    """Judge a claimed steplength threshold: is every dt in [0, claimed] valid?
    Compared with the exact largest threshold (attained or not)."""
    tol = to_rational(tolerance, "tolerance")
    c = _exact_claim(claimed)
    L = largest_threshold(system, polyhedron, method)
    tau = L.value
    too_big = (not isinstance(c, Infinity) and not isinstance(tau, Infinity) and (tau < c if isinstance(tau, RealAlgebraic) else c > tau)) \
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
        return Verdict(INVALID, "threshold", c, tau, _gap(c, tau),
                       {"dt": dt, "x": w.x, "facet": w.facet, "value": w.value},
                       f"claimed {claimed} exceeds the exact largest threshold {tau}"
                       f"{'' if L.attained else ' (not attained)'}: at dt = {dt} the point [{', '.join(map(str, w.x))}] "
                       f"leaves P through facet {w.facet}")
    gap = _gap(c, tau)
    if _within(c, tau, tol):
        return Verdict(TIGHT, "threshold", c, tau, gap, None, f"claimed {claimed} is within {tol} of the exact {tau}")
    return Verdict(VALID, "threshold", c, tau, gap, None,
                   f"claimed {claimed} is safe; the exact largest threshold is {tau}"
                   + ("" if gap is None else f" (relative gap {float(gap):.3g})"))


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


def judge_gamma(system, polyhedron, claimed: Any, tolerance: Any = "1e-9") -> Verdict:
    """Judge a claimed gamma*.  A claim below gamma* is invalid (its forward-Euler step
    1/claimed is too large: counterexample given); above it, it is safe but conservative."""
    tol = to_rational(tolerance, "tolerance")
    c = _exact_claim(claimed)
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
    """Judge a claimed first sign change of the polynomial f (coefficients, constant first)."""
    tol = to_rational(tolerance, "tolerance")
    c = _exact_claim(claimed)
    r = first_sign_change(f)
    if isinstance(r, Infinity) or isinstance(c, Infinity):
        ok = c == r
        return Verdict(TIGHT if ok else INVALID, "root", c, r, None, None, f"claimed {claimed}, exact first sign change {r}")
    if r < c if isinstance(r, RealAlgebraic) else c > r:
        return Verdict(INVALID, "root", c, r, _gap(c, r), None, f"claimed {claimed} lies beyond the first sign change {r}")
    status = TIGHT if _within(c, r, tol) else VALID
    return Verdict(status, "root", c, r, _gap(c, r), None, f"claimed {claimed}; exact first sign change {r}")


def judge_radius(method: Method, claimed: Any, tolerance: Any = "1e-9") -> Verdict:
    """Judge a claimed radius of absolute monotonicity."""
    tol = to_rational(tolerance, "tolerance")
    c = _exact_claim(claimed)
    rho = absolute_monotonicity_radius(method).value
    if isinstance(rho, Infinity) or isinstance(c, Infinity):
        ok = c == rho or (isinstance(rho, Infinity) and not isinstance(c, Infinity))
        status = TIGHT if c == rho else (VALID if ok else INVALID)
        return Verdict(status, "radius", c, rho, None, None, f"claimed {claimed}; exact rho = {rho}")
    if rho < c if isinstance(rho, RealAlgebraic) else c > rho:
        return Verdict(INVALID, "radius", c, rho, _gap(c, rho), None, f"claimed {claimed} exceeds the exact rho = {rho}")
    status = TIGHT if _within(c, rho, tol) else VALID
    return Verdict(status, "radius", c, rho, _gap(c, rho), None, f"claimed {claimed}; exact rho = {rho}")


def assert_threshold(system, polyhedron, method: Method, claimed: Any, tolerance: Any = "1e-9", require_tight: bool = False) -> Verdict:
    """pytest helper: fail (AssertionError with the counterexample) unless the claim is valid
    (and, with ``require_tight``, within ``tolerance`` of the exact largest threshold)."""
    v = judge_threshold(system, polyhedron, method, claimed, tolerance)
    if v.status == INVALID or (require_tight and v.status != TIGHT):
        raise AssertionError(str(v))
    return v


@dataclass(frozen=True)
class BatchRow:
    """One row of a batch file: where it came from and its :class:`Verdict`, or,
    for a row that could not be judged (bad input), ``verdict`` None and the
    ``error`` naming the row and what is wrong."""

    name: str
    quantity: str
    method: str
    claimed: str
    verdict: Verdict | None
    error: str | None = None
    row: int = 0

    @property
    def status(self) -> str:
        """The verdict's status, or ``"error"``."""
        return self.verdict.status if self.verdict is not None else "error"


def judge_batch(path: str, tolerance: Any = "1e-9") -> list[BatchRow]:
    """Judge a batch of float results: CSV (problem,quantity,method,claimed) or
    JSON lines; problem paths are relative to the batch file.  Every row is
    judged on its own: a row that cannot be judged (bad problem, method,
    quantity or claim) is returned with its ``error`` and the batch goes on.
    A batch file that cannot be read raises :class:`InvalidInput`."""
    tol = to_rational(tolerance, "--tolerance")
    if tol < 0:
        raise InvalidInput(f"--tolerance: must be >= 0, got {tolerance}")
    path = os.fspath(path)
    if os.path.isdir(path):
        raise InvalidInput(f"{path}: is a directory, not a results file")
    base = os.path.dirname(os.path.abspath(path))
    try:
        with open(path, encoding="utf-8", newline="") as fh:
            if path.endswith(".jsonl"):
                rows = [_json_row(line) for line in fh if line.strip()]
            else:
                reader = csv.DictReader(fh)
                rows = list(reader)
                if not reader.fieldnames:
                    raise InvalidInput(f"{path}: empty CSV file (expected the header problem,quantity,method,claimed)")
                missing = [c for c in ("problem", "claimed") if c not in reader.fieldnames]
                if missing:
                    raise InvalidInput(f"{path}: the CSV header lacks the column(s) {', '.join(missing)} "
                                       f"(expected problem,quantity,method,claimed; got {','.join(map(str, reader.fieldnames))})")
    except OSError as exc:
        raise InvalidInput(f"{path}: cannot read the results file ({exc.strerror or exc})") from None
    except (UnicodeDecodeError, csv.Error) as exc:
        raise InvalidInput(f"{path}: not a CSV or JSON-lines text file ({exc})") from None
    return [_safe_row(k, row, base, tol) for k, row in enumerate(rows, 1)]


def _json_row(line: str) -> Any:
    try:
        return json.loads(line)
    except json.JSONDecodeError as exc:
        return InvalidInput(f"not valid JSON ({exc})")


def _safe_row(k: int, row: Any, base: str, tolerance: Fraction) -> BatchRow:
    get = row.get if isinstance(row, dict) else (lambda key, default=None: default)
    name = get("problem")
    name = os.path.basename(str(name)) if isinstance(name, str) else ("-" if name is None else "(inline)")
    method = get("method")
    shown = [name, str(get("quantity") or "threshold"), str(method) if method else "-", str(get("claimed", ""))]
    try:
        if isinstance(row, InvalidInput):
            raise row
        if not isinstance(row, dict):
            raise InvalidInput(f"expected an object with problem, quantity, method, claimed; got {type(row).__name__}")
        return _judge_row(k, row, base, tolerance)
    except ExactinvException as exc:
        msg = str(exc)
        return BatchRow(*shown, verdict=None, error=f"row {k}: {msg}" if not msg.startswith(f"row {k}") else msg, row=k)


def _claim_of(text: Any) -> Any:
    if isinstance(text, (int, float)) and not isinstance(text, bool):
        return text
    if not isinstance(text, str) or not text.strip():
        raise InvalidInput(f"claimed: missing or not a number ({text!r})")
    try:
        return float(text)
    except ValueError:
        pass
    try:
        return to_rational(text.strip(), "claimed")
    except InvalidInput:
        raise InvalidInput(f"claimed: cannot read {text!r} as a number (write e.g. 0.5, 1e-3, 1/3 or inf)") from None


def _judge_row(k: int, row: dict, base: str, tolerance: Any) -> BatchRow:
    extra = set(row) - {"problem", "quantity", "method", "claimed"} - {None}
    if extra:
        key = sorted(extra)[0]
        raise InvalidInput(f"row {k}: unknown column {key!r}"
                           f"{did_you_mean(key, ('problem', 'quantity', 'method', 'claimed'))}")
    if None in row:
        raise InvalidInput(f"row {k}: more fields than the header has columns")
    source = row.get("problem")
    if not source:
        raise InvalidInput(f"row {k}: problem: missing")
    prob = load_problem(source if isinstance(source, dict) else os.path.join(base, source))
    spec = row.get("method") or None
    if isinstance(spec, str):
        method = method_from_text(spec, "method")
    else:
        method = parse_method(spec) if spec else prob.method
    quantity = row.get("quantity") or "threshold"
    claimed = _claim_of(row.get("claimed"))
    if quantity in ("threshold", "radius") and method is None:
        raise InvalidInput(f"row {k}: method: a {quantity} needs a method (in the row or in the problem file)")
    if quantity == "threshold":
        v = judge_threshold(prob.system, prob.polyhedron, method, claimed, tolerance)
    elif quantity == "gamma":
        v = judge_gamma(prob.system, prob.polyhedron, claimed, tolerance)
    elif quantity == "radius":
        v = judge_radius(method, claimed, tolerance)
    else:
        raise InvalidInput(f"row {k}: quantity: unknown {quantity!r}{did_you_mean(quantity, ('threshold', 'gamma', 'radius'))} "
                           "(threshold, gamma, radius)")
    name = prob.name if isinstance(source, dict) else os.path.basename(str(source))
    return BatchRow(name, quantity, method.name if method else "-", str(row["claimed"]), v, row=k)
