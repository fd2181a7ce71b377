import json
import subprocess
import sys
from pathlib import Path

import pytest

from exactinv.cli import main

ROOT = Path(__file__).parents[2]
BOX = ROOT / "examples" / "paper_box_taylor4.json"


def test_certify_and_check(tmp_path, capsys):
    out = tmp_path / "cert.json"
    assert main(["certify", str(BOX), "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "gamma*: 1" in text and "largest forward-Euler step: 1" in text and "VERIFIED" in text
    assert "exact largest threshold: 1.7496858314" in text
    assert main(["check", str(out)]) == 0
    assert "certificate VERIFIED" in capsys.readouterr().out
    from test_certificate_schema import assert_valid

    assert_valid(json.loads(out.read_text()), what="the certificate exactinv certify wrote")
    cert = json.loads(out.read_text())
    cert["claims"][0]["value"] = "2"
    out.write_text(json.dumps(cert))
    assert main(["check", str(out)]) == 1


def test_method_override(capsys):
    assert main(["certify", str(BOX), "--method", '{"taylor": 1}']) == 0
    assert "taylor(1)" in capsys.readouterr().out


def test_not_invariant_problem(tmp_path, capsys):
    """x' = x leaves [-1, 1] through x = 1: refuted (exit 1), and the certificate of the refutation
    (the witness point) is still written and verified."""
    prob = tmp_path / "p.json"
    prob.write_text(json.dumps({"system": {"A": [["1"]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}}))
    out = tmp_path / "cert.json"
    assert main(["certify", str(prob), "-o", str(out)]) == 1
    assert "FAILS" in capsys.readouterr().out
    assert main(["check", str(out)]) == 0  # the certificate (x = 1 leaves) is verified: check exits 0


@pytest.mark.parametrize("content, message", [
    ('{"system": {"A": [[1.5]]}, "polyhedron": {"G": [[1]], "b": [1]}}', "float"),
    ('{"system": {"A": [["1", "2"]]}, "polyhedron": {"G": [[1]], "b": [1]}}', "square"),
    ('{"polyhedron": {"G": [[1]], "b": [1]}}', "system"),
    ('{"system": {"A": [["1"]]}, "polyhedron": {"G": [[1]], "b": [1]}, "method": {"euler": 1}}', "unknown kind"),
    ('not json', "not valid JSON"),
])
def test_bad_problem_files(tmp_path, capsys, content, message):
    prob = tmp_path / "p.json"
    prob.write_text(content)
    assert main(["certify", str(prob)]) == 2
    assert message in capsys.readouterr().err


def test_missing_file(capsys):
    assert main(["certify", "/nonexistent/p.json"]) == 2
    assert main(["check", "/nonexistent/c.json"]) == 2


def test_console_entry_point_runs():
    proc = subprocess.run([sys.executable, "-m", "exactinv", "certify", str(BOX)], capture_output=True, text=True)
    assert proc.returncode == 0 and "VERIFIED" in proc.stdout


def test_certify_never_writes_a_certificate_the_kernel_rejects(tmp_path, monkeypatch, capsys):
    import exactinv_check

    rejected = exactinv_check.CheckReport([("largest_threshold", False, "forced rejection for the test")])
    monkeypatch.setattr(exactinv_check, "check", lambda cert: rejected)
    out = tmp_path / "cert.json"
    assert main(["certify", str(BOX), "-o", str(out)]) == 4  # the engine's own certificate rejected: an error
    assert not out.exists()
    assert "NOT written" in capsys.readouterr().err
    assert main(["certify", str(BOX), "--no-check", "-o", str(out)]) == 0  # the user's explicit choice
    assert out.exists() and "skipped" in capsys.readouterr().out


def test_check_exit_codes_for_bad_input(tmp_path):
    missing = tmp_path / "missing.json"
    assert main(["check", str(missing)]) == 2
    problem = tmp_path / "problem.json"
    problem.write_text(BOX.read_text())
    assert main(["check", str(problem)]) == 2  # a problem file is not a certificate


def test_version_1_certificates_stay_checkable():
    """Certificates attached to papers must not expire: every corpus certificate, rewritten as
    version 1 (H dense; the format v2 only adds optional data to, v3 writes H sparse), verifies."""
    from certificate_corpus import corpus
    from versions import as_version

    from exactinv_check import check

    for name, cert in corpus().items():
        old = as_version(cert, 1)
        assert check(old).ok, name
