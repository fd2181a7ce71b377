"""The trusted kernel stands alone: standard library only, runnable from a bare copy."""


import ast
import json
import shutil
import subprocess
import sys
from pathlib import Path

from certificate_corpus import corpus

import exactinv_check

KERNEL = Path(exactinv_check.__file__).parent


def _bare_copy(tmp_path):
    shutil.copytree(KERNEL, tmp_path / "exactinv_check", ignore=shutil.ignore_patterns("__pycache__"))
    return tmp_path


def _run(cwd, *args):
    return subprocess.run([sys.executable, "-S", "-m", "exactinv_check", *args], cwd=cwd, capture_output=True,
                          text=True, timeout=120, env={"PATH": "/usr/bin:/bin"})


# ------------------------------------------------------------------ soundness

def test_every_kernel_module_imports_only_the_standard_library():
    for path in sorted(KERNEL.rglob("*.py")):  # the routes package too
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                names = [a.name.split(".")[0] for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                if node.level:  # a relative import stays inside the kernel package
                    continue
                names = [node.module.split(".")[0]]
            else:
                continue
            bad = [n for n in names if n not in sys.stdlib_module_names]
            assert not bad, f"{path.name} imports {bad}"


def test_a_bare_copy_runs_under_python_minus_S(tmp_path):
    root = _bare_copy(tmp_path)
    good = root / "good.json"
    good.write_text(json.dumps(corpus()["box-taylor4"]))
    bad_cert = json.loads(good.read_text())
    bad_cert["claims"][0]["value"] = "2"
    bad = root / "bad.json"
    bad.write_text(json.dumps(bad_cert))
    assert _run(root, "--help").returncode == 0
    done = _run(root, "good.json")
    assert done.returncode == 0 and "certificate VERIFIED" in done.stdout, done.stdout + done.stderr
    assert _run(root, "bad.json").returncode == 1
    assert _run(root, "missing.json").returncode == 2
    (root / "not-a-cert.json").write_text('{"system": {"A": [["1"]]}}')
    assert _run(root, "not-a-cert.json").returncode == 2


def test_the_engine_entry_points_call_the_kernel():
    import exactinv
    from exactinv.interfaces import cli

    assert exactinv.check is exactinv_check.check
    assert cli.exactinv_check is exactinv_check


def test_progress_is_reported_per_claim():
    seen = []
    cert = corpus()["box-taylor4"]
    assert exactinv_check.check(cert, progress=lambda k, total, kind: seen.append((k, total, kind))).ok
    assert [k for k, _, _ in seen] == list(range(len(cert["claims"])))
    assert [kind for _, _, kind in seen] == [c["type"] for c in cert["claims"]]


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
