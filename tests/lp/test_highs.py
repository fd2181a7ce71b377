"""exactinv.lp.highs: HiGHS' banner never reaches standard output.

Each case runs in a fresh interpreter, since the banner comes once per
process, from C++, on file descriptor 1 (pytest's capture would hide it).
"""

import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _stdout(code: str) -> str:
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_plain_highspy_prints_a_banner_or_nothing():
    """The control: what highspy itself prints (a banner from 1.8 on); the tests below must see none."""
    out = _stdout("import highspy; highspy.Highs(); print('end')")
    assert out.endswith("end\n")


@pytest.mark.parametrize("code", [
    "from exactinv.lp.highs import silent_highs; silent_highs(); silent_highs(); print('end')",
    "from exactinv.lp.highs import silence_banner; import highspy; silence_banner(); highspy.Highs(); print('end')",
    "import exactinv as ei; print(ei.optimal_gamma(ei.LinearSystem([[-1, 1], [-1, -1]]),"
    " ei.Polyhedron.box([-1, -1], [1, 1])).value); print('end')",
])
def test_no_banner_on_stdout(code):
    out = _stdout(code)
    assert "HiGHS" not in out and "Copyright" not in out
    assert out.endswith("end\n")


def test_stdout_before_the_first_solve_is_kept():
    """The redirect swallows only HiGHS' banner: what was printed before it (Python and C buffers) survives."""
    out = _stdout("import ctypes; print('before', flush=False); ctypes.CDLL(None).printf(b'c-level\\n');"
                  "from exactinv.lp.highs import silent_highs; silent_highs(); print('after')")
    assert out.split() == ["before", "c-level", "after"]


def test_certify_stdout_is_exactinvs_own():
    done = subprocess.run([sys.executable, "-m", "exactinv", "certify", "examples/paper_box_taylor4.json"],
                          capture_output=True, text=True, timeout=300, cwd=ROOT)
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("problem paper_box_taylor4:")
    assert "HiGHS" not in done.stdout
