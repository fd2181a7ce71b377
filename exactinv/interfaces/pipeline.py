"""The whole job on one problem: gamma*, forward Euler, the paper's threshold,
the exact valid set and largest threshold, one certificate and (optionally)
the trusted kernel's verdict on it -- as a :class:`Report`, without printing.

The command line, the notebooks and a batch runner all call :func:`certify`.

>>> import exactinv as ei
>>> from exactinv.interfaces.problem import Problem
>>> box = Problem(ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1]), name="box")
>>> report = certify(box, ei.methods.taylor(2))
>>> report.ok, report.lines[-1]
(True, 'independent check: VERIFIED (5 claims)')
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Callable

import exactinv_check

from ..conditions.polyhedron import ConditionSet
from ..control.optimal_gain import OptimalGain, optimal_gain
from ..core.encode import encode_real, mat
from ..core.scalars import matrix_text
from ..core.text import exact_text, safe_step_text
from ..errors import Undecided
from ..invariance.gamma_star import OptimalGamma, optimal_gamma
from ..model import Method
from ..model.record import certificate as make_certificate
from ..thresholds.forward_euler import ForwardEulerThreshold
from ..thresholds.polynomial import SteplengthThreshold
from ..thresholds.steplength import steplength_threshold_from_gamma
from ..validset.engine import forward_euler_with_gamma, largest_threshold, valid_steplengths
from ..validset.results import EllipsoidForwardEulerThreshold, LargestThreshold, ValidSteplengths
from .ellipsoid_report import ellipsoid_results
from .problem import Problem

__all__ = ["Report", "certify", "VERTEX_LIMIT", "exact_text", "safe_step_text", "result_values"]

VERTEX_LIMIT = 12  # dimension above which the vertex enumeration is not attempted by default


@dataclass(frozen=True)
class Report:
    """What :func:`certify` found: the ``results`` (in certificate order), the
    JSON ``certificate``, the kernel's ``check`` report (None when skipped)
    and the human-readable ``lines``.  ``ok``: the kernel verified the
    certificate (False when the check was skipped).  ``outcome``: for the
    exit code (:mod:`exactinv.interfaces.exit_codes`).  ``undecided``: the
    questions exactinv could neither prove nor refute, as (what, why) pairs;
    their claims are absent from the certificate, every other claim is in it
    (a partial answer, never all-or-nothing)."""

    problem: Problem
    method: Method | None
    results: tuple[Any, ...] = field(repr=False)
    certificate: dict = field(repr=False)
    check: Any = None
    lines: tuple[str, ...] = field(default=(), repr=False)
    undecided: tuple[tuple[str, str], ...] = ()
    closed_loop: "Report | None" = field(default=None, repr=False)

    @property
    def ok(self) -> bool:
        """The kernel verified the certificate (of every claim that was decided); for a gain
        design, also the closed loop's certificate (``closed_loop``, its own report)."""
        return self.check is not None and self.check.ok and (self.closed_loop is None or self.closed_loop.ok)

    @property
    def complete(self) -> bool:
        """``ok`` and every question decided: nothing was left out of the certificate."""
        return self.ok and not self.undecided

    @property
    def text(self) -> str:
        return "\n".join(self.lines)

    @property
    def refuted(self) -> bool:
        """The set is not invariant: an exact witness point (a polyhedron) or direction (an ellipsoid)."""
        return any((isinstance(r, OptimalGamma) and r.witness is not None) or getattr(r, "holds", True) is False
                   for r in self.results)

    @property
    def outcome(self) -> str:
        """``"error"`` if the kernel rejected the certificate, else ``"refuted"`` if the set
        is not invariant, ``"undecided"`` if a question is undecided, else ``"proved"``
        (:mod:`exactinv.interfaces.exit_codes`; with the check skipped: what the engine found)."""
        if self.check is not None and not self.check.ok:
            return "error"
        return "refuted" if self.refuted else "undecided" if self.undecided else "proved"

    def values(self) -> dict[str, Any]:
        """The exact values of the results, encoded as the certificate encodes them (:func:`result_values`).

        >>> import exactinv as ei
        >>> from exactinv.interfaces.problem import Problem
        >>> certify(Problem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])), check=False).values()
        {'gamma_star': '1/2', 'forward_euler': '2'}

        A gain design has ``gain`` (F, gamma, the forward-Euler step over all gains) and the
        closed loop's own values under ``closed_loop``.
        """
        values = result_values(self.results)
        if self.closed_loop is not None:
            values["closed_loop"] = self.closed_loop.values()
        return values


