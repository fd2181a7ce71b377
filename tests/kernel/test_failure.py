"""exactinv_check.failure: a claim that does not verify is a CheckFailure (a rejection), one over a limit an
OverBudget (also a rejection), and any other exception inside a check a kernel fault -- never an acceptance."""

import copy

import pytest

from exactinv_check import kernel, selftest
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
