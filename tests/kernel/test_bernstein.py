"""exactinv_check.bernstein: the kernel's exact pieces -- exponential enclosures, f's Taylor coefficients at 0 --
against independent values (mpmath at 60 digits, and f worked out by hand)."""


from fractions import Fraction as F

import mpmath
import pytest  # noqa: E402
from hypothesis import given, settings
from hypothesis import strategies as st
from radius_reference import from_partial_fractions  # noqa: E402

import exactinv as ei  # noqa: E402
from exactinv.core.encode import encode_real  # noqa: E402
from exactinv.monotonicity.radius import absolute_monotonicity_radius  # noqa: E402
from exactinv_check import (
    bernstein,
    check,  # noqa: E402
)
from exactinv_check.failure import CheckFailure  # noqa: E402


def _terms(p, y, b, off):
    """b_* = 1 at p, b at p +- iy (so B = 1 + 2b cos(yt)), and real poles off the line [(q, b_q)]."""
    return [((p, F(0)), (F(1), F(0))), ((p, y), (b, F(0))), ((p, -y), (b, F(0)))] + \
        [((q, F(0)), (bq, F(0))) for q, bq in off]


def _method(terms):
    return ei.methods.rational(*from_partial_fractions(terms))


def _claim(method, **fields):
    """A certificate of ``method`` with its radius claim replaced by ``fields`` (the kernel must judge it alone)."""
    cert = absolute_monotonicity_radius(ei.methods.trapezoid()).certificate
    cert["problem"]["method"] = {"name": "forged", "numerator": [str(c) for c in method.numerator],
                                 "denominator": [str(c) for c in method.denominator]}
    cert["claims"] = [{"type": "absolute_monotonicity_radius", "attained": True, **fields}]
    return cert


CASE_A = _terms(F(7, 2), F(9, 4), F(1, 2), [(F(11, 2), F(1))])  # the CI failure (a): rho = oo


CASE_B = _terms(F(7, 4), F(9, 4), F(1, 2), [(F(15, 4), F(1))])  # (b): c < 0, rho = the root of g(-kappa)


# ------------------------------------------------------------------ soundness

@settings(deadline=None, max_examples=60)
@given(st.fractions(min_value=-60, max_value=5, max_denominator=64),
       st.fractions(min_value=-40, max_value=40, max_denominator=64),
       st.fractions(min_value=0, max_value=F(1, 4), max_denominator=1024))
def test_exponential_disk_holds_the_true_value(x, y, rad):
    """e^u for every u in the disk (x + iy, rad): the centre's value is inside, and so is the value at an edge point."""
    cx, cy, r = bernstein._exp((x, y, rad))
    with mpmath.workdps(60):
        for u in (mpmath.mpc(x.numerator, 0) / x.denominator + 1j * mpmath.mpf(y.numerator) / y.denominator,
                  mpmath.mpc(x.numerator, 0) / x.denominator + mpmath.mpf(rad.numerator) / rad.denominator
                  + 1j * mpmath.mpf(y.numerator) / y.denominator):
            value = mpmath.exp(u)
            assert abs(value - mpmath.mpc(mpmath.mpf(cx.numerator) / cx.denominator,
                                          mpmath.mpf(cy.numerator) / cy.denominator)) \
                <= mpmath.mpf(r.numerator) / r.denominator
    if rad == 0:  # a point: the enclosure is tight (relative 2^-90)
        assert r <= 2 ** -90 * max(abs(cx) + abs(cy), F(1, 2 ** 200))


def test_density_at_zero_by_hand():
    """r = (1 - z)/(1 - 2z)^4: f(t) = e^(-t/2) (t^2/32 + t^3/192) (the kernel's Sturm proof), so
    f(0) = f'(0) = 0, f''(0) = 1/16, f'''(0) = 6/192 - 3 (1/2)(2/32) = 1/32 - 3/32 = -1/16."""
    c, fs = bernstein.density_at_zero([F(1), F(-1)], [F(1), F(-8), F(24), F(-32), F(16)], 4)
    assert c == 0 and fs == [0, 0, F(1, 16), F(-1, 16)]
    c, fs = bernstein.density_at_zero([F(1), F(1, 2)], [F(1), F(-1, 2)], 3)   # trapezoid: c = -1, f = 4 e^(-2t)
    assert c == -1 and fs == [4, -8, 16]


