"""Ellipsoids through the interfaces: problem files, `exactinv certify / check /
explain`, the pipeline, the oracle."""

import json
from fractions import Fraction
from pathlib import Path

import pytest

import exactinv as ei
from exactinv.cli import main
from exactinv.interfaces.pipeline import certify
from exactinv.interfaces.problem import load_problem

EXAMPLE = Path(__file__).resolve().parent.parent / "examples" / "ellipsoid_disc_taylor2.json"


def test_the_example_problem_loads_as_an_ellipsoid():
    p = load_problem(EXAMPLE)
    assert p.is_ellipsoid and p.polyhedron == ei.Ellipsoid([[1, 0], [0, 1]]) and p.method.name == "taylor(2)"


def test_certify_check_and_explain_an_ellipsoid(tmp_path, capsys):
    out = tmp_path / "cert.json"
    assert main(["certify", str(EXAMPLE), "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "largest forward-Euler step on E: 2/5" in text and "VERIFIED" in text
    cert = json.loads(out.read_text())
    assert cert["problem"]["Q"] == [["1", "0"], ["0", "1"]]
    assert {c["type"] for c in cert["claims"]} == {"ellipsoid_continuous_invariance", "ellipsoid_forward_euler_threshold",
                                                   "ellipsoid_largest_threshold", "ellipsoid_valid_steplengths"}
    assert main(["check", str(out)]) == 0
    assert main(["explain", str(out)]) == 0
    assert "E = {x : x^T Q x <= 1}" in capsys.readouterr().out


def test_a_non_invariant_ellipsoid_is_reported_with_its_witness():
    p = load_problem({"system": {"A": [["-1", "3"], ["0", "-1"]]}, "ellipsoid": {"Q": [["1", "0"], ["0", "1"]]}})
    report = certify(p)
    assert report.ok and any("FAILS" in line and "v = [3/2, 1]" in line for line in report.lines)


@pytest.mark.parametrize("ellipsoid, match", [({"Q": [["1", "2"], ["2", "1"]]}, "ellipsoid.Q: must be positive definite"),
                                              ({"Q": [["1"]]}, "ellipsoid: the system has dimension 2"),
                                              ({"R": [["1"]]}, "ellipsoid.R: unknown key")])
def test_bad_ellipsoids_in_problem_files_are_named(ellipsoid, match):
    with pytest.raises(ei.ExactinvError, match=match):
        load_problem({"system": {"A": [["-1", "3"], ["0", "-1"]]}, "ellipsoid": ellipsoid})


def test_the_oracle_judges_float_thresholds_on_an_ellipsoid():
    S, E, m = ei.LinearSystem([[-1, -2], [2, -1]]), ei.Ellipsoid([[1, 0], [0, 1]]), ei.methods.taylor(2)
    assert ei.oracle.judge_threshold(S, E, m, 0.86).status == "valid"
    bad = ei.oracle.judge_threshold(S, E, m, 0.87)
    assert bad.status == "invalid"
    dt, v = bad.counterexample["dt"], bad.counterexample["v"]
    image = ei.methods.taylor(2).matrix(S, dt)
    Av = [sum(a * x for a, x in zip(row, v)) for row in image]
    assert sum(x * x for x in Av) > sum(x * x for x in v)  # the unit disc: ||A_d v|| > ||v||
    assert ei.oracle.judge_threshold(S, E, ei.methods.forward_euler(), Fraction(2, 5)).status == "tight"


def test_plots_and_latex_on_an_ellipsoid():
    matplotlib = pytest.importorskip("matplotlib")
    matplotlib.use("Agg")
    S, E, m = ei.LinearSystem([[-1, -2], [2, -1]]), ei.Ellipsoid([[2, 1], [1, 3]]), ei.methods.taylor(2)
    fig = ei.display.plot_images(S, E, m, ["1/4", 1])
    ax = fig.axes[0]
    assert "images of E" in ax.get_title()
    assert any(line.get_color() == "crimson" for line in ax.lines)  # h = 1 fails: its witness is drawn
    fig = ei.display.plot_valid_set(S, E, m)
    assert "valid steplengths of taylor(2)" in fig.axes[0].get_title()
    assert r"x^T" in E._repr_latex_() and "invariant" in ei.continuous_invariance(S, E)._repr_latex_()
    with pytest.raises(ei.ExactinvError, match="ellipsoid: plot_images"):
        ei.display.plot_images(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), m, [1])


@pytest.mark.parametrize("call", [lambda S, E: ei.optimal_gamma(S, E),
                                  lambda S, E: ei.steplength_threshold(S, E, ei.methods.taylor(2)),
                                  lambda S, E: ei.compare_thresholds(S, E, [ei.methods.taylor(2)])])
def test_the_paper_s_polyhedral_results_refuse_an_ellipsoid_and_say_what_works(call):
    with pytest.raises(ei.ExactinvError, match="got an Ellipsoid.*largest_threshold"):
        call(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]))
