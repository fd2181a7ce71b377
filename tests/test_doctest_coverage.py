"""Every public function and method of exactinv carries a doctest (``>>>``).

pytest runs the doctests (``--doctest-modules`` on exactinv/); this test makes
sure there is one to run.  A public function is one whose name has no leading
underscore, defined in exactinv (its ``__module__``), and reachable from a
module's namespace or ``__all__``; the public methods of such classes count
too (properties and dunder methods do not).

``NOT_YET`` lists the names still without a doctest in the modules colleagues
are rewriting.  It is exact: the test fails if a listed name gains a doctest
or disappears, so the list can only shrink.
"""

from __future__ import annotations

import importlib
import inspect
import pkgutil

import exactinv

# In beyond/{conditions,largest}.py, interfaces/pipeline.py, model/methods.py and
# paper/{monotonicity,rational}.py (being rewritten by colleagues).
NOT_YET: set[str] = {
    "exactinv.beyond.conditions.conditions_of",
    "exactinv.beyond.conditions.distinct_conditions",
    "exactinv.beyond.largest.LargestThreshold.claims",
    "exactinv.beyond.largest.LargestThreshold.to_latex",
    "exactinv.beyond.largest.ValidSteplengths.claims",
    "exactinv.beyond.largest.ValidSteplengths.to_latex",
    "exactinv.interfaces.pipeline.certify",
    "exactinv.interfaces.pipeline.stages",
    "exactinv.model.methods.Method.matrix",
    "exactinv.model.methods.Method.to_latex",
    "exactinv.model.methods.Method.to_sympy",
    "exactinv.model.methods.backward_euler",
    "exactinv.model.methods.forward_euler",
    "exactinv.model.methods.from_butcher",
    "exactinv.model.methods.gauss2",
    "exactinv.model.methods.heun",
    "exactinv.model.methods.implicit_midpoint",
    "exactinv.model.methods.lobatto_iiic2",
    "exactinv.model.methods.matrix_polynomial",
    "exactinv.model.methods.pade",
    "exactinv.model.methods.polynomial",
    "exactinv.model.methods.preset",
    "exactinv.model.methods.radau_iia2",
    "exactinv.model.methods.rational",
    "exactinv.model.methods.rk4",
    "exactinv.model.methods.ssprk22",
    "exactinv.model.methods.ssprk33",
    "exactinv.model.methods.ssprk_s1",
    "exactinv.model.methods.taylor",
    "exactinv.model.methods.theta",
    "exactinv.model.methods.trapezoid",
    "exactinv.paper.monotonicity.AbsoluteMonotonicityRadius.claims",
    "exactinv.paper.monotonicity.AbsoluteMonotonicityRadius.to_latex",
    "exactinv.paper.monotonicity.absolute_monotonicity_radius",
    "exactinv.paper.monotonicity.taylor_coefficient_polynomials",
    "exactinv.paper.rational.first_singular_steplength",
    "exactinv.paper.rational.rational_threshold",
    "exactinv.paper.rational.smallest_positive_pole",
    "exactinv.paper.rational.spectral_abscissa",
}


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
    missing = {name for name, obj in _public_callables().items() if not _has_doctest(obj)}
    assert missing - NOT_YET == set(), f"public functions without a doctest: {sorted(missing - NOT_YET)}"


def test_the_allow_list_only_shrinks():
    found = _public_callables()
    stale = {name for name in NOT_YET if name not in found or _has_doctest(found[name])}
    assert not stale, f"remove from NOT_YET (gone or now with a doctest): {sorted(stale)}"
