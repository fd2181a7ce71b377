"""exactinv.interfaces.pipeline: partial answers, never all-or-nothing (issue 21,
item 5).  An Undecided question leaves its claim out; every other claim is
certified, written and verified by the kernel; the report names what is open
and why; ``exactinv certify`` exits 3 (undecided, the exit-code rule of
exactinv.interfaces.exit_codes) with the certificate written."""

import json
from fractions import Fraction
from pathlib import Path

import exactinv as ei
import exactinv_check
from exactinv.cli import main
from exactinv.core.digits import float_text
from exactinv.interfaces.pipeline import certify
from exactinv.interfaces.problem import Problem

ROOT = Path(__file__).parents[2]
E2 = ROOT / "examples" / "erratum_e2_backward_euler.json"
E2_S, ORTHANT = ei.LinearSystem([[-1, 2], [0, 1]]), ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
# the issue's method: r = 1/(1 - z + z^2/4 - z^3/40); its radius was Undecided when this was written
ISSUE_DEN = ["1", "-1", "1/4", "-1/40"]
PARTIAL = {"gamma_star", "forward_euler_threshold", "largest_threshold", "valid_steplengths"}


def _certify_cli(problem_file: Path, cert: Path, capsys) -> tuple[int, str]:
    code = main(["certify", str(problem_file), "-o", str(cert)])
    return code, capsys.readouterr().out


def _never_decided(method):
    raise ei.Undecided(f"absolute monotonicity of {method.name}: (made undecided by the test)")


def test_an_undecided_radius_leaves_everything_else_certified(tmp_path, capsys, monkeypatch):
    """Backward Euler on erratum E2's orthant with the radius forced Undecided: gamma*, forward
    Euler, the exact valid set [0, 1) and the largest threshold 1 (not attained) are certified."""
    monkeypatch.setattr("exactinv.thresholds.rational.absolute_monotonicity_radius", _never_decided)
    cert = tmp_path / "cert.json"
    code, out = _certify_cli(E2, cert, capsys)
    assert code == 3 and cert.exists()
    assert "paper's threshold for backward_euler: UNDECIDED -- absolute monotonicity of backward_euler" in out
    assert "undecided (1, not in the certificate): paper's threshold for backward_euler" in out
    assert "exact valid steplengths for backward_euler: [0, 1)" in out
    assert "exact largest threshold: 1  (not attained); use dt <= 0.99999999999999988" in out  # the double below 1, truncated
    data = json.loads(cert.read_text())
    assert {c["type"] for c in data["claims"]} == PARTIAL
    assert main(["check", str(cert)]) == 0 and "certificate VERIFIED" in capsys.readouterr().out


def test_the_issue_method_on_the_e2_problem(tmp_path, capsys):
    """The natural example: r = 1/(1 - z + z^2/4 - z^3/40) on E2's orthant.  Whatever the radius
    (Undecided today), the certificate is written and verified and the valid set is [0, L), L the
    root of x^3 - 10x^2 + 40x - 40 (det(I - hA + h^2A^2/4 - h^3A^3/40) at A's eigenvalue 1: a pole)."""
    method = ei.methods.rational(["1"], ISSUE_DEN)
    try:
        ei.absolute_monotonicity_radius(method)
        undecided = False
    except ei.Undecided:
        undecided = True
    problem = tmp_path / "issue.json"
    problem.write_text(json.dumps({"system": {"A": [["-1", "2"], ["0", "1"]]},
                                   "polyhedron": {"G": [[-1, 0], [0, -1]], "b": [0, 0]},
                                   "method": {"rational": {"num": ["1"], "den": ISSUE_DEN}}}))
    before = problem.read_bytes()
    cert = tmp_path / "cert.json"
    code, out = _certify_cli(problem, cert, capsys)
    assert problem.read_bytes() == before
    L = ei.largest_threshold(E2_S, ORTHANT, method)
    assert not L.attained and [int(c) for c in L.value.poly.coeffs()] == [-40, 40, -10, 1]
    assert f"use dt <= {float_text(L.safe_float)}" in out and float(float_text(L.safe_float)) == L.safe_float
    types = {c["type"] for c in json.loads(cert.read_text())["claims"]}
    if undecided:
        assert code == 3 and types == PARTIAL and "UNDECIDED -- absolute monotonicity" in out
    else:  # the radius has been decided since: the whole answer
        assert code == 0 and {"rational_threshold", "absolute_monotonicity_radius"} <= types
    assert exactinv_check.check(str(cert)).ok


def test_an_undecided_valid_set_leaves_the_paper_threshold_certified(monkeypatch):
    """Any stage may be undecided: with the valid-set stage forced Undecided, the paper's
    threshold (Taylor(4) on the box: 1) is still certified and the report says what is open."""
    def undecided(*args):
        raise ei.Undecided("forced by the test")

    monkeypatch.setattr("exactinv.interfaces.pipeline._largest", undecided)
    box = Problem(ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1]), name="box")
    report = certify(box, ei.methods.taylor(4))
    assert report.ok and not report.complete
    assert report.undecided == (("exact valid steplengths and largest threshold for taylor(4)", "forced by the test"),)
    types = [c["type"] for c in report.certificate["claims"]]
    assert "polynomial_threshold" in types and "largest_threshold" not in types
    assert [r.value for r in report.results if isinstance(r, ei.SteplengthThreshold)] == [Fraction(1)]


def test_a_decided_problem_is_complete():
    box = Problem(ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1]), name="box")
    report = certify(box, ei.methods.trapezoid())
    assert report.ok and report.complete and report.undecided == ()
    assert not any("undecided" in line for line in report.lines)


def test_a_batch_records_the_partial_answer(monkeypatch):
    """A batch task (forked: the patch is inherited) records status "undecided", names the open
    question and keeps the decided values, with the outcome "undecided" (a batch's exit code 3)."""
    from exactinv.interfaces.batch.corpus import Task
    from exactinv.interfaces.batch.task import Limits, run_task

    monkeypatch.setattr("exactinv.thresholds.rational.absolute_monotonicity_radius", _never_decided)
    r = run_task(Task("e2", "certify", text=E2.read_text()), Limits(timeout=120))
    assert r["status"] == "undecided" and list(r["undecided"]) == ["paper's threshold for backward_euler"]
    assert r["outcome"] == "undecided"
    assert r["values"]["largest_threshold"] == "1" and r["values"]["gamma_star"] == "1"
