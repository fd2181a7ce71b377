"""The one exception of the kernel: a claim did not verify.  Every kernel module
imports it from here (:mod:`exactinv_check.budget` among them, which must not
import the parsers)."""

from __future__ import annotations

from typing import Any


class CheckFailure(Exception):
    """A claim did not verify; the message says which fact failed."""


def require(condition: Any, message: str) -> None:
    """Raise :class:`CheckFailure` with ``message`` unless ``condition``."""
    if not condition:
        raise CheckFailure(message)
