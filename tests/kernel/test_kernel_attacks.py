"""exactinv_check.kernel, attacked: input the driver must refuse, exceptions that must not escape, a reducible g/h.

Each test builds a certificate by hand that the kernel mishandles and asserts
the CORRECT behaviour: a false claim must be rejected, and no input may make
``check`` raise or run (practically) forever.  These tests fail until the
kernel is fixed.
"""


import json
import resource
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from exactinv_check import check

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


ROOT = Path(__file__).resolve().parents[2]


def _cert(claims, method=None, A=None, G=None, b=None, version=2):
    problem = {}
    if method is not None:
        num, den = method
        problem["method"] = {"name": "redteam", "numerator": list(num), "denominator": list(den)}
    if A is not None:
        problem.update(A=A, G=G, b=b)
    return {"format": "exactinv-certificate", "version": version, "problem": problem, "claims": claims}


def _check_in_subprocess(cert, seconds):
    """check(cert) in a child process limited to ``seconds`` of CPU time (RLIMIT_CPU:
    the machine's load does not count against it); returns its report text."""
    code = ("import json, sys; from exactinv_check import check; "
            "r = check(json.load(sys.stdin)); print('OK' if r.ok else 'REJECTED')")

    def cpu_limit():
        resource.setrlimit(resource.RLIMIT_CPU, (seconds, seconds + 1))

    try:
        proc = subprocess.run([sys.executable, "-c", code], input=json.dumps(cert), capture_output=True,
                              text=True, timeout=30 * seconds + 60, cwd=ROOT, preexec_fn=cpu_limit)
    except subprocess.TimeoutExpired:
        raise AssertionError(f"the kernel did not finish (CPU limit {seconds} s, wall limit passed)") from None
    if proc.returncode in (-signal.SIGXCPU, -signal.SIGKILL):
        raise AssertionError(f"the kernel did not finish within {seconds} s of CPU time")
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc.stdout.strip()


REMOVABLE = (["1", "0", "-1"], ["1", "-1"])  # (1 - z^2)/(1 - z) = 1 + z: forward Euler


# ------------------------------------------------------------------ soundness

def test_removable_singularity_is_not_a_hole_in_the_valid_set():
    # Same problem: the valid set is [0, oo); dt = 1 is valid (A_d = 2).
    cert = _cert([{"type": "valid_steplengths",
                   "intervals": [{"lo": "0", "hi": "1", "lo_closed": True, "hi_closed": False},
                                 {"lo": "1", "hi": "oo", "lo_closed": False, "hi_closed": False}],
                   "vertices": [["0"]], "rays": [["1"]], "lines": []}],
                 method=REMOVABLE, A=[["1"]], G=[["-1"]], b=["0"])
    assert not check(cert).ok


def test_removable_singularity_does_not_bound_the_radius():
    # r(z) = (1 + z)/(1 - z^2) = 1/(1 - z): backward Euler, rho = oo (the engine
    # says oo, reason "product").  z = -1 is NOT a pole of r and every
    # c_j(kappa) = (1 + kappa)^(-j-1) > 0, yet the kernel proves "rho = 1, not
    # attained" (it reads the root of the cancelled factor 1 + z as a pole at
    # -kappa = -1, and d_0 = c_0 h(-kappa) = 1 - kappa changes sign there).
    cert = _cert([{"type": "absolute_monotonicity_radius", "value": "1", "reason": "coefficient",
                   "attained": False}],
                 method=(["1", "1"], ["1", "0", "-1"]))
    assert not check(cert).ok


def test_deeply_nested_json_does_not_escape_check():
    # json.loads raises RecursionError on deep nesting; load() only catches
    # OSError/TypeError/ValueError/CheckFailure, so the RecursionError escapes
    # check() instead of giving a bad-input report.
    text = ('{"format": "exactinv-certificate", "version": 2, "problem": '
            + "[" * 100_000 + "]" * 100_000 + ', "claims": []}')
    report = check(text)  # must not raise
    assert not report.ok


def test_duplicate_json_keys_are_rejected():
    # The kernel promises to read a certificate strictly, but json.loads keeps
    # the LAST of duplicate keys silently.  This file states the false
    # "rho(1 + z) = oo" first and the true "1" second; the kernel verifies it,
    # while a reader or a parser that keeps the first key sees a false claim
    # in a VERIFIED certificate.  A duplicate key must reject the certificate.
    text = ('{"format": "exactinv-certificate", "version": 2, '
            '"problem": {"method": {"name": "fe", "numerator": ["1", "1"], "denominator": ["1"]}}, '
            '"claims": [{"type": "absolute_monotonicity_radius", "value": "oo", "value": "1", '
            '"reason": "coefficient", "attained": true}]}')
    assert not check(text).ok


# ------------------------------------------------------------------ resource

def test_removable_singularity_is_not_a_largest_threshold():
    # x' = x on P = {x >= 0} with r(z) = 1 + z: A_d = 1 + dt >= 0 maps P into P
    # for EVERY dt >= 0, so the largest threshold is oo (the engine says oo).
    # The kernel accepts "1, not attained" (h(dt A) = 1 - dt is singular at 1,
    # but r(A) = 1 + A = 2 exists and is valid).
    cert = _cert([{"type": "largest_threshold", "value": "1", "attained": False,
                   "vertices": [["0"]], "rays": [["1"]], "lines": []}],
                 method=REMOVABLE, A=[["1"]], G=[["-1"]], b=["0"])
    assert not check(cert).ok


def test_a_huge_claimed_radius_does_not_escape_check():
    # r = 1/((1 - z)(1 + z^2/4)): a positive pole 1 and poles +-2i, so the tail
    # needs the dominance certificate on [0, K], K = the claimed rho.  With
    # rho = 10^400 (false: the true rho is about 1.39) the float hint in
    # tail._ratio_bound computes float(K) and raises OverflowError, which
    # check() does not catch.
    cert = _cert([{"type": "absolute_monotonicity_radius", "value": "1" + "0" * 400,
                   "reason": "coefficient", "attained": True}],
                 method=(["1"], ["1", "-1", "1/4", "-1/4"]))
    report = check(cert)  # must not raise
    assert not report.ok


def test_an_algebraic_number_of_huge_degree_is_rejected_quickly():
    # Real.algebraic computes the squarefree part (a gcd with the derivative,
    # O(d^4)-ish in Fractions) BEFORE Sturm enforces MAX_DEGREE = 400.  A 6 KB
    # claim with a degree-3000 polynomial keeps the kernel busy for days
    # (degree 400 already takes ~45 s).  The claim is false anyway (rho of
    # 1 + z is 1), so it must be rejected -- and quickly.
    poly = [str((7 * k) % 19 - 9) for k in range(3000)] + ["1"]
    cert = _cert([{"type": "absolute_monotonicity_radius", "value": {"poly": poly, "interval": ["0", "2"]},
                   "reason": "coefficient", "attained": True}],
                 method=(["1", "1"], ["1"]))
    assert _check_in_subprocess(cert, 30) == "REJECTED"
