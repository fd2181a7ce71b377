"""The trusted kernel, re-exported: :mod:`exactinv_check` is the checker.

``exactinv.check(cert)`` and ``exactinv check CERT.json`` run the standalone,
standard-library-only package :mod:`exactinv_check`, which imports nothing from
exactinv.  A referee runs it alone: ``python3 -S -m exactinv_check CERT.json``.
"""

from exactinv_check import CheckFailure, CheckReport, check, main

__all__ = ["check", "CheckReport", "CheckFailure", "main"]
