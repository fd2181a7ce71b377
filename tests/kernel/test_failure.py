"""exactinv_check.failure: a claim that does not verify is a CheckFailure (a rejection), one over a limit an
OverBudget (also a rejection), and any other exception inside a check a kernel fault -- never an acceptance."""

import copy
import json

import pytest
from certificate_corpus import corpus

from exactinv_check import check, kernel, selftest
from exactinv_check.failure import CheckFailure, OverBudget, Record, require, require_budget
from exactinv_check.format import Verdict


# ------------------------------------------------------------------ soundness
def test_require_raises_only_when_the_condition_fails():
    require(True, "unused")
    with pytest.raises(CheckFailure, match="the fact that failed"):
        require(False, "the fact that failed")


def test_a_missing_key_of_a_claim_is_a_rejection_not_a_key_error():
    claim = Record({"type": "gamma_star"})
    assert claim["type"] == "gamma_star" and claim.get("H") is None
    with pytest.raises(CheckFailure, match="'H'"):
        claim["H"]


def test_an_unexpected_exception_is_a_kernel_fault_and_never_accepted():
    report = selftest.fault_is_never_accepted(selftest.genuine()["box-taylor4"])
    assert not report.ok and report.kind == Verdict.KERNEL_FAULT
    assert kernel.check(copy.deepcopy(selftest.genuine()["box-taylor4"])).ok  # the handler was put back


# ------------------------------------------------------------------ resources
def test_a_limit_is_a_rejection_of_its_own_kind():
    assert issubclass(OverBudget, CheckFailure)  # a budget rejection is never mistaken for a kernel fault
    require_budget(True, "unused")
    with pytest.raises(OverBudget, match="too much work"):
        require_budget(False, "too much work")


# Messages are built only when a check fails (a verifying claim never pays for them), and a failing
# claim still says which numbers disagree.

def test_a_passing_requirement_never_builds_its_message():
    def message():
        raise AssertionError("built although the condition holds")

    require(True, message)
    require(1 == 1, message)


@pytest.mark.parametrize("message", ["plain text", lambda: "plain text"])
def test_a_failing_requirement_says_its_message(message):
    with pytest.raises(CheckFailure, match="^plain text$"):
        require(False, message)


def _claim(cert, kind):
    return next(c for c in cert["claims"] if c["type"] == kind)


def test_a_wrong_forward_euler_step_is_rejected_with_both_numbers():
    """Box, Taylor-4: the largest forward-Euler step is 1 (= 1/gamma*); claimed 2, the message names both."""
    cert = copy.deepcopy(corpus()["box-taylor4-listed"])
    assert check(cert).ok
    claim = _claim(cert, "forward_euler_threshold")
    assert claim["value"] == "1"
    claim["value"] = "2"
    text = str(check(json.loads(json.dumps(cert))))
    assert "[REJECTED] forward_euler_threshold: the largest forward-Euler step is 1, not 2" in text, text


def test_a_wrong_largest_threshold_is_rejected_with_both_numbers():
    """Box, Taylor-4: the genuine largest threshold is the root of x^4 - 6x^2 + 12x - 12 in
    [1.749685831459, 1.74968583146] (an algebraic number: p(1.7) < 0 < p(1.8)); claimed 2, the
    message prints the true value to its certified digits."""
    cert = copy.deepcopy(corpus()["box-taylor4-listed"])
    claim = _claim(cert, "largest_threshold")
    assert claim["value"]["poly"] == ["-12", "12", "-6", "0", "1"]
    claim["value"], claim["binding"] = "2", None
    text = str(check(json.loads(json.dumps(cert))))
    assert "[REJECTED] largest_threshold: the largest threshold is 1.749685831459" in text, text
    assert "x^4 - 6x^2 + 12x - 12" in text and text.count("not 2") == 1, text
