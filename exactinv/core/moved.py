"""Names and modules that moved: the old spelling still works, with a DeprecationWarning.

A module whose names moved sets ``__getattr__ = moved_names(__name__, {name: new_module})``
(PEP 562): ``from old import name`` and ``old.name`` then warn, naming the new home, and
return the very same object.  A whole module that moved (issue 26: ``exactinv.paper`` and
``exactinv.beyond`` were re-filed by mathematics) is named in OLD_MODULE_PATHS; the package
installs :func:`install_moved_modules` once, and ``import old`` then gives a stand-in module
that warns and serves every name of the new module.  Only names and modules documented in the
README keep an old spelling; the package itself imports every name from its home
(tests/test_layering.py).
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import sys
import types
import warnings
from typing import Any, Callable, Mapping, Sequence

__all__ = ["moved_names", "OLD_MODULE_PATHS", "install_moved_modules"]

# issue 26: the README's layout listed these modules under exactinv/paper and exactinv/beyond
OLD_MODULE_PATHS: Mapping[str, str] = {
    "exactinv.paper.witness": "exactinv.invariance.witness",
    "exactinv.paper.gamma_star": "exactinv.invariance.gamma_star",
    "exactinv.paper.gamma_batch": "exactinv.invariance.gamma_batch",
    "exactinv.paper.gamma_dense": "exactinv.invariance.gamma_dense",
    "exactinv.paper.invariance": "exactinv.invariance.polyhedra",
    "exactinv.paper.monotonicity": "exactinv.monotonicity.radius",
    "exactinv.paper.monotonicity_radius": "exactinv.monotonicity.result",
    "exactinv.paper.monotonicity_tail": "exactinv.monotonicity.tail",
    "exactinv.paper.poles": "exactinv.monotonicity.poles",
    "exactinv.paper.line_poles": "exactinv.monotonicity.line_poles",
    "exactinv.paper.balanced_tie": "exactinv.monotonicity.balanced_tie",
    "exactinv.paper.bernstein": "exactinv.monotonicity.bernstein",
    "exactinv.paper.polynomial": "exactinv.thresholds.polynomial",
    "exactinv.paper.rational": "exactinv.thresholds.rational",
    "exactinv.paper.spectral": "exactinv.thresholds.spectral",
    "exactinv.paper.threshold": "exactinv.thresholds.steplength",
    "exactinv.paper.forward_euler": "exactinv.thresholds.forward_euler",
    "exactinv.paper.bisection": "exactinv.thresholds.bisection",
    "exactinv.beyond.ellipsoid_eigenvalue": "exactinv.thresholds.ellipsoid_forward_euler",
    "exactinv.beyond.ellipsoid_invariance": "exactinv.invariance.ellipsoids",
    "exactinv.beyond.conditions": "exactinv.conditions.polyhedron",
    "exactinv.beyond.box_conditions": "exactinv.conditions.box",
    "exactinv.beyond.ellipsoid_conditions": "exactinv.conditions.ellipsoid",
    "exactinv.beyond.pruning": "exactinv.conditions.pruning",
    "exactinv.beyond.pruning_rational": "exactinv.conditions.pruning_rational",
    "exactinv.beyond.lp_route": "exactinv.validset.lp_route",
}


def moved_names(module: str, homes: Mapping[str, str]) -> Callable[[str], Any]:
    """A module-level ``__getattr__`` for ``module`` serving each name of ``homes`` from its new
    module, with a DeprecationWarning; any other missing name is an AttributeError as usual.

    >>> import warnings
    >>> get = moved_names("exactinv.core.scalars", {"fraction_of": "exactinv.core.flintq"})
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     f = get("fraction_of")
    >>> from exactinv.core.flintq import fraction_of
    >>> f is fraction_of, caught[0].category.__name__
    (True, 'DeprecationWarning')
    >>> str(caught[0].message)
    'exactinv.core.scalars.fraction_of moved: import it from exactinv.core.flintq'
    """
    homes = dict(homes)

    def __getattr__(name: str) -> Any:
        home = homes.get(name)
        if home is None:
            raise AttributeError(f"module {module!r} has no attribute {name!r}")
        warnings.warn(f"{module}.{name} moved: import it from {home}", DeprecationWarning, stacklevel=2)
        return getattr(importlib.import_module(home), name)

    return __getattr__


class _MovedModules(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds each old module path of ``homes`` (and its old package) and loads a stand-in for it."""

    def __init__(self, homes: Mapping[str, str]) -> None:
        self.homes = dict(homes)
        self.packages = {old.rsplit(".", 1)[0] for old in self.homes}

    def find_spec(self, fullname: str, path: Sequence[str] | None = None,
                  target: types.ModuleType | None = None) -> importlib.machinery.ModuleSpec | None:
        if fullname in self.homes or fullname in self.packages:
            return importlib.util.spec_from_loader(fullname, self, is_package=fullname in self.packages)
        return None

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType | None:
        return None  # the default module object

    def exec_module(self, module: types.ModuleType) -> None:
        old = module.__name__
        if old in self.packages:
            module.__path__ = []
            module.__doc__ = f"{old}: an old package, re-filed by mathematics (issue 26); its modules warn."
            return
        home = self.homes[old]
        warnings.warn(f"module {old} moved: import it from {home}", DeprecationWarning, stacklevel=2)
        module.__doc__ = f"{old}: moved to {home} (a stand-in that warns)."

        def __getattr__(name: str) -> Any:
            if name.startswith("__"):
                raise AttributeError(f"module {old!r} has no attribute {name!r}")
            target = importlib.import_module(home)
            if not hasattr(target, name):
                raise AttributeError(f"module {old!r} has no attribute {name!r}")
            warnings.warn(f"{old}.{name} moved: import it from {home}", DeprecationWarning, stacklevel=2)
            return getattr(target, name)

        module.__getattr__ = __getattr__  # type: ignore[method-assign]


def install_moved_modules(homes: Mapping[str, str] = OLD_MODULE_PATHS) -> None:
    """Make every old module path of ``homes`` importable, as a stand-in that warns (DeprecationWarning)
    and serves the very objects of the new module.  Installed once (the package's ``__init__`` calls it).

    >>> install_moved_modules()
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     from exactinv.paper.bisection import paper_bisection
    >>> from exactinv.thresholds.bisection import paper_bisection as new
    >>> paper_bisection is new, caught[-1].category.__name__
    (True, 'DeprecationWarning')
    >>> str(caught[-1].message)
    'exactinv.paper.bisection.paper_bisection moved: import it from exactinv.thresholds.bisection'
    """
    if not any(isinstance(finder, _MovedModules) for finder in sys.meta_path):
        sys.meta_path.append(_MovedModules(homes))
