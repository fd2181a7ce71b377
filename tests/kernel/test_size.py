"""benchmarks/kernel_size.py: README.md states the size of each part of the kernel, and it is current."""


import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


_spec = importlib.util.spec_from_file_location("kernel_size", ROOT / "benchmarks" / "kernel_size.py")


kernel_size = importlib.util.module_from_spec(_spec)


_spec.loader.exec_module(kernel_size)


# ------------------------------------------------------------------ soundness

def test_every_module_is_in_one_part_and_counted():
    files = kernel_size.sources()
    sizes = kernel_size.sizes(files)
    assert sum(m for m, _, _ in sizes.values()) == len(files) == len(list((ROOT / "exactinv_check").rglob("*.py")))
    assert sum(n for _, n, _ in sizes.values()) == sum(len(t.splitlines()) for t in files.values())
    assert sizes["routes"][0] == len(list((ROOT / "exactinv_check" / "routes").glob("*.py")))
    assert (sizes["budget"][0], sizes["format"][0], sizes["selftest"][0]) == (1, 1, 1)


def test_code_lines_leave_out_blank_lines_comments_and_docstrings():
    source = '"""Module\\ndocstring."""\n\n# a comment\nx = 1  # code\n\n\ndef f():\n    """Doc."""\n    return x\n'
    assert kernel_size.code_lines(source) == 3  # x = 1, def f():, return x


# ------------------------------------------------------------------ resource

def test_readme_shows_the_current_sizes():
    expected = kernel_size.table(kernel_size.sources())
    assert kernel_size.readme_block((ROOT / "README.md").read_text()) == expected, (
        "README.md's kernel sizes are out of date: run python benchmarks/kernel_size.py --write")