_KEYS = ((OptimalGamma, "gamma_star"), (ForwardEulerThreshold, "forward_euler"),
         (EllipsoidForwardEulerThreshold, "forward_euler"),
         (SteplengthThreshold, "paper_threshold"), (LargestThreshold, "largest_threshold"))


def result_values(results: Any) -> dict[str, Any]:
    """The exact values of ``results`` by name -- ``gamma_star``, ``forward_euler``,
    ``paper_threshold``, ``largest_threshold`` (with ``largest_attained``) and
    ``valid_steplengths`` (intervals ``lo``, ``hi``, ``lo_closed``, ``hi_closed``) --
    each encoded as the certificate encodes it (:func:`exactinv.core.encode.encode_real`:
    ``"p/q"``, ``"oo"``, or ``{"poly": [...], "interval": [lo, hi]}``; never a float).

    >>> import exactinv as ei
    >>> S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
    >>> result_values([ei.optimal_gamma(S, P), ei.valid_steplengths(S, P, ei.methods.taylor(1))])
    {'gamma_star': '1/2', 'valid_steplengths': [{'lo': '0', 'hi': '2', 'lo_closed': True, 'hi_closed': True}]}
    """
    values: dict[str, Any] = {}
    for r in results:
        if isinstance(r, OptimalGain):
            values["gain"] = {"holds": r.holds, "F": mat(r.F) if r.holds else None, "gamma": encode_real(r.gamma),
                              "forward_euler": encode_real(r.forward_euler_step)}
        for kind, key in _KEYS:
            if isinstance(r, kind):
                values[key] = encode_real(r.value)
        if isinstance(r, LargestThreshold):
            values["largest_attained"] = bool(r.attained)
        if isinstance(r, ValidSteplengths):
            values["valid_steplengths"] = [
                {"lo": encode_real(i.lo), "hi": encode_real(i.hi), "lo_closed": i.lo_closed, "hi_closed": i.hi_closed}
                for i in r.intervals]
    return values


def stages(method: Method | None, check: bool) -> int:
    """How many progress steps :func:`certify` reports (the same on an ellipsoid).

    >>> stages(None, True), stages(None, False)   # gamma*, forward Euler, the check
    (3, 2)
    >>> from exactinv.model import methods
    >>> stages(methods.trapezoid(), True)          # + the paper's threshold, the valid set
    5
    """
    return (5 if method is not None else 3) - (not check)


