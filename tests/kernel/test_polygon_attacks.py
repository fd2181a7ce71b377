"""Attacks on the kernel's fast paths (polygon.py,
validset.py condition by condition, polys.no_root_between / sign_right_of, the
packed pruning test in pruning.py).

No soundness hole was found (see the report); the findings are RESOURCE holes:
work proportional to (listed points) x (facets) or to (surviving pairs) that no
budget priced before it ran.  Each is a test that asserts the CORRECT
behaviour (the work is bounded before it is done); all four are fixed (extra
points priced, surviving pairs counted against MAX_CONDITIONS = 500,000 while they
are found, the packed table bounded).  To stay fast the tests count the work the kernel would
do instead of doing it (monkeypatched counters), or extrapolate from a small
instance.
"""

from fractions import Fraction as F

import pytest
from pruning_helpers import polygon_rows

from exactinv_check import budget, check, conditions
from exactinv_check.failure import CheckFailure
from exactinv_check.polyhedra import prove_generators
from exactinv_check.routes import polygon, pruning

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


def _parabola_polygon(m):
    """A convex m-gon: (i, i^2) for i < m - 1 and an apex far above; its rows, counter-clockwise."""
    pts = [(F(i), F(i * i)) for i in range(m - 1)] + [(F(m // 2), F(4 * m * m))]
    return pts, *polygon_rows(pts)


def _certificate(pts, G, b, extra=(), vertex=1, horizon="2"):
    """x' = -x, forward Euler, P the polygon; a pruning record whose vertex (1, 1) bounds the set by 2."""
    s = str
    V = [[s(x) for x in v] for v in list(pts) + list(extra)]
    claim = {"type": "valid_steplengths", "vertices": V, "rays": [], "lines": [],
             "intervals": [{"lo": "0", "hi": "1", "lo_closed": True, "hi_closed": True}],
             "pruning": {"horizon": horizon, "vertex": vertex, "order": list(range(len(V)))}}
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": [["-1", "0"], ["0", "-1"]], "G": [[s(x) for x in g] for g in G], "b": [s(x) for x in b],
                        "method": {"name": "custom", "numerator": ["1", "1"], "denominator": ["1"]}},
            "claims": [claim]}


# --------------------------------------------------------------------------
# 1. polygon.prove_polygon: every listed point beyond the corners costs m row tests, unpriced
#
# The corners of a 20,000-gon are proved in 0.34 s, but each further listed point
# (an interior point, a repeated corner) goes through _require_in against all m
# rows.  Measured: m = 20,000 facets and 8,000 interior points listed (a 1.4 MB
# certificate) take 20 s before the claim is even looked at; 20,000 points ~ 50 s,
# 40,000 ~ 100 s.  (The general edge walk has the same V x m slack test, but it is
# slow for the corners too; the fast path makes the extras the whole cost.)
# A fix: price len(extra) * m before testing, or test each point in O(log m)
# against the sorted corners (binary search on the angle around an interior point).

def test_extra_listed_points_of_a_big_polygon_are_priced(monkeypatch):
    m, extras = 20_000, 20_000
    pts, G, b = _parabola_polygon(m)
    interior = [[F(m // 2), F(m * m + k)] for k in range(extras)]
    work = []

    def counted(rows, v, i):  # the work _require_in would do, without doing it
        work.append(len(rows))

    monkeypatch.setattr(polygon, "_require_in", counted)
    try:
        prove_generators(G, b, [list(p) for p in pts] + interior, [], [])
    except Exception:  # a budget rejection is the correct outcome
        pass
    assert sum(work) <= 10**8, f"{sum(work):.1e} row tests (~{sum(work) / 7e6:.0f} s) before any verdict"


# --------------------------------------------------------------------------
# 2. pruning.survivors: the surviving pairs are all built before MAX_CONDITIONS is checked
#
# pruning.survivors returns every pair its test keeps, as {vertex: [facets]}, and
# only conditions.condition_polynomials then compares their number with
# MAX_CONDITIONS = 20,000,000.  A 20,000-gon (1.16 MB certificate, the one of
# _certificate below with m = 20,000) keeps 144,156,176 pairs: the kernel runs
# 408 s and reaches 13.4 GB resident memory before it rejects with
# "144156176 generator-facet conditions exceed the kernel's bound".
# A fix: count the pairs in survivors (_descend) and reject as soon as the count
# passes MAX_CONDITIONS (the same bound, just before the lists are built).

def test_survivors_stop_at_the_condition_bound(monkeypatch):
    bound = 2_000
    monkeypatch.setattr(budget, "MAX_CONDITIONS", bound)  # what pruning.survivors reads
    monkeypatch.setattr(conditions, "MAX_CONDITIONS", bound)  # conditions' own binding of it
    built = []
    original = pruning.survivors

    def counted(*args):
        out = original(*args)
        built.append(sum(len(f) for f in out.values()))
        return out

    monkeypatch.setattr(pruning, "survivors", counted)
    pts, G, b = _parabola_polygon(200)
    report = check(_certificate(pts, G, b))
    assert not report.ok and "exceed" in str(report)
    assert sum(built) <= bound + 2 * len(G), f"{sum(built)} pairs built for a bound of {bound}"


# --------------------------------------------------------------------------
# 3. MAX_CONDITIONS = 20,000,000 is not a 30 s budget
#
# Each built condition costs about 35-40 us (condition_polynomials, then the
# Descartes skip in valid_set), so 20,000,000 conditions, which the kernel
# accepts to build, are about 12 minutes.  Measured on the genuine certificate of
# _certificate: m = 1,500 (76 KB) keeps 779,828 pairs and verifies in 27 s;
# m = 3,000 (157 KB) keeps 3,132,070 pairs and takes over 2 minutes.
# (The bound itself, 20,000,000 then, is now 500,000: about 20-45 s of conditions at the 40-90 us
# per condition measured here and in CI; a timing assertion would be flaky, so the measurement lives
# in the comment of conditions.MAX_CONDITIONS.)

# --------------------------------------------------------------------------
# 4. pruning._Packed: one long row widens every slot
#
# The slot width is set by the largest row and box entry over ALL rows, so one
# row with a 3000-digit entry (a redundant facet 10^3000 x <= 10^3001) gives every
# one of the m short rows a ~1250-byte slot, in each of the 2n + 2 columns of the
# table (2n + 1 since the remainder widens each coordinate on its own).  Measured (survivors on the 4
# corners of a square, T = 2, A = -I, forward Euler): 20,001 rows -> 380 MB resident, 100,001 rows (about 1.5 MB of G) ->
# 1.85 GB, a memory amplification of about 1000x.  (Time stays a few seconds.)
# A fix: price m x slot width before building the table, or pack rows in groups of
# similar size (a slot width per group), or test the long rows one by one.

def test_one_long_row_does_not_widen_every_slot():
    """Fixed by a bound on the packed table (MAX_PACKED_BYTES): 25,001 rows in 1250-byte slots would
    need 156 MB in the 5 columns; the kernel rejects before building it."""
    m = 25_000
    G = [[F(1), F(k, m)] for k in range(m)] + [[F(10**3000), F(0)]]
    b = [F(10)] * m + [F(10**3001)]
    square = [[F(1), F(1)], [F(-1), F(1)], [F(-1), F(-1)], [F(1), F(-1)]]
    N = [[[F(1), F(0)], [F(0), F(1)]], [[F(-1), F(0)], [F(0), F(-1)]]]  # forward Euler on x' = -x
    with pytest.raises(CheckFailure, match="packed in slots"):
        pruning.survivors(G, b, square, N, F(2))
