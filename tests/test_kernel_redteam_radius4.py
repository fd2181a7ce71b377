"""Red team (rt-radius4): the radius's coefficient route after line-balance (claims_radius.short_above, SCAN_BUDGET,
DESCARTES_BUDGET) and the rho = 0 witness (claims_radius.sign_at_zero).

Found: sign_at_zero was priced once, up front, and charged nothing while it ran.  Its price was 4 to 5 times low
for coefficients of a few thousand bits: r = A^3 / (A + B z)^3 with 500-digit A, B (an 8.6 KB certificate), witness
c_369(0) < 0, priced 9.9e7 (< WORK_BUDGET) and ran 10 s of CPU; eight such claims ran 55 s of CPU before the verdict,
all of it under the certificate's work account (each claim charged 1e8 of the 2e9), stopped only by the clock.  Now
every step of the recurrence is charged by the sizes of its numbers (claims_radius.step_cost), so the account stops
such a certificate and the clock is read every 64 steps.

Tried without a finding (numbers in the report): short_above's K against claimed rho just below / above / equal to
the true first end, a wrong binding index, an algebraic rho whose interval straddles K (every forgery rejected,
every genuine claim accepted, the values checked against radius_reference).
"""

import json
import os
import resource
import subprocess
import sys
import time
from fractions import Fraction as F
from math import comb
from pathlib import Path

import pytest

from exactinv_check import budget, check
from exactinv_check.budget import WORK_BUDGET
from exactinv_check.claims_radius import sign_at_zero, short_above
from exactinv_check.rationals import CheckFailure

from radius_reference import coefficients_at

ROOT = Path(__file__).resolve().parents[1]


def cube_method(digits):
    """r = A^3 / (A + B z)^3 (A, B of about ``digits`` digits): c_j(0) = C(j+2, 2) (-B/A)^j, of sign (-1)^j."""
    A, B = 10**digits + 7, 10**digits + 3 * 10**(digits - 3) + 1
    return [F(A**3)], [F(A**3), F(3 * A * A * B), F(3 * A * B * B), F(B**3)], A, B


def _witness_cert(digits, js):
    num, den, _, _ = cube_method(digits)
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"method": {"name": "rt4", "numerator": [str(c) for c in num],
                                   "denominator": [str(c) for c in den]}},
            "claims": [{"type": "absolute_monotonicity_radius", "value": "0", "attained": False,
                        "reason": "negative-at-0", "witness_j": j} for j in js]}


def test_sign_at_zero_matches_the_closed_form():
    """The charged recurrence still computes the exact sign: against C(j+2, 2) (-B/A)^j and the reference."""
    num, den, A, B = cube_method(4)
    for j in range(0, 40):
        expected = (-1) ** j
        assert sign_at_zero(num, den, j) == expected
    with budget.account(time_limit=None):
        assert sign_at_zero(num, den, 37) == -1
    c = coefficients_at(num, den, F(0), 12)
    assert all((x > 0) - (x < 0) == (-1) ** j and x == comb(j + 2, 2) * F(-B, A) ** j for j, x in enumerate(c))


def test_sign_at_zero_is_charged_as_it_runs():
    """Before: priced 9.9e7 up front, nothing charged while it ran 10 s (deg h = 3, 1660-digit coefficients,
    j = 369).  With an account of 2 x WORK_BUDGET it ran to the end; now the steps' charges overdraw it early."""
    num, den, _, _ = cube_method(500)
    start = time.process_time()
    with budget.account(limit=2 * WORK_BUDGET, time_limit=None) as acc:
        with pytest.raises(CheckFailure, match="work budget"):
            sign_at_zero(num, den, 369)
    assert acc.spent > 2 * WORK_BUDGET
    assert time.process_time() - start < 8


def test_a_long_witness_is_charged_more_than_its_price():
    """The whole recurrence for j = 1355 with 100-digit coefficients: charged several times its up-front price
    (about 2.4e8 + 1e8 for 7 s of CPU; the up-front price alone was 1e8)."""
    num, den, _, _ = cube_method(100)
    with budget.account(limit=10**12, time_limit=None) as acc:
        assert sign_at_zero(num, den, 1355) == -1
    assert acc.spent > 2 * WORK_BUDGET


@pytest.mark.skipif(not os.environ.get("EXACTINV_FUZZ"), reason="about 40 s: the full-size certificate (EXACTINV_FUZZ=1)")
def test_eight_witness_claims_get_a_verdict_by_the_account(tmp_path):
    """Before: 8.6 KB, eight claims c_369(0), c_367(0)... < 0, 55 s of CPU, stopped by the clock (50 s) only."""
    path = tmp_path / "cert.json"
    path.write_text(json.dumps(_witness_cert(500, [369 - 2 * k for k in range(8)])))
    assert path.stat().st_size < 10**4
    env = {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}

    def limit():
        resource.setrlimit(resource.RLIMIT_CPU, (60, 60))
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    done = subprocess.run([sys.executable, "-m", "exactinv_check", str(path)], capture_output=True, text=True,
                          timeout=300, env=env, preexec_fn=limit)
    used = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - before
    assert done.returncode != 0 and "work budget" in done.stdout + done.stderr, done.stdout[-500:]
    assert used < 45


def test_short_above_is_above_and_short():
    for q in [F(0), F(1, 3), F(2), F(10**50 + 1, 10**49), F(1, 10**40 + 3), F(12345, 1)]:
        k = short_above(q)
        assert k >= q and (q == 0 or k <= q * (1 + F(1, 2**14)))
        assert k.numerator.bit_length() + k.denominator.bit_length() <= max(40, q.numerator.bit_length() + q.denominator.bit_length())
