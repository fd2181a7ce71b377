"""The valid set the kernel derives from an ``lp`` record, and its comparison with a certificate's
intervals: the truth test shared by the lp_pieces attack files and the dual-piece fuzzer."""

from exactinv_check.failure import CheckFailure
from exactinv_check.kernel import Problem
from exactinv_check.reals import Real
from exactinv_check.routes import lp_pieces
from exactinv_check.validset import valid_set


def kernel_set(problem, record):
    """The valid set the kernel derives from an lp record (equalities included), or None when it rejects."""
    try:
        p = Problem(problem)
        _, D, inequalities, equalities, horizon = lp_pieces.lp_conditions(p, record)
        lp_pieces.require_horizon(D, inequalities, equalities, horizon, {}, "set")
        return valid_set(D, list(inequalities), list(equalities))
    except CheckFailure:
        return None


def same(W, intervals):
    """The kernel's intervals equal a certificate's intervals (exact ends, closedness)."""
    if len(W) != len(intervals):
        return False
    for w, t in zip(W, intervals):
        lo, hi = Real.parse(t["lo"]), Real.parse(t["hi"])
        if w.lo.compare(lo) or w.hi.compare(hi) or bool(w.lo_closed) != t["lo_closed"]:
            return False
        if not hi.inf and bool(w.hi_closed) != t["hi_closed"]:
            return False
    return True
