"""The driver: read a certificate strictly, check its claims in order, report.

A certificate is ``{"format": "exactinv-certificate", "version": 1, 2 or 3,
"problem": {...}, "claims": [...]}``.  Every key is required or optional by
name; an unknown key, a missing key or a value of the wrong JSON type rejects
the claim.  Claims are checked in order and may use what an earlier claim
proved (a threshold uses the gamma* and the radius verified before it); the
context holds only such proved facts, never data the certificate asserts.

The whole certificate shares one work budget (:mod:`exactinv_check.budget`):
every claim is charged to one account, and the kernel stops at the first
rejected claim -- the certificate is rejected then, whatever the later claims
say, and they may depend on the rejected one; they are reported as not checked.
Within a claim, cheap structural checks (keys, types, shapes) come before any
root isolation or elimination.
"""

from __future__ import annotations

import json
import os
from fractions import Fraction
from typing import Any, NoReturn, Sequence

from . import (
    budget,
    claims_control,
    claims_ellipsoid,
    claims_invariance,
    claims_radius,
    claims_sets,
    claims_thresholds,
    ellipsoids,
    poly_arithmetic,
    polys,
)
from .budget import MAX_METHOD_DEGREE
from .cones import integer_rank
from .failure import CheckFailure, OverBudget, Record, require
from .format import (
    BOOLEAN_KEYS,
    ENVELOPE_KEYS,
    FORMAT,
    METHOD_KEYS,
    PROBLEM_KEYS,
    VERSIONS,
    ClaimType,
    Verdict,
    keys_since,
)
from .format import CLAIMS as SPECS
from .rationals import integer_rows, matrix, vector

V2_KEYS = keys_since(1)  # keys version 1 does not have (docs/certificate-format.md)
# the exceptions a claim's check may end in: CheckFailure (and its OverBudget) rejects by design; the resource errors
# are over budget; any other exception is a fault of the kernel (never an accept)
_RESOURCE_ERRORS = (RecursionError, MemoryError)

# claim type -> its check (problem, claim, context) -> message; the keys are format.CLAIMS's
HANDLERS = {
    ClaimType.CONTINUOUS_INVARIANCE: claims_invariance.continuous_invariance,
    ClaimType.DISCRETE_INVARIANCE: claims_invariance.discrete_invariance,
    ClaimType.GAMMA_STAR: claims_invariance.gamma_star,
    ClaimType.POLYNOMIAL_THRESHOLD: claims_thresholds.polynomial_threshold,
    ClaimType.ABSOLUTE_MONOTONICITY_RADIUS: claims_radius.absolute_monotonicity_radius,
    ClaimType.RATIONAL_THRESHOLD: claims_thresholds.rational_threshold,
    ClaimType.LARGEST_THRESHOLD: claims_sets.largest_threshold,
    ClaimType.VALID_STEPLENGTHS: claims_sets.valid_steplengths,
    ClaimType.FORWARD_EULER_THRESHOLD: claims_thresholds.forward_euler_threshold,
    ClaimType.ELLIPSOID_CONTINUOUS_INVARIANCE: claims_ellipsoid.continuous_invariance,
    ClaimType.ELLIPSOID_DISCRETE_INVARIANCE: claims_ellipsoid.discrete_invariance,
    ClaimType.ELLIPSOID_VALID_STEPLENGTHS: claims_ellipsoid.valid_steplengths,
    ClaimType.ELLIPSOID_LARGEST_THRESHOLD: claims_ellipsoid.largest_threshold,
    ClaimType.ELLIPSOID_FORWARD_EULER_THRESHOLD: claims_ellipsoid.forward_euler_threshold,
    ClaimType.OPTIMAL_GAIN: claims_control.optimal_gain,
    ClaimType.ROBUST_THRESHOLD: claims_control.robust_threshold,
}
# claim type -> (handler, required keys, optional keys)
CLAIMS = {kind: (HANDLERS[kind], set(spec.required), set(spec.optional)) for kind, spec in SPECS.items()}


class BadInput(Exception):
    """The input is not a certificate at all (unreadable, not JSON, wrong format)."""


