"""exactinv.model.sets: each set type names its family, and the engine looks at a set's type in one
place only (issue 26, item 2)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

import exactinv as ei
from exactinv.model.sets import SET_TYPES, expect_set, set_family

ROOT = Path(__file__).resolve().parents[2]
SET_CLASSES = {cls.__name__ for cls in SET_TYPES.values()}


def test_each_set_type_names_its_family():
    assert set_family(ei.Polyhedron.box([-1, -1], [1, 1])) == "polyhedron"
    assert set_family(ei.Polyhedron.from_vertices([[0, 0], [1, 0], [0, 1]])) == "polyhedron"
    assert set_family(ei.Ellipsoid([[2, 0], [0, "1/2"]])) == "ellipsoid"
    assert SET_TYPES == {"polyhedron": ei.Polyhedron, "ellipsoid": ei.Ellipsoid}
    for name, cls in SET_TYPES.items():
        assert cls.family == name


@pytest.mark.parametrize("value", [None, 0, [[1, 0], [0, 1]], "polyhedron", ei.LinearSystem([[-1]]),
                                   ei.methods.taylor(2)])
def test_anything_else_has_no_family(value):
    assert set_family(value) is None
    with pytest.raises(ei.ExactinvError, match=f"^P: expected an exactinv.Polyhedron, got {type(value).__name__}$"):
        expect_set(value, "polyhedron", "P")


def test_a_set_of_the_other_family_is_refused_by_name():
    E, P = ei.Ellipsoid([[1]]), ei.Polyhedron.box([0], [1])
    assert expect_set(E, "ellipsoid", "ellipsoid") is E and expect_set(P, "polyhedron", "polyhedron") is P
    with pytest.raises(ei.InvalidInput, match="^ellipsoid: expected an exactinv.Ellipsoid, got Polyhedron$"):
        expect_set(P, "ellipsoid", "ellipsoid")
    # the public functions keep their messages
    with pytest.raises(ei.InvalidInput, match="polyhedron: got an Ellipsoid"):
        ei.optimal_gamma(ei.LinearSystem([[-1]]), E)
    with pytest.raises(ei.InvalidInput, match="^ellipsoid: expected an exactinv.Ellipsoid, got Polyhedron$"):
        from exactinv.invariance.ellipsoids import ellipsoid_continuous_invariance
        ellipsoid_continuous_invariance(ei.LinearSystem([[-1]]), P)
    with pytest.raises(ei.InvalidInput, match="^polyhedron: expected an exactinv.Polyhedron, got Ellipsoid$"):
        ei.robust_threshold([ei.LinearSystem([[-1]])], E, ei.methods.taylor(1))
    with pytest.raises(ei.InvalidInput, match="^inputs: expected an exactinv.Polyhedron"):
        ei.optimal_gain([[-1]], [[1]], P, inputs=E)


def _type_tests_on_sets(source: str) -> list[int]:
    """Lines of ``isinstance(x, ...)`` naming a set type (Polyhedron, Ellipsoid) in one module's source."""
    lines = []
    for node in ast.walk(ast.parse(source)):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "isinstance":
            kinds = node.args[1] if len(node.args) > 1 else None
            names = {n.id for n in ast.walk(kinds) if isinstance(n, ast.Name)} if kinds is not None else set()
            names |= {n.attr for n in ast.walk(kinds) if isinstance(n, ast.Attribute)} if kinds is not None else set()
            if names & SET_CLASSES:
                lines.append(node.lineno)
    return sorted(lines)


def test_the_engine_looks_at_a_set_type_in_one_place():
    found = {str(p.relative_to(ROOT)): lines for p in sorted((ROOT / "exactinv").rglob("*.py"))
             if (lines := _type_tests_on_sets(p.read_text()))}
    assert found == {"exactinv/model/sets.py": found.get("exactinv/model/sets.py", [])}, found
    assert len(found["exactinv/model/sets.py"]) == 1


def test_the_scan_sees_a_type_test():
    """The test itself: an isinstance on a set type is found (by name or attribute, alone or in a
    tuple), one on another type is not."""
    source = ("def f(P):\n"
              "    return isinstance(P, model.Ellipsoid) or isinstance(P, int)\n"
              "def g(P):\n"
              "    return isinstance(P, (int, Polyhedron))\n")
    assert _type_tests_on_sets(source) == [2, 4]
    assert _type_tests_on_sets("isinstance(P, LinearSystem)") == []
