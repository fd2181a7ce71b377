"""exactinv_check.routes: the speed-only routes are apart from the trusted core (issue 26, item 3).

The core reaches them at two dispatch points only (claims_sets, polyhedra); the routes import the core, never the
other way round; and each route module is documented in the package's docstring."""


import ast
from pathlib import Path

import exactinv_check
import exactinv_check.routes as routes

PACKAGE = Path(exactinv_check.__file__).resolve().parent


DISPATCH = {"claims_sets.py", "polyhedra.py"}


def _imports_from_routes(path: Path) -> set[str]:
    """The route modules a core module imports (from .routes import x, from .routes.x import ..., import ...routes)."""
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom) and node.module is not None and node.level >= 1:
            parts = node.module.split(".")
            if parts[0] == "routes":
                found |= {parts[1]} if len(parts) > 1 else {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("exactinv_check.routes"):
            found.add(node.module)
        elif isinstance(node, ast.Import):
            found |= {a.name for a in node.names if a.name.startswith("exactinv_check.routes")}
    return found


# ------------------------------------------------------------------ soundness

def test_the_scan_sees_every_form_of_import():
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "m.py"
        p.write_text("from .routes import pruning, boxes\nfrom .routes.polygon import prove_polygon\nfrom . import polys\n")
        assert _imports_from_routes(p) == {"pruning", "boxes", "polygon"}


def test_only_the_dispatch_points_import_routes():
    importers = {path.name: sorted(names) for path in sorted(PACKAGE.glob("*.py"))
                 if (names := _imports_from_routes(path))}
    assert set(importers) == DISPATCH, importers
    assert importers["polyhedra.py"] == ["polygon"]


def test_routes_are_documented_and_exist():
    modules = sorted(p.stem for p in (PACKAGE / "routes").glob("*.py") if p.stem != "__init__")
    assert modules == ["boxes", "lp_duals", "lp_pieces", "polygon", "pruning", "pruning_rational"]
    for name in modules:
        assert f"* {name} -- " in routes.__doc__, name


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
