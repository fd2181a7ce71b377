"""The kernel on ellipsoid certificates: genuine ones verify, forged ones are
rejected (shrunk or indefinite Q, dropped intervals, flipped flags, wrong ends,
forged witnesses, claims on the wrong kind of problem)."""


import copy
import json
from fractions import Fraction

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.certificates import certificate
from exactinv_check import check

DISC = ei.Ellipsoid([[1, 0], [0, 1]])


ROT = ei.LinearSystem([[-1, -2], [2, -1]])


GAP_METHOD = ei.methods.polynomial([1, "1/2", "3/4", "1/4"])


def _cert(S, E, method, results):
    cert = json.loads(json.dumps(certificate(S, E, method, results)))
    assert check(copy.deepcopy(cert)).ok, check(cert)
    return cert


def _taylor2():
    m = ei.methods.taylor(2)
    return _cert(ROT, DISC, m, [ei.continuous_invariance(ROT, DISC), ei.discrete_invariance(ROT, DISC, m, "1/2"),
                                ei.valid_steplengths(ROT, DISC, m), ei.largest_threshold(ROT, DISC, m),
                                ei.forward_euler_threshold(ROT, DISC)])


def _gap():
    S, E = ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]])
    return _cert(S, E, GAP_METHOD, [ei.valid_steplengths(S, E, GAP_METHOD), ei.largest_threshold(S, E, GAP_METHOD)])


def _claim(cert, kind):
    return next(c for c in cert["claims"] if c["type"] == kind)


def _rejected(cert, reason=""):
    report = check(json.loads(json.dumps(cert)))
    assert not report.ok, f"accepted:\n{report}"
    assert reason.lower() in str(report).lower(), str(report)


@st.composite
def _problems(draw):
    n = draw(st.integers(1, 2))
    entry = st.builds(Fraction, st.integers(-4, 4), st.integers(1, 3))
    A = [[draw(entry) for _ in range(n)] for _ in range(n)]
    B = [[draw(entry) for _ in range(n)] for _ in range(n)]
    Q = [[sum(B[k][i] * B[k][j] for k in range(n)) + (i == j) for j in range(n)] for i in range(n)]
    method = draw(st.sampled_from([ei.methods.taylor(1), ei.methods.taylor(2), ei.methods.theta("1/4"),
                                   ei.methods.pade(1, 1), GAP_METHOD]))
    return ei.LinearSystem(A), ei.Ellipsoid(Q), method


# ------------------------------------------------------------------ soundness

def test_genuine_certificates_verify():
    assert check(_taylor2()).ok and check(_gap()).ok


def test_a_shrunk_Q_is_rejected():
    """Q = diag(1, 4): A^T Q + Q A = [[-2, 6], [6, -8]] is indefinite, and every threshold changes."""
    cert = _taylor2()
    cert["problem"]["Q"] = [["1", "0"], ["0", "4"]]
    report = check(cert)
    verdicts = {kind: ok for kind, ok, _ in report.verdicts}
    assert not report.ok and not verdicts["ellipsoid_continuous_invariance"]
    assert not verdicts["ellipsoid_largest_threshold"] and not verdicts["ellipsoid_forward_euler_threshold"]


@pytest.mark.parametrize("Q, reason", [([["1", "2"], ["2", "1"]], "positive definite"),
                                       ([["1", "0"], ["0", "0"]], "positive definite"),
                                       ([["1", "1"], ["0", "1"]], "symmetric")])
def test_a_Q_that_is_no_ellipsoid_is_rejected(Q, reason):
    cert = _taylor2()
    cert["problem"]["Q"] = Q
    _rejected(cert, reason)


def test_a_dropped_interval_is_rejected():
    cert = _gap()
    _claim(cert, "ellipsoid_valid_steplengths")["intervals"].pop()
    _rejected(cert, "2 intervals")


@pytest.mark.parametrize("flag", ["lo_closed", "hi_closed"])
def test_a_flipped_interval_flag_is_rejected(flag):
    cert = _gap()
    iv = _claim(cert, "ellipsoid_valid_steplengths")["intervals"][0]
    iv[flag] = not iv[flag]
    _rejected(cert, flag)


def test_a_wrong_end_is_rejected():
    cert = _gap()
    _claim(cert, "ellipsoid_valid_steplengths")["intervals"][0]["hi"] = "11/10"
    _rejected(cert, "ends at")


