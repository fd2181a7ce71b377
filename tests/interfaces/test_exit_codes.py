"""One exit-code rule (issue 21, item 3): the same text in `--help` (every
sub-command), in the README's "Command line" section and in
docs/problem-format.md, and the code follows it -- a table of real runs of
certify, check, explain, oracle and batch, one per outcome."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

import exactinv_check
from exactinv.cli import main
from exactinv.interfaces.exit_codes import CODES, EXIT_CODES, INTERRUPTED, PIPE_CLOSED, exit_code

ROOT = Path(__file__).parents[2]
BOX = json.loads((ROOT / "examples" / "paper_box_taylor4.json").read_text())
SEGMENT = {"G": [[1], [-1]], "b": [1, 1]}
# h = (u^2 - 2)(u^4 - 2u^2 + 9)/34, u = z - 2: p* = 2 - sqrt 2 and the pair p* +- i on its line, with a numerator
# making f = (1 + cos t)((1 + sqrt 2) e^(-p* t) + (1 - sqrt 2) e^(-q t)): p*'s line part touches 0 and the conjugate
# line's is negative, so the radius stays undecided (docs/design.md, what stays undecided; 1/h itself is decided
# since line-irrational)
UNDECIDED = {"rational": {"num": ["1", "-61/28", "53/21", "-107/84", "2/7", "-1/42"],
                          "den": ["1", "-58/17", "157/34", "-64/17", "28/17", "-6/17", "1/34"]}}


@pytest.mark.heavy
def test_the_rule_reads_the_same_everywhere():
    readme = (ROOT / "README.md").read_text()
    section = readme[readme.index("## Command line"):]
    section = section[:section.index("\n## ", 3)]
    assert EXIT_CODES in section, "the README's Command line section must quote the rule verbatim"
    assert EXIT_CODES in (ROOT / "docs" / "problem-format.md").read_text()
    for command in ([], ["certify"], ["check"], ["explain"], ["oracle"], ["batch"]):
        proc = subprocess.run([sys.executable, "-m", "exactinv", *command, "--help"], capture_output=True, text=True)
        assert proc.returncode == 0 and EXIT_CODES in proc.stdout, command
    numbers = [int(n) for n in re.findall(r"^  (\d+)  ", EXIT_CODES, re.M)]
    assert numbers == sorted(CODES.values()) + [INTERRUPTED, PIPE_CLOSED]


def test_several_outcomes_exit_with_the_highest_code():
    assert exit_code([]) == 0
    for a in CODES:
        for b in CODES:
            assert exit_code([a, b]) == max(CODES[a], CODES[b])


def _problem(tmp_path, name: str, data: dict) -> str:
    path = tmp_path / name
    path.write_text(json.dumps(data))
    return str(path)


def test_certify_exit_codes(tmp_path, capsys, monkeypatch):
    proved = _problem(tmp_path, "box.json", BOX)
    refuted = _problem(tmp_path, "grows.json", {"system": {"A": [[1]]}, "polyhedron": SEGMENT})
    bad = _problem(tmp_path, "bad.json", {"system": {"A": [[1]]}})
    undecided = _problem(tmp_path, "undecided.json", {**BOX, "method": UNDECIDED})
    assert main(["certify", proved]) == CODES["proved"] == 0
    assert main(["certify", refuted, "-o", str(tmp_path / "refuted.cert.json")]) == CODES["refuted"] == 1
    assert main(["check", str(tmp_path / "refuted.cert.json")]) == 0  # the refutation itself is verified
    assert main(["certify", bad]) == CODES["bad_input"] == 2
    assert main(["certify", undecided]) == CODES["undecided"] == 3
    assert "undecided" in capsys.readouterr().err

    import exactinv.interfaces.cli as cli

    rejected = exactinv_check.CheckReport([("gamma_star", False, "forced rejection for the test")])
    monkeypatch.setattr(exactinv_check, "check", lambda cert: rejected)
    assert main(["certify", proved]) == CODES["error"] == 4  # the engine's own certificate rejected
    monkeypatch.undo()

    def bug(*args, **kwargs):
        raise ZeroDivisionError("a bug")

    monkeypatch.setattr(cli, "certify", bug)
    assert main(["certify", proved]) == 4
    assert "internal error" in capsys.readouterr().err


def test_check_and_explain_exit_codes(tmp_path, capsys):
    cert = tmp_path / "cert.json"
    assert main(["certify", _problem(tmp_path, "box.json", BOX), "-o", str(cert), "--quiet"]) == 0
    assert main(["check", str(cert)]) == 0 and main(["explain", str(cert)]) == 0
    data = json.loads(cert.read_text())
    data["claims"][0]["value"] = "2"  # gamma* = 1, not 2
    tampered = tmp_path / "tampered.json"
    tampered.write_text(json.dumps(data))
    assert main(["check", str(tampered)]) == 1 and main(["explain", str(tampered)]) == 1
    assert main(["check", str(tmp_path / "missing.json")]) == 2 and main(["explain", str(tmp_path / "box.json")]) == 2
    capsys.readouterr()


def test_oracle_exit_codes(tmp_path, capsys):
    _problem(tmp_path, "decay.json", {"system": {"A": [["-1"]]}, "polyhedron": SEGMENT})
    header = "problem,quantity,method,claimed\n"
    files = {  # x' = -x on [-1, 1]: gamma* = 1/2, forward Euler valid up to dt = 2
        "valid.csv": (header + "decay.json,gamma,,0.5\ndecay.json,threshold,forward_euler,1.5\n", 0),
        "invalid.csv": (header + "decay.json,threshold,forward_euler,2.5\n", 1),
        "bad.csv": (header + "decay.json,speed,,1\n", 2),
        "invalid_and_bad.csv": (header + "decay.json,threshold,forward_euler,2.5\ndecay.json,speed,,1\n", 2),
    }
    for name, (text, code) in files.items():
        (tmp_path / name).write_text(text)
        assert main(["oracle", str(tmp_path / name)]) == code, name
    capsys.readouterr()


def test_batch_exit_codes(tmp_path, capsys):
    pytest.importorskip("dask.distributed")
    corpus = tmp_path / "corpus"
    corpus.mkdir()
    (corpus / "decay.json").write_text(json.dumps({"system": {"A": [[-1]]}, "polyhedron": SEGMENT,
                                                   "method": {"taylor": 1}}))
    out = str(tmp_path / "r.jsonl")
    assert main(["batch", str(corpus), "-o", out, "--workers", "1"]) == 0
    (corpus / "grows.json").write_text(json.dumps({"system": {"A": [[1]]}, "polyhedron": SEGMENT}))
    assert main(["batch", str(corpus), "-o", out, "--workers", "1"]) == 1
    (corpus / "undecided.json").write_text(json.dumps({**BOX, "method": UNDECIDED}))
    assert main(["batch", str(corpus), "-o", out, "--workers", "1"]) == 3
    records = {json.loads(line)["id"]: json.loads(line) for line in open(out)}
    assert [records[i]["outcome"] for i in ("decay.json", "grows.json", "undecided.json")] == \
        ["proved", "refuted", "undecided"]
    assert "outcomes: proved 1, refuted 1, undecided 1 (exit code 3)" in capsys.readouterr().out


def test_a_closed_pipe_stops_quietly():
    """`exactinv certify P.json | head -0`: the reader is gone before the first line;
    no traceback, no 'internal error', exit 141 (the shell's code for SIGPIPE)."""
    import subprocess
    import sys
    from pathlib import Path
    root = Path(__file__).resolve().parents[2]
    proc = subprocess.Popen([sys.executable, "-m", "exactinv", "certify", "examples/paper_box_taylor4.json"],
                            cwd=root, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()
    _, err = proc.communicate(timeout=300)
    assert proc.returncode == 141, err
    assert err == b""
