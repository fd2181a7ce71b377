"""exactinv_check.selftest: the kernel's built-in suite of genuine and forged certificates.

Soundness: every genuine certificate is accepted and every forgery rejected with the verdict kind
it names, from a bare copy of the package under ``python3 -S`` (no exactinv, no site-packages);
the selftest itself can fail (a "forgery" that changes nothing, a genuine certificate broken).
Resources: the suite runs in seconds (no timing assertion; the kernel's own budget applies).
"""

import copy
import io
import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import exactinv_check
from exactinv_check import kernel, selftest
from exactinv_check.format import ClaimType, Verdict

PACKAGE = Path(exactinv_check.__file__).resolve().parent


# ---------------------------------------------------------------------------- soundness
def test_the_selftest_passes_from_a_bare_copy_without_site_packages(tmp_path):
    shutil.copytree(PACKAGE, tmp_path / "exactinv_check", ignore=shutil.ignore_patterns("__pycache__"))
    done = subprocess.run([sys.executable, "-S", "-m", "exactinv_check.selftest"], cwd=tmp_path,
                          capture_output=True, text=True, timeout=600, env={"PATH": "/usr/bin:/bin"})
    assert done.returncode == 0, done.stdout + done.stderr
    total = len(selftest.genuine()) + len(selftest.FORGERIES) + 1
    assert f"{total} of {total} cases behaved, 0 failed" in done.stdout
    assert "FAIL" not in done.stdout


def test_the_genuine_certificates_cover_every_family_and_every_version():
    certificates = selftest.genuine()
    types = {c["type"] for cert in certificates.values() for c in cert["claims"]}
    assert types <= set(ClaimType)
    assert {ClaimType.GAMMA_STAR, ClaimType.POLYNOMIAL_THRESHOLD, ClaimType.RATIONAL_THRESHOLD,
            ClaimType.ABSOLUTE_MONOTONICITY_RADIUS, ClaimType.LARGEST_THRESHOLD, ClaimType.VALID_STEPLENGTHS,
            ClaimType.FORWARD_EULER_THRESHOLD, ClaimType.ELLIPSOID_CONTINUOUS_INVARIANCE,
            ClaimType.ELLIPSOID_LARGEST_THRESHOLD, ClaimType.OPTIMAL_GAIN, ClaimType.ROBUST_THRESHOLD} <= types
    assert {cert["version"] for cert in certificates.values()} == {1, 2, 3}
    routes = {key for cert in certificates.values() for c in cert["claims"] for key in ("box", "lp", "vertices") if key in c}
    assert routes == {"box", "lp", "vertices"}


def test_every_genuine_certificate_is_accepted_and_every_forgery_rejected_as_named():
    certificates = selftest.genuine()
    for name, cert in certificates.items():
        report = kernel.check(copy.deepcopy(cert))
        assert report.ok and report.kind == "accepted", (name, str(report))
    for name, base, _what, mutate, expected in selftest.FORGERIES:
        cert = copy.deepcopy(certificates[base])
        mutate(cert)
        assert cert != certificates[base], f"{name} forges nothing"
        report = kernel.check(cert)
        assert not report.ok and report.kind == expected, (name, report.kind, str(report))


def test_the_selftest_fails_when_a_forgery_is_accepted(monkeypatch):
    """A 'forgery' that changes nothing is accepted: the selftest must say FAIL and count it."""
    monkeypatch.setattr(selftest, "FORGERIES", selftest.FORGERIES + [
        ("no-change", "box-taylor4", "nothing", lambda cert: None, Verdict.REJECTED)])
    out = io.StringIO()
    assert selftest.run(out) == 1
    assert "FAIL forged no-change (nothing): accepted, expected rejected" in out.getvalue()


def test_the_selftest_fails_when_a_genuine_certificate_is_rejected(monkeypatch, tmp_path):
    for p in selftest.DATA.glob("*.json"):
        shutil.copy(p, tmp_path)
    cert = json.loads((tmp_path / "radius-ssprk33.json").read_text())
    cert["claims"][0]["value"] = "2"  # rho of SSP(3,3) is 1
    (tmp_path / "radius-ssprk33.json").write_text(json.dumps(cert))
    monkeypatch.setattr(selftest, "DATA", tmp_path)
    out = io.StringIO()
    assert selftest.run(out) == 1
    assert "FAIL genuine radius-ssprk33: rejected" in out.getvalue()


def test_a_kernel_fault_is_reported_and_never_accepted():
    report = selftest.fault_is_never_accepted(selftest.genuine()["box-taylor4"])
    assert not report.ok and report.kind == "kernel-fault"
    assert "kernel fault" in report.verdicts[0][2] and "TypeError" in report.verdicts[0][2]
    assert "a fault inside the kernel" in str(report)
    assert kernel.CLAIMS[ClaimType.GAMMA_STAR][0] is kernel.HANDLERS[ClaimType.GAMMA_STAR]  # restored


@pytest.mark.parametrize("kind", ["accepted", "kernel-fault", "over-budget", "bad-input"])
def test_a_report_that_is_not_ok_is_never_of_kind_accepted(kind):
    verdicts = [("gamma_star", kind == "accepted", "message")]
    assert kernel.CheckReport(verdicts, kind=kind).kind == kind
    with pytest.raises(ValueError):
        kernel.CheckReport([("gamma_star", kind != "accepted", "message")], kind=kind)


# ---------------------------------------------------------------------------- resources
def test_an_over_budget_forgery_is_over_budget_not_rejected_nor_a_fault():
    cert = copy.deepcopy(selftest.genuine()["box-taylor4"])
    cert["claims"][2]["value"] = selftest.HUGE_ROOT
    report = kernel.check(cert)
    assert report.kind == "over-budget" and "over the kernel's budget" in str(report)