def test_a_flipped_attained_flag_and_a_wrong_threshold_are_rejected():
    cert = _taylor2()
    _claim(cert, "ellipsoid_largest_threshold")["attained"] = False
    _rejected(cert, "attained")
    cert = _taylor2()
    _claim(cert, "ellipsoid_largest_threshold")["value"] = "43/50"
    _rejected(cert, "largest threshold")
    cert = _taylor2()
    _claim(cert, "ellipsoid_forward_euler_threshold")["value"] = "1/2"
    _rejected(cert, "forward-euler")


def test_a_wrong_binding_index_is_rejected():
    cert = _taylor2()
    _claim(cert, "ellipsoid_largest_threshold")["binding"] = 2  # c_2 = c_1^2/4: a tangent root, never ends
    _rejected(cert, "condition 2")


@pytest.mark.parametrize("kind", ["ellipsoid_continuous_invariance", "ellipsoid_discrete_invariance"])
def test_flipped_holds_and_forged_witnesses_are_rejected(kind):
    cert = _taylor2()
    c = _claim(cert, kind)
    c["holds"] = False
    c["witness"] = {"v": ["1", "0"]}
    _rejected(cert, "witness does not show")
    c["witness"] = {"v": ["0", "0"], "value": "0"}
    _rejected(cert, "witness does not show")


def test_a_claim_that_holds_is_rejected_when_it_does_not():
    S = ei.LinearSystem([[-1, 3], [0, -1]])
    cert = _cert(S, DISC, None, [ei.continuous_invariance(S, DISC)])
    c = _claim(cert, "ellipsoid_continuous_invariance")
    c["holds"] = True
    del c["witness"]
    _rejected(cert, "not negative semidefinite")
    cert = _cert(ROT, DISC, ei.methods.taylor(2), [ei.discrete_invariance(ROT, DISC, ei.methods.taylor(2), 2)])
    c = _claim(cert, "ellipsoid_discrete_invariance")
    c["holds"] = True
    del c["witness"]
    _rejected(cert, "not positive semidefinite")


def test_a_wrong_witness_value_is_rejected():
    S = ei.LinearSystem([[-1, 3], [0, -1]])
    cert = _cert(S, DISC, None, [ei.continuous_invariance(S, DISC)])
    _claim(cert, "ellipsoid_continuous_invariance")["witness"]["value"] = "3"
    _rejected(cert, "recorded value")


def test_claims_on_the_wrong_kind_of_problem_are_rejected():
    cert = _taylor2()
    cert["problem"] = {"A": [["-1", "-2"], ["2", "-1"]], "G": [["1", "0"], ["0", "1"]], "b": ["1", "1"],
                       "method": cert["problem"]["method"]}
    _rejected(cert, "needs A and Q")
    P = ei.Polyhedron.box([-1, -1], [1, 1])
    cert = json.loads(json.dumps(certificate(ROT, P, None, [ei.forward_euler_threshold(ROT, P)])))
    cert["problem"] = {"A": cert["problem"]["A"], "Q": [["1", "0"], ["0", "1"]]}
    _rejected(cert, "needs A, G and b")
    cert["problem"]["G"] = [["1", "0"]]
    _rejected(cert, "ellipsoid problem has the keys")


def test_a_wrong_determinant_is_rejected():
    S, E, m = ei.LinearSystem([[-1, -2], [2, -1]]), DISC, ei.methods.backward_euler()
    cert = _cert(S, E, m, [ei.valid_steplengths(S, E, m)])
    _claim(cert, "ellipsoid_valid_steplengths")["determinant"] = ["1", "2"]
    _rejected(cert, "det h")


@given(_problems())
@settings(max_examples=15)
def test_every_end_is_checked_exactly(case):
    """A genuine certificate verifies; moving any finite end to a nearby rational is rejected."""
    S, E, m = case
    V = ei.valid_steplengths(S, E, m)
    cert = _cert(S, E, m, [V])
    for k, iv in enumerate(V):
        for key in ("lo", "hi"):
            end = getattr(iv, key)
            if end == ei.INF or (key == "lo" and end == 0):
                continue
            moved = (end.upper if key == "hi" else end.lower) if not isinstance(end, Fraction) else end + Fraction(1, 1000)
            forged = copy.deepcopy(cert)
            forged["claims"][0]["intervals"][k][key] = str(moved)
            _rejected(forged)


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
