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

Linear programs written in cvxpy (float implementations of gamma*, of the
forward-Euler vertex LPs, or any LP) are judged by :func:`judge_lp`: the
user's solved ``cvxpy.Problem`` is converted to exact data, solved exactly
with a verified certificate, and its reported value judged.
"""

from __future__ import annotations

import csv
import json
import math
import os
from dataclasses import dataclass, field
from enum import StrEnum
from fractions import Fraction
from typing import Any

import flint
import numpy as np

from ..beyond.largest import largest_threshold, valid_steplengths
from ..core.algebraic import RealAlgebraic
from ..core.roots import first_sign_change
from ..core.scalars import INF, Infinity, exact_from_float, to_rational
from ..errors import ExactinvException, InvalidInput
from ..lp import INFEASIBLE, UNBOUNDED, ExactLPSolver, LPResult
from ..model.methods import Method, forward_euler
from ..paper.invariance import discrete_invariance, optimal_gamma
from ..paper.monotonicity import absolute_monotonicity_radius
from .problem import did_you_mean, load_problem, method_from_text, parse_method

__all__ = ["Status", "Verdict", "LPVerdict", "BatchRow", "judge_threshold", "judge_gamma", "judge_root", "judge_radius",
           "judge_lp", "assert_threshold", "judge_batch", "judge_row"]

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


def judge_row(row: dict, base: str = ".", tolerance: Any = "1e-9", number: int = 1) -> BatchRow:
    """Judge one row of a batch (a dict with problem, quantity, method,
    claimed; ``problem`` a file relative to ``base``, a problem dict or its
    JSON text), as :func:`judge_batch` judges row ``number``: a row that
    cannot be judged comes back with its ``error``.

    >>> box = {"system": {"A": [[-1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}}
    >>> print(judge_row({"problem": box, "quantity": "gamma", "claimed": "0.5"}).status)  # gamma* = 1/2
    tight
    """
    tol = to_rational(tolerance, "tolerance")
    if tol < 0:
        raise InvalidInput(f"tolerance: must be >= 0, got {tolerance}")
    return _safe_row(number, row, base, tol)


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
    inline = isinstance(source, dict) or source.lstrip().startswith("{")  # the problem itself, not a file name
    prob = load_problem(source if inline else os.path.join(base, source))
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
    name = prob.name if inline else os.path.basename(str(source))
    return BatchRow(name, quantity, method.name if method else "-", str(row["claimed"]), v, row=k)


# ------------------------------------------------------------ cvxpy LPs
@dataclass(frozen=True)
class LPVerdict(Verdict):
    """The verdict on a solved cvxpy LP (:func:`judge_lp`).

    ``exact`` is the exact optimum of the LP's exact data (in the problem's own
    sense: a maximum for ``cp.Maximize``), ``INF``/``-INF`` when unbounded,
    ``None`` when infeasible.  The certificate: ``x`` an exact optimal point
    (``{variable name: values}``, column-major as cvxpy flattens), ``y`` the
    exact dual of the canonical rows ``A x (=|<=) b`` (cvxpy's order: equalities
    first): y >= 0 on the inequality rows and A^T y = -c, so every feasible x
    has c.x = -y.(Ax) >= -b.y; with c.x* = -b.y this proves optimality in Q.  ``lp`` is the verified
    :class:`~exactinv.lp.LPResult` of the canonical program ``minimize c.x + d``
    (its x, y, and the exact data ``c``, ``d``, ``A``, ``b``, ``equality``).
    ``reported_point_feasible`` says whether the solver's own point, taken
    exactly, satisfies the exact constraints (None: no point)."""

    x: dict | None = None
    y: tuple[Fraction, ...] | None = None
    lp: LPResult | None = field(default=None, repr=False, compare=False)
    data: dict | None = field(default=None, repr=False, compare=False)
    reported_point_feasible: bool | None = None


_LP_CONSTRAINTS = ("Equality", "Zero", "Inequality", "NonNeg", "NonPos")
_VARIABLE_ATTRIBUTES = {"nonneg", "nonpos", "real"}


def judge_lp(problem: Any, claimed: Any = None, *, claim: str = "optimum", tolerance: Any = "1e-9",
             limit_denominator: int | None = None, hint: Any = None) -> LPVerdict:
    """Judge a user's solved cvxpy LP exactly.

    ``problem`` is a ``cvxpy.Problem`` with a ``Minimize``/``Maximize`` of an
    affine objective and affine ``==``, ``<=``, ``>=`` constraints over
    variables of any shape (attributes ``nonneg``/``nonpos`` allowed;
    parameters take their current values).  Anything else (integer variables,
    cones, quadratic terms, symmetric/PSD/bounded variables) raises
    :class:`~exactinv.InvalidInput`.

    The data are those cvxpy hands its solvers (``problem.get_problem_data``:
    ``minimize c.x + d  s.t.  A x + s = b``, s in {0}^k x R_+^l; for
    ``Maximize(f)`` cvxpy minimizes -f); every float is
    taken exactly (``Fraction(float)``), or, with ``limit_denominator=L``,
    rounded to the nearest rational with denominator <= L (a stated rounding:
    then the verdict is about the rounded LP).  The exact LP is solved by
    exactinv's engine (float hint -> verification in Q -> PPL's exact simplex;
    ``hint`` chooses the hint backend).

    ``claimed`` defaults to ``problem.value`` (the problem must then have been
    solved, status optimal).  With ``claim="optimum"`` the value is judged as
    the optimum: ``tight`` within the relative ``tolerance``, else ``invalid``
    with an exact counterexample -- a feasible point beating it (kind
    ``"better_point"``) or a dual bound proving it unattainable (kind
    ``"dual_bound"``).  With ``claim="bound"`` it is judged as a primal bound (a
    value some feasible point attains or beats: >= the minimum, <= the
    maximum): ``valid``/``tight``, or ``invalid`` with the dual bound.
    """
    try:
        import cvxpy as cp  # optional dependency: only this judge needs it
    except ImportError:
        raise ImportError("judge_lp judges cvxpy problems and needs cvxpy, an optional dependency: pip install cvxpy") from None

    if not isinstance(problem, cp.Problem):
        raise InvalidInput(f"judge_lp: expected a cvxpy.Problem, got {type(problem).__name__}")
    if claim not in ("optimum", "bound"):
        raise InvalidInput(f"claim: {claim!r} is not 'optimum' or 'bound'")
    if limit_denominator is not None and (not isinstance(limit_denominator, int) or limit_denominator < 1):
        raise InvalidInput(f"limit_denominator: a positive integer, got {limit_denominator!r}")
    tol = to_rational(tolerance, "tolerance")
    if claimed is None:
        if problem.status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE) or problem.value is None:
            raise InvalidInput(f"judge_lp: the problem is not solved to optimality (status {problem.status!r}); "
                               "solve it first or pass claimed=")
        claimed = float(problem.value)
    c_claim = _exact_claim(claimed)
    maximize = isinstance(problem.objective, cp.Maximize)
    data = _exact_lp_data(cp, problem, limit_denominator)
    R, N = len(data["b"]), len(data["c"])
    solver = ExactLPSolver(_fmpq_matrix(data["A"], R, N), data["equality"], hint)
    res = solver.solve([-v for v in data["c"]], data["b"], [False] * N)  # max -c.x = -(min c.x)
    sign = -1 if maximize else 1  # user's value = sign * (c.x + d)
    d = data["d"]
    reported_ok = _reported_point_feasible(data, problem)
    verdict = dict(quantity="lp", claimed=c_claim, data=data, lp=res, reported_point_feasible=reported_ok)
    name = "maximum" if maximize else "minimum"
    if res.status == INFEASIBLE:
        return LPVerdict(INVALID, exact=None, counterexample={"kind": "infeasible", "farkas": res.y}, y=res.y,
                         message=f"claimed {claimed}, but the exact LP is infeasible (Farkas certificate y)", **verdict)
    if res.status == UNBOUNDED:
        exact = INF if maximize else -INF
        point = _beyond(res, data, c_claim, sign)
        return LPVerdict(INVALID, exact=exact, counterexample={"kind": "unbounded", "x": _by_variable(point, data),
                                                                "ray": _by_variable(res.ray, data)},
                         message=f"claimed {claimed}, but the exact LP is unbounded ({name} {exact})", **verdict)
    exact = sign * (-res.value + d)
    x = _by_variable(res.x, data)
    better = (c_claim < exact) if maximize else (c_claim > exact)  # a feasible point beats the claim
    gap = _gap(c_claim, exact)
    close = abs(c_claim - exact) <= tol * max(abs(exact), Fraction(1)) if not isinstance(c_claim, Infinity) else False
    common = dict(exact=exact, relative_gap=gap, x=x, y=res.y, **verdict)
    if close:
        return LPVerdict(TIGHT, message=f"claimed {claimed} is within {tol} of the exact {name} {exact}", **common)
    if better:
        if claim == "bound":
            return LPVerdict(VALID, message=f"claimed {claimed} is attained or beaten; the exact {name} is {exact}", **common)
        return LPVerdict(INVALID, counterexample={"kind": "better_point", "x": x, "value": exact},
                         message=f"claimed {name} {claimed}, but the exact feasible point x reaches {exact}", **common)
    return LPVerdict(INVALID, counterexample={"kind": "dual_bound", "y": res.y, "bound": exact},
                     message=f"claimed {name} {claimed} is unattainable: the exact dual y proves "
                             f"every feasible point has value {'<=' if maximize else '>='} {exact}", **common)


def _exact_lp_data(cp, problem, limit_denominator) -> dict:
    """c, d, A, b, row kinds and variable columns of the problem's canonical
    LP, every float taken exactly (or rounded as stated)."""
    if not problem.is_dcp() or not problem.objective.args[0].is_affine():
        raise InvalidInput("judge_lp: the objective is not affine (only linear programs are judged)")
    for k, con in enumerate(problem.constraints):
        if type(con).__name__ not in _LP_CONSTRAINTS or not all(a.is_affine() for a in con.args):
            raise InvalidInput(f"judge_lp: constraint {k} ({type(con).__name__}: {con}) is not an affine ==, <= or >=")
    variables = problem.variables()
    for v in variables:
        extra = {a for a, on in v.attributes.items() if on and on is not None and a not in _VARIABLE_ATTRIBUTES}
        if extra:
            raise InvalidInput(f"judge_lp: variable {v.name()} has attributes {sorted(extra)} "
                               "(only nonneg/nonpos are supported)")
    for param in problem.parameters():
        if param.value is None:
            raise InvalidInput(f"judge_lp: parameter {param.name()} has no value")
    solver = next((s for s in ("CLARABEL", "SCS", "ECOS") if s in cp.installed_solvers()), None)
    if solver is None:
        raise InvalidInput("judge_lp: cvxpy has no conic solver installed to canonicalise with (CLARABEL, SCS or ECOS)")
    try:
        raw, _, inverse = problem.get_problem_data(solver)
    except cp.error.DCPError as exc:
        raise InvalidInput(f"judge_lp: {exc}") from None
    dims = raw["dims"]
    if (getattr(dims, "exp", 0) or getattr(dims, "soc", []) or getattr(dims, "psd", [])
            or getattr(dims, "p3d", []) or raw.get("P") is not None):
        raise InvalidInput("judge_lp: the problem is not a linear program (cone constraints after canonicalisation)")
    c, d, A, b = raw["param_prob"].apply_parameters()  # A x + b in {0}^k x R_+^l
    A = -(A.tocsr() if hasattr(A, "tocsr") else A)  # -A x (=|<=) b
    A.sort_indices()
    exact = _exactly(limit_denominator)
    rows, nrows = [], A.shape[0]
    for r in range(nrows):
        start, end = A.indptr[r], A.indptr[r + 1]
        rows.append({int(i): exact(v) for i, v in zip(A.indices[start:end], A.data[start:end]) if v != 0})
    bs = [exact(v) for v in b]
    equality = [r < dims.zero for r in range(nrows)]
    N = len(c)
    for bounds, sense in ((raw.get("lower_bounds"), -1), (raw.get("upper_bounds"), 1)):
        if bounds is not None:  # variable bounds passed to the solver apart: as rows
            for i, v in enumerate(bounds):
                if math.isfinite(v):
                    rows.append({i: Fraction(sense)})
                    bs.append(sense * exact(v))
                    equality.append(False)
    columns = _variable_columns(problem, inverse, N)
    return {"c": [exact(v) for v in c], "d": exact(d), "A": rows, "b": bs, "equality": equality, "columns": columns}


def _exactly(limit_denominator):
    def convert(v) -> Fraction:
        q = exact_from_float(float(v))
        return q if limit_denominator is None else q.limit_denominator(limit_denominator)
    return convert


def _variable_columns(problem, inverse, N) -> dict:
    """{variable name: (its first column, its shape)} in the canonical LP, following
    cvxpy's renaming of attributed variables (CvxAttr2Constr) to the stuffed offsets."""
    renamed: dict = {}
    offsets: dict = {}
    for item in inverse:
        if isinstance(item, tuple) and item and isinstance(item[0], dict):
            renamed.update({k: v.id for k, v in item[0].items() if hasattr(v, "id")})
        if hasattr(item, "var_offsets"):
            offsets = item.var_offsets
    out = {}
    for v in problem.variables():
        vid = renamed.get(v.id, v.id)
        if vid in offsets:
            out[_variable_key(v, out)] = (offsets[vid], v.shape)
    return out


