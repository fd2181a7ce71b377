"""The kernel's exceptions: a claim did not verify (:class:`CheckFailure`), or did not fit the
kernel's work budget (:class:`OverBudget`, a CheckFailure).  Imported from here by every
kernel module (none re-exports them) and used by :mod:`exactinv_check.budget`, which
must not import the parsers.

Any *other* exception raised while a claim is checked is a fault of the kernel, not of the
certificate: :func:`exactinv_check.kernel.check` reports it as ``kind == "kernel-fault"`` (and
never accepts)."""

from typing import Any


class CheckFailure(Exception):
    """A claim did not verify; the message says which fact failed."""


class OverBudget(CheckFailure):
    """A claim would cost more than the kernel's work or time budget: rejected, never run to the end."""


class Record(dict):
    """A record of a certificate (a claim) as a check reads it: a key the check needs and the record lacks
    (one required only in some cases, e.g. gamma*'s H with a finite value) rejects the claim -- a
    :class:`CheckFailure`, not a KeyError (which would be a kernel fault)."""

    __slots__ = ()

    def __missing__(self, key: Any) -> Any:
        raise CheckFailure(f"the claim has no {key!r}, which it needs here")


def require(condition: Any, message: Any) -> Any:
    """Raise :class:`CheckFailure` with ``message`` unless ``condition``.  ``message`` may be a
    function of no arguments returning the text: it is called only on failure (a message that
    prints an algebraic number refines it to many digits -- work a passing check never needs)."""
    if not condition:
        raise CheckFailure(message() if callable(message) else message)


def require_budget(condition: Any, message: Any) -> Any:
    """Raise :class:`OverBudget` with ``message`` unless ``condition`` (a bound on work, not on the format)."""
    if not condition:
        raise OverBudget(message)
