"""Every sub-command on a corpus of bad inputs, as a user runs it (``python -m exactinv``):
never a traceback, the documented exit code (0 ok, 1 refuted/rejected/invalid,
2 bad input), and a one-line message naming the file, key, row or argument.

The cases in ``SEPARATE`` run as real ``python -m exactinv ...`` subprocesses.
To keep the suite fast, the others run in two worker subprocesses that execute
the ``exactinv`` module as ``__main__`` once per case (what ``python -m`` does:
``runpy.run_module``), with fresh sys.argv, stdout and stderr; an exception
escaping the command is recorded as a traceback, exactly as a user would see it.
"""

import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest
from certificate_corpus import corpus

ROOT = Path(__file__).resolve().parent.parent
BOX = {"system": {"A": [["-1", "1"], ["-1", "-1"]]},
       "polyhedron": {"G": [[1, 0], [-1, 0], [0, 1], [0, -1]], "b": [1, 1, 1, 1]},
       "method": {"taylor": 2}}


def _with(**changes):
    data = json.loads(json.dumps(BOX))
    for path, value in changes.items():
        *head, last = path.split("__")
        target = data
        for key in head:
            target = target[key]
        if value is _DELETE:
            del target[last]
        else:
            target[last] = value
    return json.dumps(data)


_DELETE = object()
RK4 = {"A": [[0, 0, 0, 0], ["1/2", 0, 0, 0], [0, "1/2", 0, 0], [0, 0, 1, 0]], "b": ["1/6", "1/3", "1/3", "1/6"]}

FILES = {
    "problem.json": json.dumps(BOX),
    "notjson.json": "this is not JSON {",
    "empty.json": "",
    "list.json": "[1, 2, 3]",
    "string.json": '"system"',
    "methd.json": _with(methd={"taylor": 4}, method=_DELETE),
    "sytem.json": json.dumps({"sytem": BOX["system"], "polyhedron": BOX["polyhedron"]}),
    "nested_key.json": _with(polyhedron__bb=[1, 1, 1, 1], polyhedron__b=_DELETE),
    "both_forms.json": _with(polyhedron__vertices=[[1, 0]]),
    "float.json": '{"system": {"A": [[-1.5]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}}',
    "nan.json": '{"system": {"A": [[NaN]]}, "polyhedron": {"G": [[1], [-1]], "b": [1, 1]}}',
    "ragged.json": _with(system__A=[["-1", "1"], ["-1"]]),
    "nonsquare.json": _with(system__A=[["-1", "1"]]),
    "dimension.json": _with(polyhedron={"G": [[1], [-1]], "b": [1, 1]}),
    "b_length.json": _with(polyhedron__b=[1, 1]),
    "not_a_number.json": _with(polyhedron__b=[1, 1, "one", 1]),
    "unknown_method.json": _with(method={"euler": 1}),
    "bad_preset.json": _with(method={"preset": "rk5"}),
    "bad_taylor.json": _with(method={"taylor": 0}),
    "two_methods.json": _with(method={"taylor": 2, "theta": "1/2"}),
    "butcher_c.json": _with(method={"butcher": {**RK4, "c": [0, "1/2", "1/2", "1/2"]}}),
    "butcher_key.json": _with(method={"butcher": {**RK4, "cc": [0, "1/2", "1/2", 1]}}),
    "rational_key.json": _with(method={"rational": {"num": [1], "denom": [1, -1]}}),
    "sigma0.json": _with(method={"polynomial": [2, 1]}),
    "duplicate.json": '{"system": {"A": [["1"]]}, "system": {"A": [["2"]]}, "polyhedron": {"G": [[1]], "b": [1]}}',
    "missing_system.json": json.dumps({"polyhedron": BOX["polyhedron"]}),
    "closed_loop_partial.json": _with(system={"A0": [["-1", "1"], ["-1", "-1"]], "B": [[1], [0]]}),
    "cert.json": json.dumps(corpus()["box-taylor2"]),
    "malformed_cert.json": json.dumps({"format": "exactinv-certificate", "version": 2, "problem": {},
                                       "claims": [{"type": "gamma_star"}]}),
    "no_claims_cert.json": json.dumps({"format": "exactinv-certificate", "version": 2,
                                       "problem": corpus()["box-taylor2"]["problem"], "claims": []}),
    "wrong_format.json": json.dumps({"format": "something-else", "claims": []}),
}


