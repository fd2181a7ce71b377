"""The console entry point ``exactinv`` (``exactinv.cli:main``); the command
line itself lives in :mod:`exactinv.interfaces.cli`."""

from .interfaces.cli import main

__all__ = ["main"]