def certify(problem: Problem, method: Method | None = None, check: bool = True,
            progress: Callable[[str], None] | None = None) -> Report:
    """Compute and certify everything that applies to ``problem`` (``method``
    overrides the problem's own) and, if ``check``, run the trusted kernel on
    the certificate.  ``progress(stage)`` is called before each stage.

    x' = -x on [-1, 1] = {x <= 1, -x <= 1}: H = [[-1/2, 1/2], [1/2, -1/2]] gives gamma* = 1/2,
    so forward Euler (1 - dt in [-1, 1] iff dt <= 2) has the threshold 1/gamma* = 2.

    >>> import exactinv as ei
    >>> from exactinv.interfaces.problem import Problem
    >>> decay = Problem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), name="decay")
    >>> report = certify(decay, ei.methods.forward_euler())
    >>> for line in report.lines[3:]:
    ...     print(line)
    largest forward-Euler step: 2; use dt <= 2  (1/gamma* and the valid set agree)
    paper's threshold for forward_euler (Theorem 3.4 (polynomial methods)): 2; use dt <= 2
    exact valid steplengths for forward_euler: [0, 2]
    exact largest threshold: 2; use dt <= 2
    independent check: VERIFIED (5 claims)
    >>> report.ok, certify(decay, check=False).ok  # unchecked: not ok
    (True, False)
    """
    method = method if method is not None else problem.method
    step = progress or (lambda what: None)
    if problem.design == "optimal_gain":
        return _certify_gain(problem, method, check, progress)
    S, P = problem.system, problem.polyhedron
    if problem.is_ellipsoid:
        lines = [f"problem {problem.name}: n = {S.n}, ellipsoid x^T Q x <= 1" + (f", method {method.name}" if method else "")]
        return _finish(problem, method, ellipsoid_results(S, P, method, lines, step), lines, check, step)
    lines = [f"problem {problem.name}: n = {S.n}, m = {P.m} inequalities" + (f", method {method.name}" if method else "")]
    undecided: list[tuple[str, str]] = []
    step("gamma* (verified row LPs)")
    gamma = optimal_gamma(S, P)
    results: list[Any] = [gamma]
    if gamma.witness is not None:
        w = gamma.witness
        lines.append(f"continuous invariance: FAILS -- x = [{', '.join(map(str, w.x))}] lies on facet {w.facet} "
                     f"and g_{w.facet}.Ax = {w.value} > 0")
        lines.append("gamma*: oo (no steplength threshold exists)")
    else:
        lines.append("continuous invariance: holds (certificate H with HG = GA, Hb <= 0, off-diagonal >= 0)")
        lines.append(f"gamma*: {gamma.value}   [row LPs verified in Q; routes: {_routes(gamma.paths)}]")
        step("forward Euler (1/gamma* and the valid set)")
        results += _forward_euler(S, P, gamma, lines)
        if method is not None:
            step(f"paper's threshold for {method.name}")
            results += _decided(f"paper's threshold for {method.name}", lines, undecided,
                                lambda: _paper_threshold(S, P, method, gamma, lines))
    if method is not None and P.n <= VERTEX_LIMIT:
        step("exact valid steplengths")
        results += _decided(f"exact valid steplengths and largest threshold for {method.name}", lines, undecided,
                            lambda: _largest(S, P, method, lines))
    return _finish(problem, method, results, lines, check, step, tuple(undecided))


def _decided(what: str, lines: list[str], undecided: list[tuple[str, str]],
             stage: Callable[[], list[Any]]) -> list[Any]:
    """The results of one stage, or none if it raises :class:`~exactinv.Undecided`: then
    the question and the reason are recorded (``undecided``, a report line) and the
    other stages go on -- the certificate simply holds no claim for it."""
    try:
        return stage()
    except Undecided as exc:
        undecided.append((what, str(exc)))
        lines.append(f"{what}: UNDECIDED -- {exc}")
        return []


def _finish(problem: Problem, method: Method | None, results: list[Any], lines: list[str], check: bool,
            step: Callable[[str], None], undecided: tuple[tuple[str, str], ...] = ()) -> Report:
    """The certificate of ``results`` and, if ``check``, the trusted kernel's verdict on it."""
    cert = make_certificate(problem.system, problem.polyhedron, method, results)
    report = None
    if check:
        step("independent check (the trusted kernel)")
        report = exactinv_check.check(cert)
        lines.append(f"independent check: {'VERIFIED' if report.ok else 'REJECTED'} ({len(cert['claims'])} claims)")
    else:
        lines.append(f"independent check: skipped (--no-check); run `exactinv check` on the certificate "
                     f"({len(cert['claims'])} claims)")
    if undecided:
        lines.append(f"undecided ({len(undecided)}, not in the certificate): " + "; ".join(w for w, _ in undecided))
    return Report(problem, method, tuple(results), cert, report, tuple(lines), undecided)


def _routes(paths: Any) -> str:
    """{'float-rounded': 4} -> 'float-rounded x4'."""
    if isinstance(paths, dict):
        return ", ".join(f"{k} x{v}" for k, v in paths.items())
    return str(paths)


def _forward_euler(S, P, gamma: OptimalGamma, lines: list[str]) -> list[Any]:
    if P.n > VERTEX_LIMIT:
        lines.append("largest forward-Euler step 1/gamma* (Lemma 3.14): see gamma* above")
        return []
    fe = forward_euler_with_gamma(S, P, gamma)
    lines.append(f"largest forward-Euler step: {exact_text(fe.value)}{safe_step_text(fe)}  "
                 "(1/gamma* and the valid set agree)")
    return [fe]