def test_the_kernel_proves_the_balanced_line_of_the_ci_failures():
    """(a) e^(pt) f = (1 + cos(9t/4)) + e^(-2t): B >= 0 (b_* = 2|b|) and R > 0; (b) the same f, and c < 0."""
    for terms in (CASE_A, CASE_B):
        c, how = bernstein.prove_density_nonnegative(*from_partial_fractions(terms))
        assert "line part" in how and "slowest-decaying pole q" in how
    assert "c = 7045/21329 >= 0" in bernstein.prove_completely_monotone(*from_partial_fractions(CASE_A))
    with pytest.raises(CheckFailure, match="c = -73/1365 < 0"):
        bernstein.prove_completely_monotone(*from_partial_fractions(CASE_B))


def test_genuine_bernstein_root_certificates_verify():
    """The trapezoid (rho = 2 = the root of 1 - kappa/2), case (b) (rho ~ 53.66, a quartic's root)."""
    for method in (ei.methods.trapezoid(), _method(CASE_B)):
        r = absolute_monotonicity_radius(method)
        assert r.reason == "bernstein-root"
        verdict = check(r.certificate)
        assert verdict.ok, str(verdict)


def test_forged_bernstein_root_claims_are_rejected():
    trapezoid = ei.methods.trapezoid()
    assert check(_claim(trapezoid, value="2", reason="bernstein-root")).ok
    for fields in ({"value": "3", "reason": "bernstein-root"},             # not the root of g(-kappa)
                   {"value": "oo", "reason": "bernstein-root"},            # rho = oo is not this reason's
                   {"value": "2", "reason": "bernstein-root", "attained": False},
                   {"value": "2", "reason": "bernstein-root", "tail_index": 1},
                   {"value": "2", "reason": "bernstein-root", "d": [["1", "-1/2"]]},
                   {"value": "2", "reason": "bernstein-root", "binding": 0},
                   {"value": "2", "reason": "bernstein"}):                 # c = -1 < 0: not completely monotone
        assert not check(_claim(trapezoid, **fields)).ok, fields
    b = absolute_monotonicity_radius(_method(CASE_B)).value
    assert check(_claim(_method(CASE_B), value=encode_real(b), reason="bernstein-root")).ok
    assert not check(_claim(_method(CASE_B), value="53", reason="bernstein-root")).ok
    assert not check(_claim(_method(CASE_B), value="oo", reason="bernstein")).ok   # c < 0
    # c >= 0 claimed as a finite root: case (a) has c = 7045/21329 > 0 and rho = oo
    assert not check(_claim(_method(CASE_A), value="1", reason="bernstein-root")).ok


def test_a_density_negative_near_zero_cannot_pass_as_bernstein_root():
    """f = 4 e^(-t) - 5 e^(-4t), f(0) = -1 < 0, c = 1 - (4 - 5/4) = -7/4 < 0: rho is not the root of g(-kappa)."""
    method = _method([((F(1), F(0)), (F(4), F(0))), ((F(4), F(0)), (F(-5), F(0)))])
    g_minus = [c * (-1) ** k for k, c in enumerate(method.numerator)]
    with pytest.raises(CheckFailure):
        bernstein.prove_density_nonnegative(method.numerator, method.denominator)
    import flint

    from exactinv.core.roots import real_roots
    roots = [x for x, _ in real_roots(flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in g_minus]))
             if x > 0]
    assert roots
    assert not check(_claim(method, value=encode_real(roots[0]), reason="bernstein-root")).ok
    genuine = absolute_monotonicity_radius(method)
    assert genuine.reason != "bernstein-root" and check(genuine.certificate).ok


@pytest.mark.parametrize("terms, why", [
    (_terms(F(1), F(2), F(1, 2), [(F(2), F(-1))]), "not proved positive"),      # b_q < 0: f < 0 near B's zeros
    (_terms(F(1), F(2), F(3, 5), [(F(3), F(1))]), "not proved >= 0"),            # 2|b| = 6/5 > b_* = 1: B < 0 somewhere
    ([((F(1), F(0)), (F(1), F(0))), ((F(1), F(2)), (F(1, 2), F(0))), ((F(1), F(-2)), (F(1, 2), F(0))),
      ((F(2), F(1)), (F(1), F(0))), ((F(2), F(-1)), (F(1), F(0)))], "not real"),  # slowest off the line: a pair
])
def test_the_balanced_line_proof_refuses_what_it_cannot_prove(terms, why):
    """rho = oo claimed (reason bernstein) where the balanced-line far piece does not hold: rejected, for the reason
    named (b_q < 0 gives a genuinely finite rho; the others are not provable by this route)."""
    method = _method(terms)
    with pytest.raises(CheckFailure, match=why):
        bernstein.prove_density_nonnegative(method.numerator, method.denominator)
    assert not check(_claim(method, value="oo", reason="bernstein")).ok


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