def _tampered():
    cert = json.loads(FILES["cert.json"])
    cert["claims"][0]["value"] = "2"
    return json.dumps(cert)


FILES["tampered.json"] = _tampered()

ORACLE = {
    "rows.csv": "problem,quantity,method,claimed\n"
                "problem.json,threshold,,abc\n"             # row 1: claimed is not a number
                "problem.json,threshold,rk5,1.0\n"          # row 2: unknown preset
                "problem.json,speed,,1.0\n"                 # row 3: unknown quantity
                "missing.json,gamma,,1.0\n"                 # row 4: missing problem file
                "problem.json,threshold,,-1.0\n"            # row 5: negative claim
                "problem.json,threshold,\"{\"\"taylor\"\": 0}\",1.0\n"  # row 6: bad method JSON value
                "problem.json,threshold,{bad,1.0\n"         # row 7: method not JSON
                "notjson.json,gamma,,1.0\n"                 # row 8: problem file not JSON
                "problem.json,gamma,,1.0\n"                 # row 9: fine (tight)
                "problem.json,threshold,,2.0\n",            # row 10: invalid (sqrt 2 < 2)
    "bad_only.csv": "problem,quantity,method,claimed\nproblem.json,gamma,,abc\n",
    "good.csv": "problem,quantity,method,claimed\nproblem.json,gamma,,1.0\nproblem.json,threshold,rk4,0.5\n",
    "header.csv": "file,value\nproblem.json,1.0\n",
    "rows.jsonl": '{"problem": "problem.json", "quantity": "gamma", "claimed": 1.0}\n'
                  "{not json\n"
                  '[1, 2]\n'
                  '{"problem": "problem.json", "quantity": "gamma", "claimed": 1.0, "claimd": 2}\n',
}

