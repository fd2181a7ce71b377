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
    polys,
)
from .cones import integer_rank
from .failure import CheckFailure, require
from .rationals import integer_rows, matrix, vector

FORMAT = "exactinv-certificate"
VERSIONS = (1, 2, 3)  # 3: H and H~ sparse (exactinv_check/sparse.py); the engine writes 3
# keys version 1 does not have (docs/certificate-format.md)
V2_KEYS = {"discrete_invariance": {"dt"}, "absolute_monotonicity_radius": {"poles"}}
MAX_METHOD_DEGREE = 64
_ERRORS = (CheckFailure, KeyError, TypeError, ValueError, ZeroDivisionError, IndexError, AttributeError,
           RecursionError, OverflowError, MemoryError)

# claim type -> (handler, required keys, optional keys)
CLAIMS = {
    "continuous_invariance": (claims_invariance.continuous_invariance, {"holds"}, {"H", "witness"}),
    "discrete_invariance": (claims_invariance.discrete_invariance, {"holds"}, {"Ad", "dt", "H", "witness"}),
    "gamma_star": (claims_invariance.gamma_star, {"value"}, {"paths", "H", "binding_row", "dual", "witness", "rows"}),
    "polynomial_threshold": (claims_thresholds.polynomial_threshold, {"value"}, {"binding", "f"}),
    "absolute_monotonicity_radius": (claims_radius.absolute_monotonicity_radius, {"value", "reason", "attained"},
                                     {"binding", "witness_j", "tail_index", "d", "pole", "poles"}),
    "rational_threshold": (claims_thresholds.rational_threshold, {"value", "attained", "rho"},
                           {"pole", "alpha", "H", "gamma_H"}),
    "largest_threshold": (claims_sets.largest_threshold, {"value", "attained"},
                          {"vertices", "rays", "lines", "box", "lp", "determinant", "binding", "pruning"}),
    "valid_steplengths": (claims_sets.valid_steplengths, {"intervals"},
                          {"vertices", "rays", "lines", "box", "lp", "determinant", "pruning"}),
    "forward_euler_threshold": (claims_thresholds.forward_euler_threshold, {"value", "vertices", "rays", "lines"},
                                {"attained"}),
    "ellipsoid_continuous_invariance": (claims_ellipsoid.continuous_invariance, {"holds"}, {"witness"}),
    "ellipsoid_discrete_invariance": (claims_ellipsoid.discrete_invariance, {"holds"}, {"Ad", "dt", "witness"}),
    "ellipsoid_valid_steplengths": (claims_ellipsoid.valid_steplengths, {"intervals"}, {"determinant"}),
    "ellipsoid_largest_threshold": (claims_ellipsoid.largest_threshold, {"value", "attained"}, {"determinant", "binding"}),
    "ellipsoid_forward_euler_threshold": (claims_ellipsoid.forward_euler_threshold, {"value"}, set()),
    "optimal_gain": (claims_control.optimal_gain, {"holds", "value"}, {"F", "H", "Lambda", "dual", "farkas", "x"}),
    "robust_threshold": (claims_control.robust_threshold, {"value", "attained", "gamma", "rho", "forward_euler",
                                                           "vertices", "x"}, {"beta", "v"}),
}
_BOOLEAN_KEYS = {"holds", "attained"}


class BadInput(Exception):
    """The input is not a certificate at all (unreadable, not JSON, wrong format)."""


