"""exactinv_check.routes.pruning_rational, attacked: the kernel's pruning in u = h/(s + h),
its use in claims_sets / conditions (``without_D``) and the chord-end test of pruning.py.

Soundness held on about 11,000 random (problem, record) pairs (2-D and 3-D, rational methods with
poles on both sides, polynomial methods, records with U in {0, 1, 1 - 2^-k, ...}, scales 2^-63..2^63):
every record the kernel accepted gave the unpruned valid set / first end.  The hole found was a
resource one: the Bernstein pieces were priced by their count only, not by the size of the numbers
(method coefficients, the 64-bit scale), and with U = 1 nothing else is checked before them (175 s
and 36 s before a verdict).  Fixed: the pieces run in integers and are priced by bit size
(pruning_rational.pieces_cost); both inputs are now rejected by the price in a fraction of a second."""


import random
from math import factorial

import pytest
from kernel_deadline import check_within

import exactinv as ei
from exactinv_check import check

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


SQUARE = [["1", "1"], ["1", "-1"], ["-1", "1"], ["-1", "-1"]]


SQUARE_G = [["1", "0"], ["-1", "0"], ["0", "1"], ["0", "-1"]]


def _square_cert(method, A, record, intervals=()):
    problem = {"A": A, "G": SQUARE_G, "b": ["1"] * 4, "method": method}
    claim = {"type": "valid_steplengths", "intervals": list(intervals), "vertices": SQUARE, "rays": [], "lines": [],
             "pruning": record}
    return {"format": "exactinv-certificate", "version": 2, "problem": problem, "claims": [claim]}


def _record(U, scale, pieces, vertex=0):
    return {"horizon": U, "vertex": vertex, "order": [0, 1, 2, 3], "variable": "h/(s+h)", "scale": scale,
            "pieces": pieces}


def _true_cert(kind=ei.valid_steplengths):
    """(1 + z)/(1 + z/3), A = diag(-1, -2): D(h) = (1 - h/3)(1 - 2h/3), roots 3/2 and 3 (D changes sign);
    the valid set is [0, 3/4]."""
    m = ei.methods.rational([1, 1], [1, "1/3"])
    S = ei.LinearSystem([[-1, 0], [0, -2]])
    P = ei.Polyhedron.from_vertices([[1, 1], [1, -1], [-1, 1], [-1, -1]])
    return kind(S, P, m, prune=False, box=False).certificate


# ------------------------------------------------------------------ soundness

@pytest.mark.parametrize("kind", [ei.valid_steplengths, ei.largest_threshold])
@pytest.mark.parametrize("U, ok, why", [
    ("3/5", False, "vanishes"),      # T = 3/2 exactly a root of D
    ("1", False, "vanishes"),        # U = 1: D has roots in [0, oo)
    ("1/3", False, "does not bound"),  # T = 1/2 < 3/4
    ("1/2", True, ""),               # T = 1 in (3/4, 3/2): sound
    ("4/7", True, ""),               # T = 4/3 just below the root
])
def test_determinant_root_in_or_at_the_end_of_the_range(kind, U, ok, why):
    cert = _true_cert(kind)
    cert["claims"][0]["pruning"] = {"horizon": U, "vertex": 0, "order": [0, 1, 2, 3], "variable": "h/(s+h)",
                                    "scale": "1", "pieces": 4}
    r = check(cert)
    assert r.ok == ok and why in str(r)


@pytest.mark.parametrize("field, value", [("scale", "0"), ("scale", "-1"), ("scale", True), ("scale", 1.0),
                                          ("pieces", 0), ("pieces", 513), ("pieces", True), ("pieces", "8"),
                                          ("horizon", "3/2"), ("horizon", "-1/2"), ("variable", "h"),
                                          ("scale", str(2 ** 64 + 1)), ("horizon", f"{2 ** 65 - 1}/{2 ** 65}")])
def test_bad_record_fields_rejected(field, value):
    cert = _true_cert()
    record = {"horizon": "1/2", "vertex": 0, "order": [0, 1, 2, 3], "variable": "h/(s+h)", "scale": "1", "pieces": 4}
    record[field] = value
    cert["claims"][0]["pruning"] = record
    assert not check(cert).ok


def test_touch_at_infinity_kept_with_u_equal_one():
    """Backward Euler, x' = -x on a polygon with the origin as a vertex: vertex images reach the
    facets through 0 only as h -> oo; with U = 1 the kernel keeps those pairs and the claim
    [0, oo) verifies, a claim ending earlier does not."""
    S = ei.LinearSystem([[-1, 0], [0, -1]])
    P = ei.Polyhedron.from_vertices([[0, 0], [4, 0], [6, 1], [7, 3], [6, 5], [4, 6], [1, 5], [0, 3]])
    cert = ei.valid_steplengths(S, P, ei.methods.backward_euler(), prune=False, box=False).certificate
    nv = len(cert["claims"][0]["vertices"])
    for k in range(nv):
        cert["claims"][0]["pruning"] = {"horizon": "1", "vertex": k, "order": list(range(nv)),
                                        "variable": "h/(s+h)", "scale": "1", "pieces": 1}
        assert check(cert).ok
    cert["claims"][0]["intervals"][-1]["hi"] = "1000"
    cert["claims"][0]["intervals"][-1]["hi_closed"] = True
    assert not check(cert).ok


# ------------------------------------------------------------------ resource

def test_bernstein_pieces_priced_by_bit_size_taylor64():
    method = {"numerator": [f"1/{factorial(k)}" for k in range(65)], "denominator": ["1"]}
    A = [["-1", "1/3"], ["-1/5", "-1"]]
    cert = _square_cert(method, A, _record("1", "18446744073709551615/9223372036854775809", 512))
    assert not check_within(cert, 2).ok


def test_bernstein_pieces_priced_by_method_coefficient_size():
    rng = random.Random(1)
    def big():
        return str(rng.randrange(10 ** 999, 10 ** 1000))

    method = {"numerator": ["1"] + [f"{big()}/{big()}" for _ in range(20)], "denominator": ["1"]}
    cert = _square_cert(method, [["-1", "0"], ["0", "-1"]], _record("1", "1", 8))
    assert not check_within(cert, 2).ok