class Method:
    """r = g/h from the problem, normalised to h(0) > 0 (and h = 1 for polynomials)."""

    def __init__(self, record: Any) -> None:
        require(isinstance(record, dict) and set(record) <= set(METHOD_KEYS)
                and set(METHOD_KEYS[1:]) <= set(record), "method has the keys name, numerator, denominator")
        num = poly_arithmetic.trim(vector(record["numerator"], "method numerator"))
        den = poly_arithmetic.trim(vector(record["denominator"], "method denominator"))
        require(den and den[0] != 0, "the method's denominator vanishes at 0")
        require(num and num[0] == den[0], "r(0) != 1")
        require(len(num) - 1 <= MAX_METHOD_DEGREE and len(den) - 1 <= MAX_METHOD_DEGREE,
                f"method degree above the kernel's bound {MAX_METHOD_DEGREE}")
        if den[0] < 0:
            num, den = [-c for c in num], [-c for c in den]
        common = polys.affordable_gcd(num, den) if len(den) > 1 else [Fraction(1)]  # a constant h: coprime
        if len(common) > 1:  # r is the reduced function: a cancelled factor is no pole
            num, den = poly_arithmetic.divmod_(num, common)[0], poly_arithmetic.divmod_(den, common)[0]
            num, den = [c / den[0] for c in num], [c / den[0] for c in den]
        if len(den) == 1:
            num, den = [c / den[0] for c in num], [Fraction(1)]
        require(isinstance(record.get("name", ""), str), "the method's name is a string")
        self.name = record.get("name")
        self.numerator, self.denominator = num, den
        self.is_polynomial = len(den) == 1


class Problem:
    """A, G, b (each shape-checked) and the method; or A, Q (an ellipsoid, Q proved
    symmetric positive definite) and the method; radius certificates have only the method."""

    def __init__(self, record: Any, version: Any = VERSIONS[-1]) -> None:
        self.version = version  # the encoding of H and H~ in the claims (version 3: sparse, exactinv_check/sparse.py)
        require(isinstance(record, dict) and set(record) <= set(PROBLEM_KEYS),
                "problem has the keys A, G, b (or Q), method; B and inputs (a gain); hull, G, b, method (robust)")
        self.method = Method(record["method"]) if record.get("method") is not None else None
        self.Q = self.B = self.hull = None
        self.E, self.e, self.p = [], [], 0
        if "hull" in record:
            self._hull(record)
            return
        require(not {"B", "inputs"} & set(record) or {"A", "G", "b", "B"} <= set(record) and "method" not in record,
                "a gain problem has the keys A, B, G, b (and inputs)")
        if "Q" in record:
            require(set(record) <= {"A", "Q", "method"} and "A" in record, "an ellipsoid problem has the keys A, Q, method")
            self.A = matrix(record["A"], "A")
            self.n = len(self.A)
            require(self.n >= 1 and all(len(r) == self.n for r in self.A), "A is not a nonempty square matrix")
            require(self.n <= budget.MAX_DEGREE, f"an ellipsoid problem has dimension at most {budget.MAX_DEGREE} "
                    f"(every condition claim needs n (2s - 1) <= {budget.MAX_DEGREE}), not {self.n}")
            self.Q = matrix(record["Q"], "Q", self.n, self.n)
            require(ellipsoids.is_symmetric(self.Q), "Q is not symmetric")
            require(ellipsoids.psd(self.Q)[1], "Q is not positive definite: {x : x^T Q x <= 1} is no ellipsoid")
            self.G = self.b = None
            self.m = 0
        elif {"A", "G", "b"} & set(record):
            require({"A", "G", "b"} <= set(record), "problem needs all of A, G, b")
            self.A = matrix(record["A"], "A")
            self.n = len(self.A)
            require(self.n >= 1 and all(len(r) == self.n for r in self.A), "A is not a nonempty square matrix")
            self.G = matrix(record["G"], "G", cols=self.n)
            self.m = len(self.G)
            self.b = vector(record["b"], "b", self.m)
            require(all(any(row) for row in self.G), "G has a zero row (void or infeasible; exactinv never writes one)")
        else:
            self.A = self.G = self.b = None
            self.n = self.m = 0
        if "B" in record:
            self.B = matrix(record["B"], "B", self.n)
            self.p = len(self.B[0]) if self.B else 0
            require(self.p >= 1, "B has no column")
            if "inputs" in record:
                U = record["inputs"]
                require(isinstance(U, dict) and set(U) == {"E", "e"}, "inputs has the keys E, e")
                self.E = matrix(U["E"], "inputs E", cols=self.p)
                self.e = vector(U["e"], "inputs e", len(self.E))
                require(self.E and all(any(row) for row in self.E), "inputs E is empty or has a zero row")

    def _hull(self, record: Any) -> None:
        """conv{A_1, ..., A_k} on P = {x : Gx <= b}: the vertices, G, b and the method."""
        require(set(record) <= {"hull", "G", "b", "method"} and {"G", "b"} <= set(record),
                "a robust problem has the keys hull, G, b, method")
        require(isinstance(record["hull"], list) and record["hull"], "hull is a nonempty list of matrices")
        self.G = matrix(record["G"], "G")
        self.m = len(self.G)
        self.n = len(self.G[0]) if self.G else 0
        require(self.m >= 1 and self.n >= 1, "G is empty")
        self.b = vector(record["b"], "b", self.m)
        require(all(any(row) for row in self.G), "G has a zero row (void or infeasible; exactinv never writes one)")
        self.hull = [matrix(A, f"hull[{i}]", self.n, self.n) for i, A in enumerate(record["hull"])]  # type: ignore[assignment]
        self.A = None
        # fraction-free and charged as it runs (a Fraction Gauss-Jordan here ran minutes uncharged on a 400 x 200 G)
        self.lines_possible = integer_rank([g for g, _ in integer_rows(self.G, self.b)], self.n) < self.n


