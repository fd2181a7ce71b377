"""Output files of the command line and the batch runner: refused before any work."""

from __future__ import annotations

import os

from ..errors import InvalidInput

__all__ = ["check_writable"]


def check_writable(path: str, label: str, example: str) -> None:
    """Refuse an output ``path`` that cannot be written (``label`` names the argument,
    ``example`` is a file name to suggest inside a directory), before any computation.

    >>> check_writable("/", "out", "results.jsonl")
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: out: / is a directory; give a file name such as /results.jsonl
    """
    if os.path.isdir(path):
        raise InvalidInput(f"{label}: {path} is a directory; give a file name such as {os.path.join(path, example)}")
    parent = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(parent):
        raise InvalidInput(f"{label}: the directory {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK) or (os.path.exists(path) and not os.access(path, os.W_OK)):
        raise InvalidInput(f"{label}: {path} is not writable")
