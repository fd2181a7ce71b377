"""The oracle's judge of linear programs written in cvxpy (:func:`judge_lp`).

The user's solved ``cvxpy.Problem`` is converted to exact data -- the data
cvxpy hands its solvers (``problem.get_problem_data``: ``minimize c.x + d
s.t. A x + s = b``, s in {0}^k x R_+^l; for ``Maximize(f)`` cvxpy minimizes
-f), every float taken exactly (``Fraction(float)``) or rounded as stated --
solved exactly with a verified certificate by :mod:`exactinv.lp` (float hint
-> verification in Q -> PPL's exact simplex), and its reported value judged.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

import flint
import numpy as np

from ..core.scalars import INF, Infinity, exact_from_float, to_rational
from ..core.tags import CounterexampleKind
from ..errors import InvalidInput
from ..lp import INFEASIBLE, UNBOUNDED, ExactLPSolver, HintBackend, LPResult
from .oracle_judges import INVALID, TIGHT, VALID, Verdict, exact_claim, exact_gap

__all__ = ["LPVerdict", "judge_lp"]

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
             limit_denominator: int | None = None, hint: str | HintBackend | None = None) -> LPVerdict:
    """Judge a user's solved cvxpy LP exactly.

    ``problem``: a ``cvxpy.Problem``, ``Minimize``/``Maximize`` of an affine
    objective under affine ``==``, ``<=``, ``>=`` constraints (variables of any
    shape, ``nonneg``/``nonpos`` allowed, parameters at their values); else
    :class:`~exactinv.InvalidInput`.  Floats are taken exactly, or rounded to a
    denominator <= ``limit_denominator`` (then the verdict is about that LP).
    ``claimed`` (default ``problem.value``) is judged as the optimum
    (``claim="optimum"``: ``tight`` within the relative ``tolerance``, else
    ``invalid`` with a feasible point beating it, kind ``"better_point"``, or a
    dual bound, ``"dual_bound"``) or as a primal bound (``claim="bound"``:
    ``valid``/``tight``, or ``invalid`` with the dual bound).  ``hint``: the
    engine's float-hint backend.

    >>> import cvxpy as cp
    >>> x = cp.Variable(2, nonneg=True, name='x')
    >>> lp = cp.Problem(cp.Maximize(x[0] + x[1]), [3 * x[0] + x[1] <= 1, x[0] + 3 * x[1] <= 1])
    >>> v = judge_lp(lp, 0.5)   # the maximum is 1/2, at x = (1/4, 1/4)
    >>> v.status, v.exact, v.x
    (<Status.TIGHT: 'tight'>, Fraction(1, 2), {'x': (Fraction(1, 4), Fraction(1, 4))})
    >>> judge_lp(lp, 0.6).counterexample['kind']   # 0.6 is unattainable: a dual bound proves it
    'dual_bound'
    """
    try:
        import cvxpy as cp  # optional dependency: only this judge needs it
    except ImportError:
        raise ImportError("judge_lp judges cvxpy problems and needs cvxpy, an optional dependency: pip install cvxpy") from None
    claimed, tol = _checked_claim(cp, problem, claimed, claim, limit_denominator), to_rational(tolerance, "tolerance")
    maximize = isinstance(problem.objective, cp.Maximize)
    data = _exact_lp_data(cp, problem, limit_denominator)
    R, N = len(data["b"]), len(data["c"])
    solver = ExactLPSolver(_fmpq_matrix(data["A"], R, N), data["equality"], hint)
    res = solver.solve([-v for v in data["c"]], data["b"], [False] * N)  # max -c.x = -(min c.x)
    common = dict(quantity="lp", claimed=exact_claim(claimed), data=data, lp=res,
                  reported_point_feasible=_reported_point_feasible(data, problem))
    if res.status in (INFEASIBLE, UNBOUNDED):
        return _failure_verdict(res, data, claimed, maximize, common)
    return _optimum_verdict(res, data, claimed, maximize, claim, tol, common)


def _checked_claim(cp: Any, problem: Any, claimed: Any, claim: str, limit_denominator: int | None) -> Any:
    """The arguments of :func:`judge_lp` checked; the claim (default: the problem's value)."""
    if not isinstance(problem, cp.Problem):
        raise InvalidInput(f"judge_lp: expected a cvxpy.Problem, got {type(problem).__name__}")
    if claim not in ("optimum", "bound"):
        raise InvalidInput(f"claim: {claim!r} is not 'optimum' or 'bound'")
    if limit_denominator is not None and (not isinstance(limit_denominator, int) or limit_denominator < 1):
        raise InvalidInput(f"limit_denominator: a positive integer, got {limit_denominator!r}")
    if claimed is None:
        if problem.status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE) or problem.value is None:
            raise InvalidInput(f"judge_lp: the problem is not solved to optimality (status {problem.status!r}); "
                               "solve it first or pass claimed=")
        claimed = float(problem.value)
    return claimed


