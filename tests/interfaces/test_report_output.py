"""`exactinv certify --json / --latex / --quiet` (issue 21, item 6).

The JSON is parsed and compared with the certificate written by the same run
(every value equals its claim's, encoded the same way: strings, never
floats); the LaTeX of every example goes into one document compiled by a
real engine where one is installed (as tests/test_latex_compile.py: a
missing engine skips, or fails when CI is set); --quiet prints nothing."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
from fractions import Fraction
from pathlib import Path

import pytest

from exactinv.cli import main

ROOT = Path(__file__).parents[2]
EXAMPLES = sorted(p for p in (ROOT / "examples").glob("*.json") if "design" not in json.loads(p.read_text()))
DESIGNS = sorted(p for p in (ROOT / "examples").glob("*.json") if "design" in json.loads(p.read_text()))
CLAIM = {"gamma_star": ("gamma_star", "value"), "forward_euler": ("forward_euler_threshold", "value"),
         "largest_threshold": ("largest_threshold", "value"), "largest_attained": ("largest_threshold", "attained"),
         "valid_steplengths": ("valid_steplengths", "intervals")}


def _no_floats(x) -> bool:
    if isinstance(x, float):
        return False
    if isinstance(x, dict):
        return all(_no_floats(v) for v in x.values())
    if isinstance(x, list):
        return all(_no_floats(v) for v in x)
    return True


def _json_of(args, capsys) -> tuple[int, dict]:
    code = main(["certify", *args, "--json"])
    out = capsys.readouterr().out
    return code, json.loads(out)


@pytest.mark.parametrize("example", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_json_equals_the_certificate(example, tmp_path, capsys):
    cert_path = tmp_path / "cert.json"
    code, report = _json_of([str(example), "-o", str(cert_path)], capsys)
    cert = json.loads(cert_path.read_text())
    assert code == report["exit_code"] == 0 and report["outcome"] == "proved" and report["invariant"] is True
    assert report["format"] == "exactinv-report" and report["certificate"] == str(cert_path)
    assert report["problem"] == json.loads(example.read_text()).get("name", example.stem) and _no_floats(report)
    claims = {c["type"]: c for c in cert["claims"]}
    assert report["check"]["verified"] is True and report["check"]["kind"] == "accepted"
    assert report["check"]["claims"] == len(cert["claims"])
    assert [v["claim"] for v in report["check"]["verdicts"]] == [c["type"] for c in cert["claims"]]
    values = report["values"]
    assert values, "no values"
    for key, value in values.items():
        if key == "paper_threshold":
            kind = next(t for t in claims if t.endswith("_threshold") and t.split("_")[0] in ("polynomial", "rational"))
            assert value == claims[kind]["value"], key
            continue
        kind, field = CLAIM[key]
        kind = kind if kind in claims else "ellipsoid_" + kind
        assert value == claims[kind][field], key


def test_json_of_a_refuted_problem_carries_the_witness(tmp_path, capsys):
    problem = tmp_path / "grows.json"
    problem.write_text(json.dumps({"system": {"A": [[1]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}}))
    cert_path = tmp_path / "cert.json"
    code, report = _json_of([str(problem), "-o", str(cert_path)], capsys)
    cert = json.loads(cert_path.read_text())
    assert code == report["exit_code"] == 1 and report["outcome"] == "refuted" and report["invariant"] is False
    assert report["witness"] == cert["claims"][0]["witness"] and report["values"]["gamma_star"] == "oo"
    assert report["witness"]["x"] == ["1"]  # x' = x leaves [-1, 1] at x = 1


def test_json_without_the_check(capsys):
    code, report = _json_of([str(ROOT / "examples" / "paper_box_taylor4.json"), "--no-check"], capsys)
    assert code == 0 and report["check"] == {"verified": None, "kind": None, "claims": 5, "verdicts": []}
    assert report["values"]["gamma_star"] == "1" and report["certificate"] is None


def test_quiet_prints_nothing(tmp_path, capsys):
    out = tmp_path / "cert.json"
    assert main(["certify", str(ROOT / "examples" / "paper_box_taylor4.json"), "--quiet", "-o", str(out)]) == 0
    assert capsys.readouterr() == ("", "") and out.exists()


def test_output_formats_exclude_each_other(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["certify", str(ROOT / "examples" / "paper_box_taylor4.json"), "--json", "--latex"])
    assert stop.value.code == 2 and "not allowed with" in capsys.readouterr().err


@pytest.mark.parametrize("example", DESIGNS, ids=[p.stem for p in DESIGNS])
def test_json_of_a_gain_design(example, tmp_path, capsys):
    """A gain design (issue 25): the gain's values equal its certificate's claim, and the closed
    loop's values are the engine's own results for x' = (A + BF)x, recomputed here through the API;
    gamma*(A + BF) = gamma and the forward-Euler step is 1/gamma (the LP's theorem)."""
    import exactinv as ei
    from exactinv.interfaces.problem import load_problem

    cert_path = tmp_path / "cert.json"
    code, report = _json_of([str(example), "-o", str(cert_path)], capsys)
    claim = json.loads(cert_path.read_text())["claims"][0]
    assert code == report["exit_code"] == 0 and report["outcome"] == "proved" and _no_floats(report)
    assert report["check"]["verified"] is True and report["closed_loop_check"]["verified"] is True
    gain, closed = report["values"]["gain"], report["values"]["closed_loop"]
    assert claim["type"] == "optimal_gain" and (gain["F"], gain["gamma"]) == (claim["F"], claim["value"])
    problem = load_problem(str(example))
    loop = ei.LinearSystem.closed_loop(problem.system.A, problem.B, [[Fraction(x) for x in row] for row in gain["F"]])
    gamma = ei.optimal_gamma(loop, problem.polyhedron).value
    assert closed["gamma_star"] == gain["gamma"] == str(gamma)
    assert closed["forward_euler"] == gain["forward_euler"] == str(1 / gamma if gamma > 0 else ei.INF)
    largest = ei.largest_threshold(loop, problem.polyhedron, problem.method)
    assert closed["largest_threshold"] == str(largest.value) and closed["largest_attained"] == largest.attained


def test_latex_tables(capsys):
    tables = []
    for example in EXAMPLES + DESIGNS:
        assert main(["certify", str(example), "--latex"]) == 0
        tables.append(capsys.readouterr().out)
    box = tables[[p.stem for p in EXAMPLES].index("paper_box_taylor4")]
    gain = tables[len(EXAMPLES)]
    assert "optimal gain $F$" in gain and r"closed loop: $\gamma^*$" in gain
    assert r"$\gamma^*$ & $1$ \\" in box and r"x^{4}-6x^{2}+12x-12" in box
    assert all(t.count(r"\begin{tabular}") == t.count(r"\end{tabular}") == 1 for t in tables)
    _compile(tables)


def _compile(tables: list[str]) -> None:
    engine = next((e for e in ("pdflatex", "lualatex", "xelatex", "tectonic") if shutil.which(e)), None)
    if engine is None:  # .ci/run installs pdflatex: in CI a missing engine is a failure
        (pytest.fail if os.environ.get("CI") else pytest.skip)("no LaTeX engine installed (.ci/run installs pdflatex)")
    import tempfile

    with tempfile.TemporaryDirectory() as d:
        doc = "\n".join([r"\documentclass{article}", r"\usepackage{amsmath}", r"\usepackage[margin=1cm]{geometry}",
                         r"\begin{document}", *[t + "\n\n\\bigskip\n" for t in tables], r"\end{document}"])
        Path(d, "tables.tex").write_text(doc, encoding="utf-8")
        cmd = ([engine, "--chatter", "minimal", "tables.tex"] if engine == "tectonic" else
               [engine, "-interaction=nonstopmode", "-halt-on-error", "-file-line-error", "tables.tex"])
        run = subprocess.run(cmd, cwd=d, capture_output=True, text=True, timeout=120)
        log = Path(d, "tables.log")
        text = log.read_text(errors="replace") if log.exists() else run.stdout + run.stderr
        errors = [line for line in text.splitlines() if line.startswith("!") or re.match(r"\./tables\.tex:\d+:", line)]
        assert run.returncode == 0 and Path(d, "tables.pdf").exists(), "\n".join(errors[:10])
