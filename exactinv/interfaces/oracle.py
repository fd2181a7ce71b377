"""A regression oracle for floating-point implementations.

A float implementation of the paper (or of anything computing the same
quantities) outputs a number; the oracle turns that float into the exact
rational it denotes (``exact_from_float``: this is the one place where a float
is accepted, because judging it is the point) and compares it with the exact
result:

* ``valid``   -- on the safe side of the exact value; ``relative_gap`` says by how much;
* ``tight``   -- on the safe side and within ``tolerance`` (relative) of it;
* ``invalid`` -- on the wrong side; for thresholds and gamma* the verdict carries
  an exact counterexample: a rational steplength dt <= claimed and a point x of P
  whose image A_d(dt) x leaves P through ``facet``.

For pytest: ``assert_threshold(system, polyhedron, method, claimed)``.

Linear programs written in cvxpy (float implementations of gamma*, of the
forward-Euler vertex LPs, or any LP) are judged by :func:`judge_lp`: the
user's solved ``cvxpy.Problem`` is converted to exact data, solved exactly
with a verified certificate, and its reported value judged.
"""

from __future__ import annotations

from .oracle_batch import BatchRow, judge_batch, judge_row
from .oracle_judges import (
    INVALID,
    TIGHT,
    VALID,
    Status,
    Verdict,
    assert_threshold,
    judge_gamma,
    judge_radius,
    judge_root,
    judge_threshold,
)
from .oracle_lp import LPVerdict, judge_lp

__all__ = ["Status", "Verdict", "LPVerdict", "BatchRow", "judge_threshold", "judge_gamma", "judge_root", "judge_radius",
           "judge_lp", "assert_threshold", "judge_batch", "judge_row", "VALID", "TIGHT", "INVALID"]
