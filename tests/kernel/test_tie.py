"""The kernel's `tie` route (exactinv_check/tie.py): genuine tie certificates verify, forged ones are
rejected -- a value that is not a root of the tie polynomial, a root where no pole ties, a tie that p*
loses (its principal part is outweighed), a tie claimed after a coefficient already turned negative."""


import copy
import json
from fractions import Fraction

import pytest

import exactinv as ei
from exactinv import methods as M
from exactinv.core.encode import encode_real
from exactinv.core.roots import real_roots
from exactinv.monotonicity.poles import dominance_tie, pole_structure, precision, tie_polynomial
from exactinv_check import check
from exactinv_check.tie import tie_polynomial as kernel_tie_polynomial


def _cert(method):
    return copy.deepcopy(ei.absolute_monotonicity_radius(method).certificate)


def _rejected(cert, reason=""):
    report = check(json.loads(json.dumps(cert)))
    assert not report.ok, f"accepted:\n{report}"
    assert reason.lower() in str(report).lower(), str(report)


def _kappa_A(method):
    p_star = [z for z, _ in real_roots(method.h) if z > 0][0]
    with precision(256):
        return dominance_tie(pole_structure(method.numerator, method.denominator, p_star), method.h).kappa


# ------------------------------------------------------------------ soundness

@pytest.mark.parametrize("k", [2, 3, 4, 5, 6])
def test_genuine_ties_verify(k):
    cert = _cert(M.pade(k, 3))
    assert cert["claims"][0]["reason"] == "tie"
    assert check(cert).ok


def test_engine_and_kernel_tie_polynomials_agree():
    """Two implementations (FLINT resultants; Fractions and Euclid) of the same T, up to a constant."""
    for m in (M.pade(2, 3), M.pade(1, 5), M.rational([1], [1, "-2/3", "-1/4"])):
        T = tie_polynomial(m.h)
        K = kernel_tie_polynomial(list(m.denominator))
        ratio = Fraction(K[-1]) / Fraction(int(T.coeffs()[-1].p), int(T.coeffs()[-1].q))
        assert [Fraction(c) for c in K] == [ratio * Fraction(int(c.p), int(c.q)) for c in T.coeffs()]


def test_a_rational_near_the_tie_is_rejected():
    cert = _cert(M.radau_iia3())
    cert["claims"][0]["value"] = "17/10"  # rho = 1.7034...: 17/10 is admissible but not a tie
    _rejected(cert, "meets no pole's enclosure of kappa_z")  # the cheap test, before the tie polynomial


def test_a_rational_within_2_to_the_minus_200_of_the_tie_is_rejected():
    """Inside every pole's kappa_z enclosure, so the cheap test passes: the tie polynomial rejects it."""
    from exactinv_check.reals import Real
    cert = _cert(M.radau_iia3())
    v = Real.parse(cert["claims"][0]["value"], "rho")
    for _ in range(200):
        v.bisect()
    q = (v.lo + v.hi) / 2  # kappa* is irrational (a root of 2k^3 + 9k^2 - 36), so q != kappa*
    cert["claims"][0]["value"] = f"{q.numerator}/{q.denominator}"
    _rejected(cert, "not a root of the tie polynomial")


def test_another_root_of_the_tie_polynomial_is_rejected():
    """Pade(2,5): T has positive roots besides kappa_A (ties of the farther pair, or of pairs among
    themselves); at each a nearer pole already beats p*, or no pole ties p* there."""
    m = M.pade(2, 5)
    others = [r for r, _ in real_roots(tie_polynomial(m.h)) if r > 0 and not r == _kappa_A(m)]
    assert others
    cert = _cert(m)
    claim = cert["claims"][0]
    claim.update(reason="tie", attained=True, tail_index=0)
    for key in ("binding", "d"):
        claim.pop(key, None)
    for r in others[:3]:
        claim["value"] = encode_real(r)
        _rejected(cert)


@pytest.mark.parametrize("k", [0, 1])
def test_a_tie_that_p_star_loses_is_rejected(k):
    """Pade(0,3) and Pade(1,3): the complex pair's residues outweigh p*'s, so the true rho is a coefficient
    end strictly below kappa_A; claiming rho = kappa_A by a tie must fail."""
    m = M.pade(k, 3)
    r = ei.absolute_monotonicity_radius(m)
    assert r.reason == "coefficient" and r.value < _kappa_A(m)
    cert = _cert(m)
    claim = cert["claims"][0]
    claim.update(value=encode_real(_kappa_A(m)), reason="tie", attained=True, tail_index=0)
    for key in ("binding", "d"):
        claim.pop(key, None)
    _rejected(cert)


def test_tie_claims_carry_no_binding_and_are_finite():
    cert = _cert(M.radau_iia3())
    cert["claims"][0]["binding"] = 0
    _rejected(cert, "binding")
    cert = _cert(M.radau_iia3())
    cert["claims"][0]["value"] = "oo"
    _rejected(cert)


def test_a_tie_on_a_method_with_only_real_positive_poles_is_rejected():
    cert = _cert(M.ssp_sdirk(2))  # ((1 + z/4)/(1 - z/4))^2: one pole, no tie exists
    claim = cert["claims"][0]
    claim.update(reason="tie", value="4", attained=True)
    for key in ("binding", "d"):
        claim.pop(key, None)
    _rejected(cert)


@pytest.mark.parametrize("value", ["1/2", "11957/10000", "2"])
def test_a_moved_coefficient_radius_is_rejected(value):
    """Pade(0,3): rho = 0.58446...  Below it (1/2) every d_j is positive on (0, K] and is set aside, so only
    the guard 2K + 1 - kappa is left, beyond K: rejected.  Above it the binding d_j ends first: rejected."""
    cert = _cert(M.pade(0, 3))
    claim = cert["claims"][0]
    claim.pop("d", None)
    claim["value"] = value
    _rejected(cert)


def test_the_guard_never_stands_in_for_rho():
    """A claimed rho = 0 with K = 0 for Pade(1,1) (true rho = 2) is rejected: nothing is set aside at K = 0."""
    cert = _cert(M.trapezoid())
    claim = cert["claims"][0]
    claim.update(value="0", binding=None)
    claim.pop("d", None)
    _rejected(cert)


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
