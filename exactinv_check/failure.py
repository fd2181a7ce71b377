"""The one exception of the kernel: a claim did not verify.  Re-exported by
:mod:`exactinv_check.rationals` (its old home) and used by
:mod:`exactinv_check.budget`, which must not import the parsers."""


class CheckFailure(Exception):
    """A claim did not verify; the message says which fact failed."""


def require(condition, message):
    """Raise :class:`CheckFailure` with ``message`` unless ``condition``."""
    if not condition:
        raise CheckFailure(message)
