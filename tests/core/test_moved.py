"""Old spellings of moved names (exactinv/core/moved.py): each warns with a DeprecationWarning naming
the new home and gives the very object of the new home; the package itself never uses them."""

import importlib
import warnings

import pytest

from exactinv.core.moved import moved_names

MOVED = [
    ("exactinv.core.scalars", name, "exactinv.core.flintq")
    for name in ("dyadic_of", "fmpq_column", "fmpq_matrix", "fmpq_of", "fraction_of", "matrix_of", "vector_of")
] + [
    ("exactinv.core.algebraic", "significant_digits", "exactinv.core.digits"),
    ("exactinv.core.algebraic", "sign_at", "exactinv.core.polys"),
    ("exactinv.interfaces.problem", "METHOD_KINDS", "exactinv.interfaces.method_format"),
    ("exactinv.interfaces.problem", "method_from_text", "exactinv.interfaces.method_format"),
    ("exactinv.interfaces.problem", "did_you_mean", "exactinv.interfaces.strict_json"),
] + [("exactinv.lp.hint", name, "exactinv.lp.hint_types") for name in ("LPStatus", "Basis", "Hint", "UNKNOWN_HINT", "HintModel")]


@pytest.mark.parametrize("old, name, home", MOVED)
def test_an_old_spelling_warns_and_gives_the_same_object(old, name, home):
    module = importlib.import_module(old)
    with pytest.warns(DeprecationWarning, match=f"{old}.{name} moved: import it from {home}"):
        value = getattr(module, name)
    assert value is getattr(importlib.import_module(home), name)


@pytest.mark.parametrize("old, name, home", MOVED[:1] + MOVED[-1:])
def test_from_import_of_an_old_spelling_warns(old, name, home):
    with pytest.warns(DeprecationWarning):
        exec(f"from {old} import {name}", {})


def test_the_new_homes_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for _, name, home in MOVED:
            getattr(importlib.import_module(home), name)


def test_an_unknown_name_is_still_an_attribute_error():
    import exactinv.core.scalars as scalars

    with pytest.raises(AttributeError, match="has no attribute 'no_such_name'"):
        scalars.no_such_name  # noqa: B018
    with pytest.raises(AttributeError):
        moved_names("m", {"a": "exactinv.core.flintq"})("b")


# ------------------------------------------------------------------ whole modules (issue 26: paper/ and beyond/ re-filed)

from exactinv.core.moved import OLD_MODULE_PATHS  # noqa: E402


@pytest.mark.parametrize("old, home", sorted(OLD_MODULE_PATHS.items()))
def test_an_old_module_path_imports_warns_and_serves_the_new_module(old, home):
    import sys

    new = importlib.import_module(home)
    sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning, match=f"module {old} moved: import it from {home}"):
        stand_in = importlib.import_module(old)
    public = getattr(new, "__all__", None) or [n for n in vars(new) if not n.startswith("_")]
    assert public
    for name in public:
        with pytest.warns(DeprecationWarning, match=f"{old}.{name} moved: import it from {home}"):
            assert getattr(stand_in, name) is getattr(new, name)
    with pytest.raises(AttributeError):
        stand_in.no_such_name  # noqa: B018


def test_documented_old_spellings_still_work():
    """The spellings the notebooks, examples and docs used before issue 26."""
    from exactinv.conditions.polyhedron import ConditionSet
    from exactinv.monotonicity.radius import absolute_monotonicity_radius
    from exactinv.thresholds.bisection import paper_bisection_float

    with pytest.warns(DeprecationWarning):
        from exactinv.paper.bisection import paper_bisection_float as old_bisection
    with pytest.warns(DeprecationWarning):
        from exactinv.paper.monotonicity import absolute_monotonicity_radius as old_radius
    with pytest.warns(DeprecationWarning):
        from exactinv.beyond.conditions import ConditionSet as old_conditions
    import sys

    sys.modules.pop("exactinv.paper.rational", None)  # a module warns when it is imported (once per process)
    vars(sys.modules.get("exactinv.paper", sys)).pop("rational", None)
    with pytest.warns(DeprecationWarning, match="module exactinv.paper.rational moved"):
        from exactinv.paper import rational
    assert (old_bisection, old_radius, old_conditions) == (paper_bisection_float, absolute_monotonicity_radius,
                                                           ConditionSet)
    with pytest.warns(DeprecationWarning, match="rational_threshold moved: import it from exactinv.thresholds.rational"):
        assert rational.rational_threshold is importlib.import_module("exactinv.thresholds.rational").rational_threshold


def test_the_old_packages_hold_no_code():
    """paper/ and beyond/ are gone from the tree: an old path is only a stand-in, and every new home is real."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[2] / "exactinv"
    assert not (root / "paper").exists() and not (root / "beyond").exists()
    for home in OLD_MODULE_PATHS.values():
        assert (root.parent / (home.replace(".", "/") + ".py")).is_file(), home