def _paper_threshold(S, P, method: Method, gamma: OptimalGamma, lines: list[str]) -> list[Any]:
    t = steplength_threshold_from_gamma(method, gamma)
    lines.append(f"paper's threshold for {method.name} ({t.theorem}): {exact_text(t.value)}"
                 + ("" if t.attained else "  (not attained: valid on [0, tau))") + safe_step_text(t))
    if t.paper != t.value:
        lines.append(f"  the paper, taken literally, gives {exact_text(t.paper)}")
    lines.extend(f"  note: {note}" for note in t.notes)
    return [t]


def _largest(S, P, method: Method, lines: list[str]) -> list[Any]:
    conditions = ConditionSet(S, P, method)  # built once, shared by both results
    V = valid_steplengths(S, P, method, conditions=conditions)
    L = largest_threshold(S, P, method, conditions=conditions)
    lines.append(f"exact valid steplengths for {method.name}: {V.intervals!r}")
    lines.append(f"exact largest threshold: {exact_text(L.value)}" + ("" if L.attained else "  (not attained)")
                 + safe_step_text(L))
    return [L, V]


def _certify_gain(problem: Problem, method: Method | None, check: bool,
                  progress: Callable[[str], None] | None) -> Report:
    """A gain design: the optimal gain's certificate (checked by the kernel), then
    :func:`certify` on the closed loop x' = (A + BF)x (its own report and certificate,
    ``Report.closed_loop``).

    >>> import exactinv as ei
    >>> from exactinv.interfaces.problem import load_problem
    >>> p = load_problem({"system": {"A": [[0, 1], [0, 0]], "B": [[0], [1]]}, "design": "optimal_gain",
    ...                   "polyhedron": {"G": [[1, 0], [-1, 0], [1, 1], [-1, -1]], "b": [1, 1, 1, 1]},
    ...                   "inputs": {"G": [[1], [-1]], "b": [2, 2]}})
    >>> report = certify(p)
    >>> print("\\n".join(report.lines[:4]))
    problem problem: n = 2, m = 4 inequalities, p = 1 inputs, q = 2 input constraints; design optimal_gain
    optimal gain F = [[0, -1]]  (one LP over (H, F, gamma, Lambda), verified in Q)
    gamma = min over gains of gamma*(A + BF): 1  (the LP dual proves no gain does better)
    largest forward-Euler step over all linear gains: 1 = 1/gamma
    >>> report.ok, report.closed_loop.ok
    (True, True)
    """
    step = progress or (lambda what: None)
    S, P, U = problem.system, problem.polyhedron, problem.inputs
    lines = [f"problem {problem.name}: n = {S.n}, m = {P.m} inequalities, p = {len(problem.B[0])} inputs"
             + (f", q = {U.m} input constraints" if U is not None else ", inputs unconstrained") + "; design optimal_gain"]
    step("the optimal gain (one exact LP)")
    gain = optimal_gain(S, problem.B, P, U)
    if gain.holds:
        lines.append(f"optimal gain F = {matrix_text(gain.F)}  (one LP over (H, F, gamma, Lambda), verified in Q)")
        lines.append(f"gamma = min over gains of gamma*(A + BF): {exact_text(gain.gamma)}  "
                     "(the LP dual proves no gain does better)")
        lines.append(f"largest forward-Euler step over all linear gains: {exact_text(gain.forward_euler_step)} = 1/gamma")
    else:
        lines.append("optimal gain: NONE -- no linear gain u = Fx makes P invariant"
                     + (" with u in U" if U is not None else "") + " (a Farkas certificate proves it)")
    cert = gain.certificate
    report = None
    if check:
        step("independent check (the trusted kernel)")
        report = exactinv_check.check(cert)
        lines.append(f"independent check of the gain: {'VERIFIED' if report.ok else 'REJECTED'} ({len(cert['claims'])} claims)")
    closed = None
    if gain.holds:
        closed = certify(Problem(gain.system, P, method, f"{problem.name} (closed loop)"), method, check, progress)
        lines.append("the closed loop x' = (A + BF)x:")
        lines.extend("  " + line for line in closed.lines)
    undecided = closed.undecided if closed is not None else ()
    return Report(problem, method, (gain,), cert, report, tuple(lines), undecided, closed)
