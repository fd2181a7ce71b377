"""The package's layers, checked from the source (AST, nothing is imported).

    errors <- core <- lp <- model <- {invariance, monotonicity, conditions} <- thresholds
           <- {validset, control, certificates} <- interfaces <- top

Every import inside ``exactinv`` must point to the same or a lower layer,
``invariance``, ``monotonicity`` and ``conditions`` never import each other, the module import graph has
no cycle, and no import sits inside a function except optional heavy extras.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "exactinv"

LAYERS = {
    "errors": 0,
    "core": 1,
    "lp": 2,
    "model": 3,
    # rooms by mathematics (issue 26), the paper's Section 2 and 3.2 and the conditions beyond it
    "invariance": 4,  # continuous and discrete invariance, gamma* (polyhedra, ellipsoids)
    "monotonicity": 4,  # the radius of absolute monotonicity
    "conditions": 4,  # the polynomial conditions of A_d(h) S in S, their certified pruning
    "thresholds": 5,  # the paper's thresholds from gamma* and rho, forward Euler, the paper's bisection
    "validset": 6,  # the one valid-set engine and its routes (issue 26)
    "control": 6,  # gain design and robust thresholds (issue 25)
    "certificates": 6,
    "interfaces": 7,
    "top": 8,  # exactinv/__init__, __main__, cli (the entry point), check (the kernel re-exported)
}
SIBLINGS_THAT_NEVER_MEET = {(a, b) for a in ("invariance", "monotonicity", "conditions")
                            for b in ("invariance", "monotonicity", "conditions") if a != b}
# Optional heavy extras, imported where they are used.  cvxpy: only the cvxpy
# hint backend (exactinv/lp/hint.py) and the oracle's judge_lp need it, so it
# stays an optional dependency.  dask: only `exactinv batch` (interfaces/batch/engine.py)
# schedules on it (the `batch` extra).  nodepy: only ei.methods.from_nodepy
# (model/nodepy_methods.py) reads its method objects (the `nodepy` extra).
IN_FUNCTION_ALLOWED = ("matplotlib", "sympy", "IPython", "cvxpy", "dask", "nodepy")


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


MODULES = {_module_name(p): p for p in sorted(PACKAGE.rglob("*.py"))}


def _layer(module: str) -> str:
    parts = module.split(".")
    if len(parts) == 1 or parts[1] in ("__main__", "cli", "check"):
        return "top"
    if parts[1] not in LAYERS:
        raise AssertionError(f"{module} belongs to no layer: add its package to LAYERS in tests/test_layering.py")
    return parts[1]


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> list[str]:
    """The exactinv modules an ``from ... import ...`` names."""
    if node.level:
        base = module.split(".") if is_package else module.split(".")[:-1]
        base = base[: len(base) - (node.level - 1)]
        target = ".".join(base + ([node.module] if node.module else []))
    else:
        target = node.module or ""
    if not (target == "exactinv" or target.startswith("exactinv.")):
        return []
    out = []
    for alias in node.names:  # "from . import display" names the module exactinv.display
        sub = f"{target}.{alias.name}"
        out.append(sub if sub in MODULES else target)
    return out


def _imports(module: str):
    """(imported exactinv module, line, inside a function?) and the in-function
    imports of anything, for one module."""
    path = MODULES[module]
    tree = ast.parse(path.read_text(), filename=str(path))
    is_package = path.name == "__init__.py"
    found, in_function = [], []

    def visit(node, depth):
        for child in ast.iter_child_nodes(node):
            inner = depth + isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
            if isinstance(child, ast.Import):
                names = [a.name for a in child.names]
                found.extend((n, child.lineno) for n in names if n == "exactinv" or n.startswith("exactinv."))
                if inner:
                    in_function.extend((n, child.lineno) for n in names)
            elif isinstance(child, ast.ImportFrom):
                found.extend((t, child.lineno) for t in _resolve(module, is_package, child))
                if inner:
                    in_function.append(("." * child.level + (child.module or ""), child.lineno))
            visit(child, inner)

    visit(tree, 0)
    return found, in_function


GRAPH = {m: _imports(m) for m in MODULES}


def test_every_module_has_a_layer():
    for module in MODULES:
        _layer(module)


@pytest.mark.parametrize("module", sorted(MODULES))
def test_imports_point_down(module):
    here = _layer(module)
    for target, line in GRAPH[module][0]:
        there = _layer(target)
        assert (here, there) not in SIBLINGS_THAT_NEVER_MEET, f"{module}:{line} imports {target}: siblings never meet"
        assert LAYERS[there] <= LAYERS[here], f"{module}:{line} ({here}) imports {target} ({there}): up a layer"


@pytest.mark.parametrize("module", sorted(MODULES))
def test_no_import_inside_functions(module):
    for name, line in GRAPH[module][1]:
        root = name.lstrip(".").split(".")[0]
        assert root in IN_FUNCTION_ALLOWED, f"{module}:{line} imports {name or '.'} inside a function"


def test_no_import_cycle():
    edges = {m: {t for t, _ in GRAPH[m][0] if t in MODULES and t != m} for m in MODULES}
    # a package's __init__ may re-export its own submodules: that is not a cycle back into it
    for m in MODULES:
        edges[m] = {t for t in edges[m] if not (m.startswith(t + ".") and MODULES[t].name == "__init__.py")}
    state: dict[str, int] = {}

    def visit(m, path):
        state[m] = 1
        for t in sorted(edges[m]):
            if state.get(t) == 1:
                cycle = path[path.index(t):] + [t]
                raise AssertionError("import cycle: " + " -> ".join(cycle))
            if t not in state:
                visit(t, path + [t])
        state[m] = 2

    for m in sorted(MODULES):
        if m not in state:
            visit(m, [m])


def test_the_kernel_imports_nothing_from_the_engine():
    for path in sorted((ROOT / "exactinv_check").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                assert not any(a.name.split(".")[0] == "exactinv" for a in node.names), path
            elif isinstance(node, ast.ImportFrom) and node.level == 0:
                assert (node.module or "").split(".")[0] != "exactinv", path


def test_the_layering_test_sees_an_upward_import():
    """The test itself: a core module importing invariance would be caught."""
    node = ast.parse("from ..invariance.gamma_star import optimal_gamma").body[0]
    target = _resolve("exactinv.core.roots", False, node)[0]
    assert LAYERS[_layer(target)] > LAYERS[_layer("exactinv.core.roots")]


# ------------------------------------------------------------------ private names stay private (issue 26)

def _private_cross_imports(path: Path, source: str | None = None) -> list[str]:
    """``from <project module> import _name`` and ``<imported project module>._name`` in one file of
    exactinv/ or exactinv_check/: a private name used outside its module (dunder names excepted)."""
    package = path.relative_to(ROOT).parts[0]
    tree = ast.parse(source if source is not None else path.read_text())
    is_package = path.name == "__init__.py"
    here = _module_name(path) if package == "exactinv" else ".".join(path.relative_to(ROOT).with_suffix("").parts)

    def private(name: str) -> bool:
        return name.startswith("_") and not name.startswith("__")

    def project(target: str) -> bool:
        return target.split(".")[0] in ("exactinv", "exactinv_check")

    found, modules = [], set()
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = here.split(".") if is_package else here.split(".")[:-1]
                base = base[: len(base) - (node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if not project(target):
                continue
            for alias in node.names:
                if private(alias.name):
                    found.append(f"{path.relative_to(ROOT)}:{node.lineno} imports {alias.name} from {target}")
                else:
                    modules.add(alias.asname or alias.name)  # maybe a module: checked below
        elif isinstance(node, ast.Import):
            for alias in node.names:
                if project(alias.name):
                    modules.add(alias.asname or alias.name.split(".")[0])
    for node in ast.walk(tree):
        if (isinstance(node, ast.Attribute) and private(node.attr) and isinstance(node.value, ast.Name)
                and node.value.id in modules):
            found.append(f"{path.relative_to(ROOT)}:{node.lineno} uses {node.value.id}.{node.attr}")
    return found


def test_no_private_name_crosses_a_module_boundary():
    """A name with a leading underscore is used only in its own module: what two modules share is
    public (documented, no underscore) or lives where it is used."""
    found = [hit for package in ("exactinv", "exactinv_check")
             for path in sorted((ROOT / package).rglob("*.py")) for hit in _private_cross_imports(path)]
    assert found == [], "\n".join(found)


def test_the_private_name_test_sees_a_private_import():
    """The test itself: both forms are caught, a dunder and a public name are not."""
    path = ROOT / "exactinv_check" / "polys.py"
    assert len(_private_cross_imports(path, "from .cones import _primitive, primitive, __doc__")) == 1
    assert len(_private_cross_imports(path, "from . import cones\ncones._reduce(1, 2)\ncones.__name__")) == 1
    assert len(_private_cross_imports(ROOT / "exactinv" / "core" / "roots.py", "from ..monotonicity import tail as t\nt._x")) == 1
    assert _private_cross_imports(path, "from fractions import _gcd") == []
