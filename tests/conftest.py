import math
import os
import sys

from hypothesis import HealthCheck, settings

# EXACTINV_DERANDOMIZE=1 (set by .ci/run): every property test draws the same examples on every run, so the
# gate that decides whether a change lands tests exactly what its author ran on a fresh clone.  Without it (a
# developer's run, the README's command) Hypothesis explores new examples each time, as it should.
settings.register_profile(
    "ci",
    max_examples=int(os.environ.get("EXACTINV_EXAMPLES", "25")),
    deadline=None,
    derandomize=os.environ.get("EXACTINV_DERANDOMIZE", "") not in ("", "0"),
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
settings.load_profile("ci")


def pytest_collection_modifyitems(config, items):
    """Tests marked ``heavy`` (tens of seconds each) run first, so that under ``-n auto`` no worker is
    left with one of them at the end while the others idle: CI's wall time is the longest worker's.

    EXACTINV_EXAMPLES_SCALE=s (``.ci/run``'s lowest-versions stage): every property test draws
    max(3, ceil(s * n)) examples instead of its own n (.ci/run: s = 0.1).  That stage checks that the declared lower bounds of
    the dependencies work, not new examples (stage 2 runs them all at full strength)."""
    items.sort(key=lambda item: item.get_closest_marker("heavy") is None)  # stable: the rest keep their order
    scale = float(os.environ.get("EXACTINV_EXAMPLES_SCALE", "1") or "1")
    if scale >= 1:
        return
    for item in items:
        test = getattr(getattr(item, "obj", None), "__func__", getattr(item, "obj", None))
        own = getattr(test, "_hypothesis_internal_use_settings", None)
        if own is not None:
            fewer = max(3, math.ceil(scale * own.max_examples))
            test._hypothesis_internal_use_settings = settings(own, max_examples=min(fewer, own.max_examples))

sys.path.insert(0, os.path.dirname(__file__))  # tests/strategies.py, under --import-mode=importlib


# Every certificate the kernel verifies during the tests must also match the
# documented JSON Schema (docs/certificate.schema.json): the kernel's entry
# point is wrapped here, before any test module (or exactinv) binds it.
import json  # noqa: E402
from pathlib import Path  # noqa: E402

import pytest  # noqa: E402

import exactinv_check  # noqa: E402
import exactinv_check.kernel  # noqa: E402

try:
    import jsonschema  # noqa: E402
except ImportError:  # pragma: no cover - jsonschema comes with nbformat (test extra)
    jsonschema = None

if jsonschema is not None:
    _SCHEMA = json.loads((Path(__file__).parent.parent / "docs" / "certificate.schema.json").read_text())
    _VALIDATOR = jsonschema.Draft202012Validator(_SCHEMA)
    _kernel_check = exactinv_check.kernel.check

    def _check_and_validate(certificate, progress=None):
        report = _kernel_check(certificate, progress)
        if report.ok:
            cert = exactinv_check.kernel.load(certificate)
            problems = sorted(_VALIDATOR.iter_errors(cert), key=str)
            assert not problems, f"a verified certificate does not match the schema: {problems[0].message}"
        return report

    _check_and_validate.__doc__ = _kernel_check.__doc__
    _check_and_validate.unvalidated = _kernel_check  # the kernel alone (a test of a huge certificate skips the schema)
    exactinv_check.check = exactinv_check.kernel.check = _check_and_validate


@pytest.fixture
def forced(monkeypatch):
    """Pruning always applied, however many pairs survive (tests/test_pruning*.py)."""
    monkeypatch.setattr("exactinv.conditions.pruning.WORTHWHILE", 1.0)
