"""The documentation site (docs/site) builds with warnings as errors.

``sphinx-build -W --keep-going -b html docs/site <tmp>`` runs in a subprocess:
the API reference from the docstrings (autodoc), the format docs and errata,
and the notebooks, executed during the build (myst-nb, ``nb_execution_mode =
"force"``), so a notebook cell that raises fails this test too.  Skipped where
Sphinx or myst-nb is not installed (the ``docs`` extra), except in CI (the
environment variable CI set), where ``.ci/run`` installs the extra and a
missing Sphinx is a failure.
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SITE = ROOT / "docs" / "site"


def _require(module: str) -> None:
    if importlib.util.find_spec(module) is None:
        message = f"{module} is not installed (python -m pip install -e '.[docs]')"
        (pytest.fail if os.environ.get("CI") else pytest.skip)(message)


@pytest.mark.heavy
def test_docs_build_without_warnings(tmp_path):
    _require("sphinx")
    _require("myst_nb")
    out = tmp_path / "html"
    env = dict(os.environ)
    # The notebooks' kernel and autodoc import exactinv from this checkout.
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(ROOT), env.get("PYTHONPATH", "")) if p)
    run = subprocess.run(
        [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-q", "-b", "html", str(SITE), str(out)],
        cwd=ROOT, env=env, capture_output=True, text=True, timeout=900,
    )
    assert run.returncode == 0, f"sphinx-build failed:\n{run.stdout[-6000:]}\n{run.stderr[-6000:]}"
    for page in ("index", "api", "generated/problem-format", "generated/certificate-format", "generated/errata"):
        assert (out / f"{page}.html").is_file(), page
    api = (out / "api.html").read_text(encoding="utf-8")
    for name in ("exactinv.largest_threshold", "exactinv.model.methods.taylor",
                 "exactinv.interfaces.oracle.judge_threshold", "exactinv.interfaces.display.plot_valid_set",
                 "exactinv_check.check"):
        assert f'id="{name}"' in api, name
    # The notebooks are rendered with the outputs of their execution at build
    # time (the committed notebooks have none: tests/test_notebooks.py).
    notebooks = sorted((ROOT / "notebooks").glob("*.ipynb"))
    assert notebooks
    for nb in notebooks:
        html = (out / "generated" / "notebooks" / f"{nb.stem}.html").read_text(encoding="utf-8")
        assert "cell_output" in html, nb.stem
    assert "Fraction(1, 1)" in (out / "generated" / "notebooks" / "01_quickstart.html").read_text(encoding="utf-8")
    assert list((out / "_images").glob("*.png")), "the notebooks' figures are in the site"