# (name, args, exit code, words that the output must contain, whether stderr must be one line)
CASES = [
    ("version", ["--version"], 0, ["exactinv 0."], False),
    ("no command", [], 2, ["usage"], False),
    ("unknown command", ["frobnicate"], 2, ["frobnicate"], False),
    ("unknown option", ["certify", "{d}/problem.json", "--frobnicate"], 2, ["--frobnicate"], False),
    ("certify ok", ["certify", "{d}/problem.json"], 0, ["VERIFIED"], False),
    ("certify preset", ["certify", "{d}/problem.json", "--method", "rk4"], 0, ["rk4", "VERIFIED"], False),
    ("certify missing", ["certify", "{d}/missing.json"], 2, ["missing.json", "no such file"], True),
    ("certify directory", ["certify", "{d}/adir"], 2, ["adir", "directory"], True),
    ("certify binary", ["certify", "{d}/binary.json"], 2, ["binary.json"], True),
    ("certify a certificate", ["certify", "{d}/cert.json"], 2, ["cert.json", "certificate"], True),
    ("certify bad preset option", ["certify", "{d}/problem.json", "--method", "rk5"], 2, ["--method", "rk4"], True),
    ("certify bad method json", ["certify", "{d}/problem.json", "--method", "{taylor: 4}"], 2, ["--method", "JSON"], True),
    ("certify bad method value", ["certify", "{d}/problem.json", "--method", '{"taylor": "x"}'], 2,
     ["--method.taylor"], True),
    ("certify float method", ["certify", "{d}/problem.json", "--method", '{"theta": 0.5}'], 2, ["0.5", "string"], True),
    ("certify -o missing dir", ["certify", "{d}/problem.json", "-o", "{d}/nowhere/cert.json"], 2,
     ["-o", "nowhere", "does not exist"], True),
    ("certify -o directory", ["certify", "{d}/problem.json", "-o", "{d}/adir"], 2, ["-o", "directory"], True),
    ("check missing", ["check", "{d}/missing.json"], 2, ["missing.json"], True),
    ("check directory", ["check", "{d}/adir"], 2, ["adir", "directory"], True),
    ("check not json", ["check", "{d}/notjson.json"], 2, ["notjson.json", "JSON"], True),
    ("check empty", ["check", "{d}/empty.json"], 2, ["empty.json"], True),
    ("check list", ["check", "{d}/list.json"], 2, ["list.json", "object"], True),
    ("check binary", ["check", "{d}/binary.json"], 2, ["binary.json"], True),
    ("check problem file", ["check", "{d}/problem.json"], 2, ["problem.json", "problem file"], True),
    ("check wrong format", ["check", "{d}/wrong_format.json"], 2, ["wrong_format.json", "format"], True),
    ("check ok", ["check", "{d}/cert.json"], 0, ["VERIFIED"], False),
    ("check tampered", ["check", "{d}/tampered.json"], 1, ["REJECTED"], False),
    ("check malformed", ["check", "{d}/malformed_cert.json"], 1, ["REJECTED"], False),
    ("check no claims", ["check", "{d}/no_claims_cert.json"], 1, ["no claim"], False),
    ("explain ok", ["explain", "{d}/cert.json"], 0, ["gamma* = 1", "verified"], False),
    ("explain missing", ["explain", "{d}/missing.json"], 2, ["missing.json"], True),
    ("explain directory", ["explain", "{d}/adir"], 2, ["adir"], True),
    ("explain not json", ["explain", "{d}/notjson.json"], 2, ["notjson.json", "JSON"], True),
    ("explain list", ["explain", "{d}/list.json"], 2, ["list.json"], True),
    ("explain problem file", ["explain", "{d}/problem.json"], 2, ["problem.json", "problem file"], True),
    ("explain tampered", ["explain", "{d}/tampered.json"], 1, ["tampered.json", "REJECTED", "not explained"], False),
    ("explain malformed", ["explain", "{d}/malformed_cert.json"], 1, ["REJECTED"], False),
    # an invalid claim (1) and rows that cannot be judged (2): the highest code, as for every sub-command
    ("oracle rows", ["oracle", "{d}/rows.csv"], 2,
     ["row 1", "abc", "row 2", "rk4", "row 3", "speed", "row 4", "missing.json", "row 5", "negative",
      "row 6", "row 7", "row 8", "notjson.json", "TIGHT", "INVALID", "10 results judged: 1 invalid"], False),
    ("oracle bad rows only", ["oracle", "{d}/bad_only.csv"], 2, ["row 1", "abc"], False),
    ("oracle good", ["oracle", "{d}/good.csv"], 0, ["2 results judged: 0 invalid"], False),
    ("oracle jsonl", ["oracle", "{d}/rows.jsonl"], 2, ["row 2", "JSON", "row 3", "row 4", "claimd", "claimed"], False),
    ("oracle header", ["oracle", "{d}/header.csv"], 2, ["header.csv", "problem", "claimed"], True),
    ("oracle missing", ["oracle", "{d}/missing.csv"], 2, ["missing.csv"], True),
    ("oracle directory", ["oracle", "{d}/adir"], 2, ["adir", "directory"], True),
    ("oracle empty", ["oracle", "{d}/empty.json"], 2, ["empty.json"], True),
    ("oracle tolerance", ["oracle", "{d}/good.csv", "--tolerance", "abc"], 2, ["--tolerance", "abc"], True),
]

# every bad problem file, through certify (exit 2, names the file and the key)
PROBLEM_CASES = {
    "notjson.json": ["JSON"],
    "empty.json": ["JSON"],
    "list.json": ["JSON object", "list"],
    "string.json": ["JSON object"],
    "methd.json": ["methd", 'did you mean "method"'],
    "sytem.json": ["sytem", 'did you mean "system"'],
    "nested_key.json": ["polyhedron.bb", 'did you mean "b"'],
    "both_forms.json": ["polyhedron", "not both"],
    "float.json": ["-1.5", "float", "string"],
    "nan.json": ["NaN"],
    "ragged.json": ["system.A", "ragged"],
    "nonsquare.json": ["system.A", "square"],
    "dimension.json": ["polyhedron", "dimension"],
    "b_length.json": ["polyhedron.b"],
    "not_a_number.json": ["polyhedron.b[2]", "one"],
    "unknown_method.json": ["method.euler", "unknown kind"],
    "bad_preset.json": ["method.preset", "rk5", 'did you mean "rk4"'],
    "bad_taylor.json": ["method.taylor", "order"],
    "two_methods.json": ["method", "one key"],
    "butcher_c.json": ["method.butcher.c[3]", "row sums"],
    "butcher_key.json": ["method.butcher.cc", 'did you mean "c"'],
    "rational_key.json": ["method.rational.denom", 'did you mean "den"'],
    "sigma0.json": ["method.polynomial", "sigma_0"],
    "duplicate.json": ["duplicate", "system"],
    "missing_system.json": ["system", "missing"],
    "closed_loop_partial.json": ["system", "F"],
}
CASES += [(f"certify {name}", ["certify", "{d}/" + name], 2, [name, *words], True)
          for name, words in PROBLEM_CASES.items()]


