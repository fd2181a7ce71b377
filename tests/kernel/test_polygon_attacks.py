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


# ------------------------------------------------------------------ soundness

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


# ------------------------------------------------------------------ resource

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
