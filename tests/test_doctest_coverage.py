"""Every public function and method of exactinv carries a doctest (``>>>``).

pytest runs the doctests (``--doctest-modules`` on exactinv/); this test makes
sure there is one to run.  A public function is one whose name has no leading
underscore, defined in exactinv (its ``__module__``), and reachable from a
module's namespace or ``__all__``; the public methods of such classes count
too (properties and dunder methods do not).

There is no allow-list: a new public function without a doctest fails this
test.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import exactinv


def _modules():
    for info in pkgutil.walk_packages(exactinv.__path__, "exactinv."):
        if info.name.endswith("__main__"):
            continue
        yield importlib.import_module(info.name)


def _public_callables():
    """(qualified name, object) of every public function and method defined in exactinv."""
    seen: dict[str, object] = {}
    for module in _modules():
        names = set(getattr(module, "__all__", ())) | {n for n in vars(module) if not n.startswith("_")}
        for name in sorted(names):
            obj = getattr(module, name, None)
            if getattr(obj, "__module__", None) != module.__name__ or name.startswith("_"):
                continue
            if inspect.isfunction(obj):
                seen[f"{module.__name__}.{name}"] = obj
            elif inspect.isclass(obj):
                for attr, value in vars(obj).items():
                    if attr.startswith("_"):
                        continue
                    func = value.__func__ if isinstance(value, (staticmethod, classmethod)) else value
                    if inspect.isfunction(func) and func.__qualname__.startswith(obj.__qualname__ + "."):
                        seen[f"{module.__name__}.{obj.__qualname__}.{attr}"] = func
    return seen


def _has_doctest(obj) -> bool:
    return ">>>" in (obj.__doc__ or "")  # its own docstring, not one inherited


def test_every_public_function_has_a_doctest():
    missing = sorted(name for name, obj in _public_callables().items() if not _has_doctest(obj))
    assert not missing, f"public functions without a doctest: {missing}"


def test_the_scan_sees_the_public_api():
    # guards against a scan that finds nothing (and so cannot fail)
    found = _public_callables()
    for name in ("exactinv.model.families.taylor", "exactinv.model.method.Method.matrix",
                 "exactinv.conditions.polyhedron.ConditionSet.all", "exactinv.thresholds.rational.rational_threshold"):
        assert name in found, name
