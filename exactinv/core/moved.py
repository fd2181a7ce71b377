"""Names that moved to another module: the old spelling still works, with a DeprecationWarning.

A module whose names moved sets ``__getattr__ = moved_names(__name__, {name: new_module})``
(PEP 562): ``from old import name`` and ``old.name`` then warn, naming the new home, and
return the very same object.  Only names documented in the README keep an old spelling;
the package itself imports every name from its home (tests/test_layering.py).
"""

from __future__ import annotations

import importlib
import warnings
from typing import Any, Callable, Mapping

__all__ = ["moved_names"]


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
