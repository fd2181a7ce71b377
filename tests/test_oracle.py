import csv
import math
from fractions import Fraction
from pathlib import Path

import pytest

import exactinv as ei
from exactinv import oracle
from exactinv.cli import main

S = ei.LinearSystem([[-1, 1], [-1, -1]])
P = ei.Polyhedron.box([-1, -1], [1, 1])
T2 = ei.methods.taylor(2)
ROOT = Path(__file__).parent.parent


def test_threshold_verdicts():
    assert oracle.judge_threshold(S, P, T2, 1.0).status == "valid"
    assert oracle.judge_threshold(S, P, T2, 1.41421356237).status == "tight"
    bad = oracle.judge_threshold(S, P, T2, math.sqrt(2))  # the double sqrt(2) is above sqrt(2)
    assert bad.status == "invalid" and not bad
    dt, x = bad.counterexample["dt"], bad.counterexample["x"]
    assert dt <= Fraction(math.sqrt(2)) and not ei.discrete_invariance(S, P, T2, dt).holds
    assert P.contains(x)
    with pytest.raises(ei.InvalidInput):
        oracle.judge_threshold(S, P, T2, float("nan"))


def test_erratum_e3_caught_by_the_oracle():
    """The paper's float bisection returns inf for f(t) = 1 - t; the pipeline built on it claims tau = inf."""
    from exactinv.thresholds.bisection import paper_bisection_float

    claimed = float(paper_bisection_float(["1", "-1"]).tau)  # f_1 of Taylor(2) at gamma = 1, normalised
    assert claimed == math.inf
    v = oracle.judge_threshold(S, P, T2, claimed)
    assert v.status == "invalid" and v.counterexample is not None


def test_not_attained_end_is_invalid():
    S2, O = ei.LinearSystem([[-1, 2], [0, 1]]), ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
    v = oracle.judge_threshold(S2, O, ei.methods.backward_euler(), 1.0)
    assert v.status == "invalid" and v.counterexample["singular"]


def test_gamma_root_radius():
    assert oracle.judge_gamma(S, P, 1.0).status == "tight"
    assert oracle.judge_gamma(S, P, 1.5).status == "valid"
    low = oracle.judge_gamma(S, P, 0.5)
    assert low.status == "invalid" and low.counterexample["dt"] == 2
    assert oracle.judge_root([1, -1], 0.5).status == "valid"
    assert oracle.judge_root([1, -1], math.inf).status == "invalid"
    assert oracle.judge_radius(ei.methods.trapezoid(), 2.0).status == "tight"
    assert oracle.judge_radius(ei.methods.trapezoid(), 2.5).status == "invalid"


def test_assert_threshold_helper():
    oracle.assert_threshold(S, P, T2, 1.0)
    with pytest.raises(AssertionError, match="exceeds"):
        oracle.assert_threshold(S, P, T2, 1.5)
    with pytest.raises(AssertionError):
        oracle.assert_threshold(S, P, T2, 1.0, require_tight=True)


def test_cli_oracle_on_the_worked_example(capsys):
    path = ROOT / "examples" / "oracle" / "paper_float_results.csv"
    rows = list(csv.DictReader(path.open()))
    assert any(r["claimed"] == "inf" for r in rows)
    assert main(["oracle", str(path)]) == 1  # invalid results found
    out = capsys.readouterr().out
    assert "INVALID" in out and "TIGHT" in out and "leaves P through facet" in out


def test_cli_explain(tmp_path, capsys):
    cert = tmp_path / "c.json"
    assert main(["certify", str(ROOT / "examples" / "erratum_e2_backward_euler.json"), "-o", str(cert)]) == 0
    capsys.readouterr()
    assert main(["explain", str(cert)]) == 0
    text = capsys.readouterr().out
    assert "LP duality" in text and "erratum E2" in text and "not attained" in text