class CheckReport:
    """The verdict per claim, and on the whole certificate.

    ``ok`` is True only if there is a claim and every claim verified.  ``kind`` (a
    :class:`exactinv_check.format.Verdict`, a string) says which outcome: ``"accepted"`` (ok),
    ``"rejected"`` (a claim is wrong or the kernel could not prove it), ``"over-budget"`` (a claim
    would cost more than the kernel's work or time budget), ``"kernel-fault"`` (an unexpected
    exception inside the kernel: a kernel bug, reported and never accepted) or ``"bad-input"``
    (not a certificate at all)."""

    def __init__(self, verdicts: Any, bad_input: Any=False, work: Any=0, kind: Any=None) -> None:
        self.verdicts = verdicts  # list of (claim type, ok, message)
        self.bad_input = bad_input
        self.work = work  # the certificate's charged work, in word operations (exactinv_check.budget)
        if kind is None:
            kind = Verdict.BAD_INPUT if bad_input else Verdict.ACCEPTED if self.ok else Verdict.REJECTED
        kind = Verdict(kind)
        if (kind == Verdict.ACCEPTED) != self.ok:  # a fault, an overdraft or a bad input is never accepted
            raise ValueError(f"a report of kind {kind!r} with ok = {self.ok}")
        self.kind = kind

    @property
    def ok(self) -> bool:
        return bool(self.verdicts) and all(ok for _, ok, _ in self.verdicts)

    def __bool__(self) -> Any:
        return self.ok

    def __str__(self) -> str:
        lines = [f"[{'ok' if ok else 'REJECTED'}] {kind}: {msg}" for kind, ok, msg in self.verdicts]
        last = {Verdict.ACCEPTED: "certificate VERIFIED",
                Verdict.OVER_BUDGET: "certificate REJECTED (over the kernel's budget)",
                Verdict.KERNEL_FAULT: "certificate REJECTED (a fault inside the kernel, not a verdict on the "
                                      "certificate: please report it)"}
        lines.append(last.get(self.kind, "certificate REJECTED"))
        return "\n".join(lines)

    __repr__ = __str__


def load(certificate: Any) -> Any:
    """A certificate dict from a dict, a JSON string or a path; BadInput otherwise."""
    if isinstance(certificate, dict):
        return certificate
    if not isinstance(certificate, (str, os.PathLike)):
        raise BadInput(f"expected a certificate dict, JSON text or a path, got {type(certificate).__name__}")
    strict = {"parse_float": _no_float, "parse_constant": _no_float, "object_pairs_hook": _no_duplicates}
    try:
        if isinstance(certificate, str) and certificate.lstrip().startswith("{"):
            data = json.loads(certificate, **strict)  # type: ignore[arg-type]
        else:
            with open(certificate, encoding="utf-8") as fh:
                data = json.load(fh, **strict)  # type: ignore[arg-type]
    except OSError as exc:
        raise BadInput(f"cannot read {certificate!r}: {exc}") from None
    except (ValueError, CheckFailure, RecursionError) as exc:
        raise BadInput(f"not valid JSON: {type(exc).__name__}: {exc}") from None
    if not isinstance(data, dict):
        raise BadInput("a certificate is a JSON object")
    return data


def _no_duplicates(pairs: Sequence[tuple[str, Any]]) -> Any:
    keys = [k for k, _ in pairs]
    if len(set(keys)) != len(keys):
        raise CheckFailure(f"duplicate JSON keys {sorted({k for k in keys if keys.count(k) > 1})}: ambiguous")
    return dict(pairs)


def _no_float(text: str) -> NoReturn:
    raise CheckFailure(f"the JSON number {text} is not exact: certificates write numbers as strings")


