"""The StrEnum tags write the same JSON as the strings they replaced."""

import json
from fractions import Fraction

import pytest

import exactinv as ei
from exactinv.core import tags
from exactinv.core.tags import BisectionStep, CounterexampleKind
from exactinv.lp.hint_types import LPStatus
from exactinv.lp.solver import LPPath
from exactinv.model.record import certificate
from exactinv.thresholds.bisection import paper_bisection
from exactinv_check.format import ClaimType, RadiusReason


def test_tags_are_their_strings():
    for tag in (*ClaimType, *RadiusReason, *BisectionStep, *CounterexampleKind, *LPStatus, *LPPath):
        assert tag == tag.value and json.dumps(tag) == json.dumps(tag.value) and str(tag) == tag.value


def test_certificates_serialise_to_plain_strings():
    S = ei.LinearSystem([[-1, 1], [-1, -1]])
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    result = ei.steplength_threshold(S, P, ei.methods.taylor(2))
    text = json.dumps(certificate(S, P, ei.methods.taylor(2), [result]), sort_keys=True)
    types = [claim["type"] for claim in json.loads(text)["claims"]]
    assert types == ["gamma_star", "polynomial_threshold"]
    assert all(type(t) is str for t in types)


def test_bisection_reports_its_step():
    # f(t) = 1 - t: one sign change at t = 1 (the paper's Step 3 or a bisection step)
    res = paper_bisection([1, -1], epsilon=Fraction(1, 2**10))
    assert res.terminated_by in set(BisectionStep) and isinstance(res.terminated_by, str)


def test_the_moved_tags_are_deprecated_aliases_of_the_formats():
    """ClaimType and RadiusReason live in exactinv_check.format; the old names still work, with a warning."""
    with pytest.warns(DeprecationWarning, match="exactinv_check.format"):
        assert tags.ClaimType is ClaimType
    with pytest.warns(DeprecationWarning, match="exactinv_check.format"):
        assert tags.RadiusReason is RadiusReason
    with pytest.raises(AttributeError):
        tags.NoSuchTag  # noqa: B018 (the attribute access is the test)