class Method:
    """r = g/h from the problem, normalised to h(0) > 0 (and h = 1 for polynomials)."""

    def __init__(self, record: Any) -> None:
        require(isinstance(record, dict) and set(record) <= {"name", "numerator", "denominator"}
                and {"numerator", "denominator"} <= set(record), "method has the keys name, numerator, denominator")
        num = polys.trim(vector(record["numerator"], "method numerator"))
        den = polys.trim(vector(record["denominator"], "method denominator"))
        require(den and den[0] != 0, "the method's denominator vanishes at 0")
        require(num and num[0] == den[0], "r(0) != 1")
        require(len(num) - 1 <= MAX_METHOD_DEGREE and len(den) - 1 <= MAX_METHOD_DEGREE,
                f"method degree above the kernel's bound {MAX_METHOD_DEGREE}")
        if den[0] < 0:
            num, den = [-c for c in num], [-c for c in den]
        common = polys.affordable_gcd(num, den) if len(den) > 1 else [Fraction(1)]  # a constant h: coprime
        if len(common) > 1:  # r is the reduced function: a cancelled factor is no pole
            num, den = polys.divmod_(num, common)[0], polys.divmod_(den, common)[0]
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
        require(isinstance(record, dict) and set(record) <= {"A", "B", "inputs", "hull", "G", "b", "Q", "method"},
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
            require(self.n <= polys.MAX_DEGREE, f"an ellipsoid problem has dimension at most {polys.MAX_DEGREE} "
                    f"(every condition claim needs n (2s - 1) <= {polys.MAX_DEGREE}), not {self.n}")
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
    """The verdict per claim; ``ok`` is True only if there is a claim and every claim verified."""

    def __init__(self, verdicts: Sequence[tuple[Any, bool, str]], bad_input: bool = False, work: int = 0) -> None:
        self.verdicts = verdicts  # list of (claim type, ok, message)
        self.bad_input = bad_input
        self.work = work  # the certificate's charged work, in word operations (exactinv_check.budget)

    @property
    def ok(self) -> bool:
        return bool(self.verdicts) and all(ok for _, ok, _ in self.verdicts)

    def __bool__(self) -> Any:
        return self.ok

    def __str__(self) -> str:
        lines = [f"[{'ok' if ok else 'REJECTED'}] {kind}: {msg}" for kind, ok, msg in self.verdicts]
        lines.append("certificate VERIFIED" if self.ok else "certificate REJECTED")
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
    for key in _BOOLEAN_KEYS & keys:
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
        verdicts = _check_claims(cert, progress)
    return CheckReport(verdicts, work=account.spent)


def _check_claims(cert: Any, progress: Any) -> Any:
    """The verdicts: the problem, then the claims in order, stopping at the first rejected one."""
    try:
        require(set(cert) == {"format", "version", "problem", "claims"}, "a certificate has exactly the keys "
                "format, version, problem, claims")
        require(type(cert["version"]) is int and cert["version"] in VERSIONS,
                f"unsupported certificate version {cert['version']!r}")
        problem = Problem(cert["problem"], cert["version"])
        require(isinstance(cert["claims"], list) and cert["claims"], "the certificate makes no claim")
    except _ERRORS as exc:
        return [("problem", False, f"{type(exc).__name__}: {exc}")]
    context: dict[str, Any] = {}
    verdicts: list[Any] = []
    claims = cert["claims"]
    for k, claim in enumerate(claims):
        kind = claim.get("type", "?") if isinstance(claim, dict) else "?"
        if progress is not None:
            progress(k, len(claims), kind)
        try:
            require(kind in CLAIMS, f"unknown claim type {kind!r}")
            _check_keys(claim, kind, cert["version"])
            if kind.startswith("ellipsoid_"):
                require(problem.Q is not None, f"a {kind} claim needs A and Q in the problem")
            elif kind == "robust_threshold":
                require(problem.hull is not None, "a robust_threshold claim needs hull, G and b in the problem")
            elif kind != "absolute_monotonicity_radius":
                require(problem.A is not None and problem.G is not None, f"a {kind} claim needs A, G and b in the problem")
            verdicts.append((kind, True, CLAIMS[kind][0](problem, claim, context)))
        except _ERRORS as exc:
            verdicts.append((kind, False, f"{exc}" if isinstance(exc, CheckFailure) else f"{type(exc).__name__}: {exc}"))
            for later in claims[k + 1:]:  # stop: the certificate is rejected, and later claims may use this one
                verdicts.append((later.get("type", "?") if isinstance(later, dict) else "?", False,
                                 f"not checked: claim {k} ({kind}) was rejected"))
            break
    return verdicts
