"""Packaging: the sdist is complete (the tests run from it), the wheel is typed
and licensed, and the metadata a scientific library is expected to carry is there."""

from __future__ import annotations

import os
import subprocess
import sys
import tarfile
import tomllib
import zipfile
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text())

# files the tests need beside the test modules, and the files a user expects
MUST_SHIP = [
    "LICENSE", "CITATION.cff", "CHANGELOG.md", "README.md", "pyproject.toml",
    "exactinv/py.typed", "exactinv_check/py.typed",
    "tests/conftest.py", "tests/certificate_corpus.py", "tests/strategies.py",
    "examples/paper_box_taylor4.json", "examples/oracle/paper_float_results.csv",
    "docs/errata.md", "docs/certificate.schema.json", "docs/make_figures.py", "docs/img/valid_set.png",
    "notebooks/01_quickstart.ipynb", "benchmarks/README.md", "benchmarks/gamma.py",
]
SUBSET = ["tests/kernel/test_standalone.py", "tests/core/test_roots.py"]


def _setuptools_version() -> tuple[int, ...]:
    try:
        from importlib.metadata import version
        return tuple(int(p) for p in version("setuptools").split(".")[:2])
    except Exception:  # noqa: BLE001 - absent or unparsable: too old for us
        return (0,)


def _build(kind: str, out: Path, source: Path = ROOT) -> Path:
    """Build an sdist or a wheel of ``source`` with setuptools' own backend, in a
    subprocess (the backend works on the current directory)."""
    if _setuptools_version() < (77,):
        # CI installs the test extra: there a missing build backend is a failure, not a skip
        (pytest.fail if os.environ.get("CI") else pytest.skip)("building needs setuptools>=77 (the test extra installs it)")
    code = (f"import sys; from setuptools import build_meta as b; "
            f"print(b.build_{kind}(sys.argv[1]))")
    run = subprocess.run([sys.executable, "-c", code, str(out)], cwd=source, capture_output=True, text=True,
                         timeout=300)
    assert run.returncode == 0, run.stderr[-3000:]
    return out / run.stdout.strip().splitlines()[-1]


def _tracked_files() -> set[str] | None:
    try:
        run = subprocess.run(["git", "ls-files", "-z"], cwd=ROOT, capture_output=True, timeout=60)
    except (OSError, subprocess.SubprocessError):
        return None
    if run.returncode != 0 or not run.stdout:
        return None  # not a git checkout (e.g. the unpacked sdist itself)
    return {f for f in run.stdout.decode().split("\0") if f}


@pytest.fixture(scope="module")
def sdist(tmp_path_factory) -> Path:
    return _build("sdist", tmp_path_factory.mktemp("sdist"))


@pytest.fixture(scope="module")
def unpacked(sdist, tmp_path_factory) -> tuple[Path, set[str]]:
    """The sdist unpacked: its top directory and the files it holds (relative)."""
    where = tmp_path_factory.mktemp("unpacked")
    with tarfile.open(sdist) as tar:
        names = tar.getnames()
        tar.extractall(where, filter="data")
    top = names[0].split("/")[0]
    return where / top, {n.split("/", 1)[1] for n in names if "/" in n}


def test_metadata():
    project = PYPROJECT["project"]
    assert project["license"] == "MIT" and project["license-files"] == ["LICENSE"]
    assert "MIT License" in (ROOT / "LICENSE").read_text()
    assert any(c.startswith("Topic :: Scientific/Engineering") for c in project["classifiers"])
    assert "Typing :: Typed" in project["classifiers"] and project["keywords"] and project["urls"]
    requires = PYPROJECT["build-system"]["requires"]
    assert any(r.replace(" ", "").startswith("setuptools>=") and int(r.split(">=")[1].split(".")[0]) >= 77
               for r in requires), "SPDX license strings need setuptools>=77"
    import exactinv
    assert exactinv.__version__ == project["version"]


def test_no_pre_release_pins():
    """pplpy's own requirement (gmpy2>=2.1.0b1) lets pip take an alpha gmpy2; ours caps it."""
    deps = PYPROJECT["project"]["dependencies"]
    gmpy2 = [d for d in deps if d.startswith("gmpy2")]
    assert gmpy2 and "<2.4" in gmpy2[0]
    for d in deps + [d for extra in PYPROJECT["project"]["optional-dependencies"].values() for d in extra]:
        assert not any(tag in d for tag in ("a0", "a1", "b1", "rc", "dev")), d


def test_citation_names_the_paper():
    cff = (ROOT / "CITATION.cff").read_text()
    assert "cff-version: 1.2.0" in cff and "arXiv:1406.6755" in cff
    assert "Steplength Thresholds for Invariance Preserving" in cff
    for author in ("Horváth", "Song", "Terlaky"):
        assert author in cff
    assert f"version: {PYPROJECT['project']['version']}" in cff
    assert f"## [{PYPROJECT['project']['version']}]" in (ROOT / "CHANGELOG.md").read_text()


def test_sdist_is_complete_and_its_tests_run(unpacked):
    tree, shipped = unpacked
    missing = [f for f in MUST_SHIP if f not in shipped]
    assert not missing, f"the sdist lacks {missing}"
    tracked = _tracked_files()
    if tracked is not None:
        left_out = sorted(f for f in tracked - shipped if f != ".gitignore")
        assert not left_out, f"tracked files missing from the sdist: {left_out[:20]}"
    assert not [n for n in shipped if "__pycache__" in n or n.endswith(".pyc")]

    env = {**os.environ, "PYTHONPATH": str(tree)}
    where = subprocess.run([sys.executable, "-c", "import exactinv, exactinv_check; "
                            "print(exactinv.__file__); print(exactinv_check.__file__)"],
                           cwd=tree, env=env, capture_output=True, text=True, timeout=120)
    assert where.returncode == 0, where.stderr
    assert all(Path(p).resolve().is_relative_to(tree.resolve()) for p in where.stdout.split()), where.stdout
    run = subprocess.run([sys.executable, "-m", "pytest", "-q", "-x", "-p", "no:randomly", *SUBSET],
                         cwd=tree, env=env, capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-2000:]
    assert " passed" in run.stdout


def test_wheel_from_the_sdist_is_typed_and_licensed(unpacked, tmp_path):
    wheel = _build("wheel", tmp_path, source=unpacked[0])
    with zipfile.ZipFile(wheel) as zf:
        names = zf.namelist()
        metadata = zf.read(next(n for n in names if n.endswith(".dist-info/METADATA"))).decode()
    assert "exactinv/py.typed" in names and "exactinv_check/py.typed" in names
    shipped = {n for n in names if n.startswith("exactinv_check/selftest_certificates/")}  # the kernel's selftest
    assert shipped == {f"exactinv_check/selftest_certificates/{p.name}"
                       for p in (ROOT / "exactinv_check" / "selftest_certificates").glob("*.json")} != set()
    assert any(n.endswith(".dist-info/licenses/LICENSE") for n in names)
    assert "License-Expression: MIT" in metadata
    assert not any(n.startswith(("tests/", "docs/", "notebooks/")) for n in names)
