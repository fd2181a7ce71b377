"""exactinv_check -- the trusted kernel of exactinv.

A small, standalone checker that re-proves every claim of an exactinv
certificate from the problem (A, G, b, the method r = g/h) and the
certificate's data alone, in exact rational arithmetic, with the Python
standard library only.  It imports nothing from exactinv and trusts no list,
bound or flag the engine wrote: generator lists are proved complete,
thresholds, radii and valid sets are recomputed, and what it cannot prove it
rejects.  Run it as ``python3 -S -m exactinv_check CERT.json``.

Modules, bottom up: failure (CheckFailure), budget (every work budget and the
one account of a certificate), rationals (strict parsing, matrices), polys (Q[x], Descartes and Sturm,
root isolation), reals (rationals, infinities, algebraic numbers), linalg
(characteristic polynomials), polyhedra (generators proved complete),
conditions (the polynomial conditions of A_d(h)P in P), validset (the exact
valid set), tail (positivity of a Taylor-coefficient tail), and one module per
family of claims: claims_invariance, claims_thresholds, claims_radius,
claims_sets; kernel is the driver.  format defines the certificate vocabulary once (claim
types, keys, versions, bounds; the JSON schema is generated from it) and selftest is the
built-in suite of genuine and forged certificates (``python3 -S -m exactinv_check.selftest``).
"""

from typing import Any

from .format import Verdict
from .kernel import FORMAT, VERSIONS, CheckReport, check

__all__ = ["check", "CheckReport", "CheckFailure", "Verdict", "FORMAT", "VERSIONS", "main"]


def main(argv: Any = None) -> int:
    """The command line (``python3 -m exactinv_check``); imported on call so that
    ``-m exactinv_check`` does not find its ``__main__`` already imported."""
    from .__main__ import main as _main

    return _main(argv)