SEPARATE = {"version", "no command", "certify missing", "certify -o missing dir", "check tampered",
            "explain problem file", "oracle rows", "certify methd.json"}

WORKER = r"""
import io, json, runpy, sys, traceback
results = {}
for name, args in json.load(sys.stdin):
    out, err = io.StringIO(), io.StringIO()
    saved = sys.argv, sys.stdout, sys.stderr
    sys.argv, sys.stdout, sys.stderr = ["exactinv", *args], out, err
    try:
        runpy.run_module("exactinv", run_name="__main__", alter_sys=True)
        code = 0
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    except BaseException:
        err.write(traceback.format_exc())
        code = 1
    finally:
        sys.argv, sys.stdout, sys.stderr = saved
    results[name] = (code, out.getvalue(), err.getvalue())
json.dump(results, sys.stdout)
"""


def _env():
    return {**os.environ, "PYTHONPATH": str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")}


def _run(args, cwd):
    proc = subprocess.run([sys.executable, "-m", "exactinv", *args], capture_output=True, text=True, cwd=cwd,
                          env=_env(), timeout=300)
    return proc.returncode, proc.stdout, proc.stderr


def _run_many(jobs, cwd):
    proc = subprocess.run([sys.executable, "-c", WORKER], input=json.dumps(jobs), capture_output=True, text=True,
                          cwd=cwd, env=_env(), timeout=600)
    assert proc.returncode == 0, proc.stderr
    return {name: tuple(r) for name, r in json.loads(proc.stdout).items()}


@pytest.fixture(scope="module")
def outcomes(tmp_path_factory):
    d = tmp_path_factory.mktemp("bad_inputs")
    for name, text in {**FILES, **ORACLE}.items():
        (d / name).write_text(text)
    (d / "binary.json").write_bytes(b"\xff\xfe\x00\x01 not text")
    (d / "adir").mkdir()
    jobs = {name: [a.replace("{d}", str(d)) for a in args] for name, args, *_ in CASES}
    shared = [(name, args) for name, args in jobs.items() if name not in SEPARATE]
    with ThreadPoolExecutor(max_workers=4) as pool:
        separate = {name: pool.submit(_run, jobs[name], d) for name in SEPARATE}
        halves = [pool.submit(_run_many, shared[k::2], d) for k in range(2)]
        results = {name: f.result() for name, f in separate.items()}
        for half in halves:
            results.update(half.result())
    return results


@pytest.mark.parametrize("name, args, code, words, one_line", CASES, ids=[c[0] for c in CASES])
def test_no_traceback_and_the_right_exit_code(outcomes, name, args, code, words, one_line):
    rc, out, err = outcomes[name]
    assert "Traceback" not in err and "Traceback" not in out, err
    assert "internal error" not in err, err
    assert rc == code, f"exit {rc}, expected {code}\nstdout: {out}\nstderr: {err}"
    text = out + err
    for word in words:
        assert word in text, f"{word!r} not in the output:\n{text}"
    if one_line:
        lines = err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("exactinv: "), err


def test_output_is_checked_before_computing(outcomes):
    rc, out, err = outcomes["certify -o missing dir"]
    assert out == "", "the computation ran before -o was refused"


def test_oracle_reports_every_row(outcomes):
    rc, out, err = outcomes["oracle rows"]
    table = [line for line in out.splitlines() if line[:3].strip().isdigit() and "judged" not in line]
    assert [int(line[:3]) for line in table] == list(range(1, 11))
    assert sum("ERROR" in line for line in table) == 8