def _check_keys(claim: Any, kind: Any, version: Any) -> None:
    _, required, optional = CLAIMS[kind]
    keys = set(claim) - {"type"}
    require(required <= keys, f"missing keys {sorted(required - keys)}")
    require(keys <= required | optional, f"unknown keys {sorted(keys - required - optional)}")
    newer = keys & V2_KEYS.get(kind, set())
    require(version >= 2 or not newer, f"the keys {sorted(newer)} belong to certificate version 2, not {version}")
    for key in BOOLEAN_KEYS & keys:
        require(isinstance(claim[key], bool), f"{key} must be a JSON boolean")


def check(certificate: Any, progress: Any = None, time_limit: Any = budget.TIME_LIMIT) -> CheckReport:
    """Re-verify a certificate (a dict, a JSON string or a path to a JSON file).

    Returns a :class:`CheckReport`, truthy only if every claim was proved.
    ``progress(k, total, claim_type)``, if given, is called before each claim.
    The whole certificate shares one work budget (budget.CERTIFICATE_BUDGET word
    operations) and, as a safety net, ``time_limit`` seconds (None: no clock)."""
    try:
        cert = load(certificate)
    except BadInput as exc:
        return CheckReport([("input", False, str(exc))], bad_input=True)
    if cert.get("format") != FORMAT:
        return CheckReport([("input", False, "not an exactinv certificate (format is missing or wrong)")], bad_input=True)
    with budget.account(time_limit=time_limit) as account:
        verdicts, kind = _check_claims(cert, progress)
    return CheckReport(verdicts, work=account.spent, kind=kind)


def _outcome(exc: Any) -> Any:
    """(verdict kind, message) of the exception that ended a claim's check."""
    if isinstance(exc, OverBudget):
        return Verdict.OVER_BUDGET, str(exc)
    if isinstance(exc, CheckFailure):
        return Verdict.REJECTED, str(exc)
    if isinstance(exc, _RESOURCE_ERRORS):
        return Verdict.OVER_BUDGET, f"{type(exc).__name__}: {exc}"
    return Verdict.KERNEL_FAULT, f"kernel fault (a bug in the kernel, please report it): {type(exc).__name__}: {exc}"


def _check_claims(cert: Any, progress: Any) -> Any:
    """The verdicts and the certificate's verdict kind: the problem, then the claims in order, stopping at
    the first rejected one."""
    try:
        require(set(cert) == set(ENVELOPE_KEYS), "a certificate has exactly the keys "
                "format, version, problem, claims")
        require(type(cert["version"]) is int and cert["version"] in VERSIONS,
                f"unsupported certificate version {cert['version']!r}")
        problem = Problem(cert["problem"], cert["version"])
        require(isinstance(cert["claims"], list) and cert["claims"], "the certificate makes no claim")
    except Exception as exc:  # noqa: BLE001 -- every exception is a verdict: rejected, over budget or a kernel fault
        kind, message = _outcome(exc)
        return [("problem", False, message if kind == Verdict.KERNEL_FAULT else f"{type(exc).__name__}: {exc}")], kind
    context: dict[str, Any] = {}
    verdicts: list[Any] = []
    claims = cert["claims"]
    for k, claim in enumerate(claims):
        kind = claim.get("type", "?") if isinstance(claim, dict) else "?"
        kind = kind if isinstance(kind, str) else repr(kind)[:40]
        if progress is not None:
            progress(k, len(claims), kind)
        try:
            require(kind in CLAIMS, f"unknown claim type {kind!r}")
            _check_keys(claim, kind, cert["version"])
            if kind.startswith("ellipsoid_"):
                require(problem.Q is not None, f"a {kind} claim needs A and Q in the problem")
            elif kind == ClaimType.ROBUST_THRESHOLD:
                require(problem.hull is not None, "a robust_threshold claim needs hull, G and b in the problem")
            elif kind != ClaimType.ABSOLUTE_MONOTONICITY_RADIUS:
                require(problem.A is not None and problem.G is not None, f"a {kind} claim needs A, G and b in the problem")
            verdicts.append((kind, True, CLAIMS[kind][0](problem, Record(claim), context)))  # type: ignore[index]
        except Exception as exc:  # noqa: BLE001 -- as above
            outcome, message = _outcome(exc)
            verdicts.append((kind, False, message))
            for later in claims[k + 1:]:  # stop: the certificate is rejected, and later claims may use this one
                verdicts.append((later.get("type", "?") if isinstance(later, dict) else "?", False,
                                 f"not checked: claim {k} ({kind}) was rejected"))
            return verdicts, outcome
    return verdicts, Verdict.ACCEPTED
