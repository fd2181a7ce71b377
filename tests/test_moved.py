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
