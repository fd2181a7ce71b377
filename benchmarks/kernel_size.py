"""The size of each part of the trusted kernel, exactinv_check/ (issue 26: a kernel a referee can read).

    python benchmarks/kernel_size.py            # print the table
    python benchmarks/kernel_size.py --write    # write it into README.md (between the kernel-size markers)
    python benchmarks/kernel_size.py --ref REV  # the table of another commit (git show), e.g. before a change

Parts: the trusted core (parsing, exact arithmetic, root counting, one module per claim family, the driver),
the speed-only routes (exactinv_check/routes/), the work budgets (budget.py), the certificate format
(format.py) and the selftest (selftest.py; its certificates are data, counted apart).  "lines" are physical
lines; "code" leaves out blank lines, comments and docstrings.  tests/kernel/test_size.py checks that README.md
shows what this script prints, so the numbers cannot drift."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BEGIN, END = "<!-- kernel-size:begin -->", "<!-- kernel-size:end -->"
PARTS = ("trusted core", "routes", "budget", "format", "selftest")


def part(name: str) -> str:
    """The part of the kernel a module path (relative to exactinv_check/) belongs to."""
    if name.startswith("routes/"):
        return "routes"
    return {"budget.py": "budget", "format.py": "format", "selftest.py": "selftest"}.get(name, "trusted core")


def code_lines(source: str) -> int:
    """Lines holding code: not blank, not only a comment, not inside a docstring."""
    skip = set()
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) and node.body:
            first = node.body[0]
            if isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant) and isinstance(first.value.value, str):
                skip.update(range(first.lineno, first.end_lineno + 1))
    return sum(1 for i, line in enumerate(source.split("\n"), 1)
               if line.strip() and not line.strip().startswith("#") and i not in skip)


def sources(ref: str | None = None) -> dict[str, str]:
    """Module path (relative to exactinv_check/) -> source, of the working tree or of a git revision."""
    if ref is None:
        base = ROOT / "exactinv_check"
        return {str(p.relative_to(base)): p.read_text() for p in sorted(base.rglob("*.py"))}
    names = subprocess.run(["git", "ls-tree", "-r", "--name-only", ref, "exactinv_check/"], cwd=ROOT, check=True,
                           capture_output=True, text=True).stdout.split()
    return {n.removeprefix("exactinv_check/"): subprocess.run(["git", "show", f"{ref}:{n}"], cwd=ROOT, check=True,
                                                             capture_output=True, text=True).stdout
            for n in names if n.endswith(".py")}


def sizes(files: dict[str, str]) -> dict[str, tuple[int, int, int]]:
    """Part -> (modules, lines, code lines)."""
    out = {p: (0, 0, 0) for p in PARTS}
    for name, text in files.items():
        m, n, c = out[part(name)]
        out[part(name)] = (m + 1, n + len(text.splitlines()), c + code_lines(text))
    return out


def table(files: dict[str, str]) -> str:
    """The markdown table of the parts' sizes, with the total."""
    rows = ["| kernel part | modules | lines | code lines |", "| --- | ---: | ---: | ---: |"]
    total = [0, 0, 0]
    for name, (m, n, c) in sizes(files).items():
        rows.append(f"| {name} | {m} | {n:,} | {c:,} |")
        total = [total[0] + m, total[1] + n, total[2] + c]
    rows.append(f"| all | {total[0]} | {total[1]:,} | {total[2]:,} |")
    return "\n".join(rows)


def readme_block(readme: str) -> str:
    """The table between the markers of README.md."""
    start, end = readme.index(BEGIN) + len(BEGIN), readme.index(END)
    return readme[start:end].strip()


def main(argv: list[str]) -> None:
    ref = argv[argv.index("--ref") + 1] if "--ref" in argv else None
    text = table(sources(ref))
    if "--write" in argv:
        path = ROOT / "README.md"
        readme = path.read_text()
        start, end = readme.index(BEGIN) + len(BEGIN), readme.index(END)
        path.write_text(readme[:start] + "\n" + text + "\n" + readme[end:])
    print(text)


if __name__ == "__main__":
    main(sys.argv[1:])