def _failure_verdict(res: LPResult, data: dict, claimed: Any, maximize: bool, common: dict) -> LPVerdict:
    """The exact LP is infeasible (Farkas certificate) or unbounded (a point beating the claim and a ray)."""
    if res.status == INFEASIBLE:
        return LPVerdict(INVALID, exact=None, counterexample={"kind": CounterexampleKind.INFEASIBLE, "farkas": res.y}, y=res.y,
                         message=f"claimed {claimed}, but the exact LP is infeasible (Farkas certificate y)", **common)
    exact = INF if maximize else -INF
    point = _beyond(res, data, common["claimed"], -1 if maximize else 1)
    return LPVerdict(INVALID, exact=exact, counterexample={"kind": CounterexampleKind.UNBOUNDED, "x": _by_variable(point, data),
                                                            "ray": _by_variable(res.ray, data)},
                     message=f"claimed {claimed}, but the exact LP is unbounded "
                             f"({'maximum' if maximize else 'minimum'} {exact})", **common)


def _optimum_verdict(res: LPResult, data: dict, claimed: Any, maximize: bool, claim: str, tol: Fraction,
                     common: dict) -> LPVerdict:
    """tight / valid (a bound attained) / invalid with a better point or a dual bound."""
    c_claim, name = common["claimed"], "maximum" if maximize else "minimum"
    exact = (-1 if maximize else 1) * (-res.value + data["d"])  # user's value = sign * (c.x + d)
    x = _by_variable(res.x, data)
    better = (c_claim < exact) if maximize else (c_claim > exact)  # a feasible point beats the claim
    close = abs(c_claim - exact) <= tol * max(abs(exact), Fraction(1)) if not isinstance(c_claim, Infinity) else False
    common = dict(exact=exact, relative_gap=exact_gap(c_claim, exact), x=x, y=res.y, **common)
    if close:
        return LPVerdict(TIGHT, message=f"claimed {claimed} is within {tol} of the exact {name} {exact}", **common)
    if better:
        if claim == "bound":
            return LPVerdict(VALID, message=f"claimed {claimed} is attained or beaten; the exact {name} is {exact}", **common)
        return LPVerdict(INVALID, counterexample={"kind": CounterexampleKind.BETTER_POINT, "x": x, "value": exact},
                         message=f"claimed {name} {claimed}, but the exact feasible point x reaches {exact}", **common)
    return LPVerdict(INVALID, counterexample={"kind": CounterexampleKind.DUAL_BOUND, "y": res.y, "bound": exact},
                     message=f"claimed {name} {claimed} is unattainable: the exact dual y proves "
                             f"every feasible point has value {'<=' if maximize else '>='} {exact}", **common)


def _exact_lp_data(cp, problem, limit_denominator) -> dict:
    """c, d, A, b, row kinds and variable columns of the problem's canonical
    LP, every float taken exactly (or rounded as stated)."""
    raw, inverse = _canonical_data(cp, problem)
    dims = raw["dims"]
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
    for bounds, sense in ((raw.get("lower_bounds"), -1), (raw.get("upper_bounds"), 1)):
        if bounds is not None:  # variable bounds passed to the solver apart: as rows
            for i, v in enumerate(bounds):
                if math.isfinite(v):
                    rows.append({i: Fraction(sense)})
                    bs.append(sense * exact(v))
                    equality.append(False)
    columns = _variable_columns(problem, inverse, len(c))
    return {"c": [exact(v) for v in c], "d": exact(d), "A": rows, "b": bs, "equality": equality, "columns": columns}


def _canonical_data(cp: Any, problem: Any) -> tuple[dict, Any]:
    """cvxpy's solver data of an LP (and its inverse data); InvalidInput if it is not one."""
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
    return raw, inverse


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