def _variable_key(v, taken) -> str:
    """A variable's name, made unique by its cvxpy id when two share a name."""
    return v.name() if v.name() not in taken else f"{v.name()}#{v.id}"


def _fmpq_matrix(rows, R, N):
    M = flint.fmpq_mat(R, N)
    for r, row in enumerate(rows):
        for i, v in row.items():
            M[r, i] = flint.fmpq(v.numerator, v.denominator)
    return M


def _by_variable(x, data) -> dict:
    out = {}
    for name, (start, shape) in data["columns"].items():
        size = math.prod(shape) if shape else 1
        out[name] = tuple(x[start:start + size])
    return out


def _beyond(res, data, claimed, sign):
    """A feasible point of an unbounded LP whose value beats ``claimed``."""
    c, d = data["c"], data["d"]
    value = lambda pt: sign * (sum(ci * xi for ci, xi in zip(c, pt)) + d)  # noqa: E731
    x, ray = res.x, res.ray
    slope = value(ray) - value([0] * len(ray))
    t = Fraction(0) if isinstance(claimed, Infinity) else max(Fraction(0), (claimed - value(x)) / slope) + 1
    return tuple(xi + t * di for xi, di in zip(x, ray))


def _reported_point_feasible(data, problem) -> bool | None:
    """Does the solver's own point, taken exactly, satisfy the exact constraints?"""
    x = [Fraction(0)] * len(data["c"])
    keys: dict = {}
    for v in problem.variables():
        key = _variable_key(v, keys)
        keys[key] = None
        if key not in data["columns"] or v.value is None:
            return None
        start, _ = data["columns"][key]
        for k, val in enumerate(np.asarray(v.value, dtype=float).flatten(order="F")):
            x[start + k] = exact_from_float(val)
    for row, rhs, eq in zip(data["A"], data["b"], data["equality"]):
        lhs = sum(a * x[i] for i, a in row.items())
        if lhs > rhs or (eq and lhs != rhs):
            return False
    return True
