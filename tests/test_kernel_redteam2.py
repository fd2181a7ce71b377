"""Red-team round 2 against the optimised trusted kernel (exactinv_check).

Each test builds a certificate that the kernel mishandles and asserts the
CORRECT behaviour: a false claim must be rejected, a genuine certificate
accepted, and no input may make ``check`` raise or run (practically) forever.
These tests fail until the kernel is fixed.
"""

import json
import random
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _cert(claims, method=None, A=None, G=None, b=None, version=2):
    problem = {}
    if method is not None:
        num, den = method
        problem["method"] = {"name": "redteam2", "numerator": list(num), "denominator": list(den)}
    if A is not None:
        problem.update(A=A, G=G, b=b)
    return {"format": "exactinv-certificate", "version": version, "problem": problem, "claims": claims}


def _check_in_subprocess(cert, seconds):
    """check(cert) in a child process that is killed after `seconds`; returns its verdict."""
    code = ("import json, sys; from exactinv_check import check; "
            "r = check(json.load(sys.stdin)); print('OK' if r.ok else 'REJECTED')")
    try:
        proc = subprocess.run([sys.executable, "-c", code], input=json.dumps(cert), capture_output=True,
                              text=True, timeout=seconds, cwd=ROOT)
    except subprocess.TimeoutExpired:
        raise AssertionError(f"the kernel did not finish within {seconds} s") from None
    assert proc.returncode == 0, proc.stderr[-2000:]
    return proc.stdout.strip()


# --------------------------------------------------------------------------
# 1. Exact root work on a small, bounded-degree input runs for minutes
#
# MAX_DEGREE = 200 bounds the degree of every polynomial, and MAX_DIGITS =
# 4000 the length of every number, but nothing bounds their PRODUCT.  Parsing
# an algebraic number runs polys.squarefree (an integer primitive-PRS gcd with
# the derivative) and then a full Sturm sequence; with primitive PRS the
# coefficients grow to ~ degree x coefficient-size bits, so the work grows
# like d^4 * bits^2.  Measured on the kernel: degree 200 with 10-digit
# coefficients (a 2.4 KB claim) takes ~80 s; degree 200 with 30-digit or
# degree 100 with 100-digit coefficients (about 10 KB) runs for more than
# 100 s, degree 40 with 1000-digit coefficients spends 67 s in squarefree and
# another 70 s in Sturm.  The claim below is false anyway (rho(1 + z) = 1)
# and must be rejected quickly -- e.g. by a budget on degree x bit size
# before any gcd / Sturm work on certificate-supplied polynomials.

def test_a_bounded_degree_algebraic_number_with_long_coefficients_is_rejected_quickly():
    rng = random.Random(1)
    poly = [str(rng.randint(-10**30, 10**30)) for _ in range(200)] + ["1"]  # degree 200, ~6 KB
    cert = _cert([{"type": "absolute_monotonicity_radius", "value": {"poly": poly, "interval": ["0", "2"]},
                   "reason": "coefficient", "attained": True}],
                 method=(["1", "1"], ["1"]))
    assert _check_in_subprocess(cert, 60) == "REJECTED"


def test_a_forged_threshold_with_long_coefficients_is_rejected_quickly():
    # The same cost reached through a valid_steplengths claim: a forged end
    # (degree 60, 1000-digit coefficients, ~60 KB) about a trivial problem.
    # x' = -x, P = [-1, 1], forward Euler: the valid set is [0, 2].
    rng = random.Random(2)
    poly = [str(rng.randint(-10**1000, 10**1000)) for _ in range(60)] + ["1"]
    cert = _cert([{"type": "valid_steplengths",
                   "intervals": [{"lo": "0", "hi": {"poly": poly, "interval": ["1", "3"]},
                                  "lo_closed": True, "hi_closed": True}],
                   "vertices": [["-1"], ["1"]], "rays": [], "lines": []}],
                 method=(["1", "1"], ["1"]), A=[["-1"]], G=[["1"], ["-1"]], b=["1", "1"])
    assert _check_in_subprocess(cert, 60) == "REJECTED"
