"""exactinv_check.bernstein: the kernel's exact pieces -- exponential enclosures, f's Taylor coefficients at 0 --
against independent values (mpmath at 60 digits, and f worked out by hand)."""


from fractions import Fraction as F

import mpmath
import pytest  # noqa: E402
from hypothesis import given, settings
from hypothesis import strategies as st
from radius_reference import admissible, from_partial_fractions, product, sextic  # noqa: E402

import exactinv as ei  # noqa: E402
from exactinv.core.encode import encode_real  # noqa: E402
from exactinv.monotonicity.radius import absolute_monotonicity_radius  # noqa: E402
from exactinv_check import (
    bernstein,
    budget,
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


CASE_A = _terms(F(7, 2), F(9, 4), F(1, 2), [(F(11, 2), F(1))])  # the issue's CI failure (a): rho = oo


CASE_B = _terms(F(7, 4), F(9, 4), F(1, 2), [(F(15, 4), F(1))])  # (b): c < 0, rho = the root of g(-kappa)


def _one_over(h):
    return ei.methods.rational([F(1)], [c / h[0] for c in h])


ISSUE_SEXTIC = _one_over(sextic(F(2), F(2), F(1)))  # rho = oo; the kernel's march took 3,577 steps (54 s) before


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


def test_the_longer_taylor_bound_does_not_reach_past_a_dip():
    """f = u (1 - 21u/5 + 43u^2/10) + a small pair, u = e^(-t): f(0) > 0 but f < 0 for t in about (0.57, 0.89), inside
    the span (0, 4] of the longer Taylor bound at 0: rho = oo is refused, and the engine finds rho finite."""
    terms = [((F(1), F(0)), (F(1), F(0))), ((F(2), F(0)), (F(-21, 5), F(0))), ((F(3), F(0)), (F(43, 10), F(0))),
             ((F(5), F(1)), (F(1, 100), F(0))), ((F(5), F(-1)), (F(1, 100), F(0)))]
    method = _method(terms)
    with pytest.raises(CheckFailure):
        bernstein.prove_density_nonnegative(method.numerator, method.denominator)
    assert not check(_claim(method, value="oo", reason="bernstein")).ok
    genuine = absolute_monotonicity_radius(method)
    assert genuine.value != ei.INF and check(genuine.certificate).ok


def _density(terms, t):
    return sum(mpmath.mpf(u.numerator) / u.denominator * mpmath.exp(-(mpmath.mpf(x.numerator) / x.denominator) * t)
               * mpmath.cos((mpmath.mpf(y.numerator) / y.denominator) * t)
               + mpmath.mpf(v.numerator) / v.denominator * mpmath.exp(-(mpmath.mpf(x.numerator) / x.denominator) * t)
               * mpmath.sin((mpmath.mpf(y.numerator) / y.denominator) * t)
               for (x, y), (u, v) in terms)


@settings(deadline=None, max_examples=40)
@given(st.fractions(min_value=F(1, 4), max_value=3, max_denominator=8),
       st.lists(st.tuples(st.fractions(min_value=F(1, 8), max_value=4, max_denominator=8),
                          st.fractions(min_value=0, max_value=3, max_denominator=4),
                          st.fractions(min_value=-2, max_value=2, max_denominator=8)), min_size=1, max_size=3))
def test_an_accepted_density_is_nonnegative(p, others):
    """Whatever the kernel proves f >= 0 for is >= 0 (mpmath, 30 digits, t on a grid to 12): p* = p with b_* = 1 and
    poles p + dx (+- i y) with random residues -- densities that dip below 0 anywhere in (0, 4] (where the longer
    Taylor bound at 0 reaches) included."""
    terms = [((p, F(0)), (F(1), F(0)))]
    for dx, y, b in others:
        if y == 0:
            terms.append(((p + dx, F(0)), (b, F(0))))
        else:
            terms += [((p + dx, y), (b, F(0))), ((p + dx, -y), (b, F(0)))]
    zs = [z for z, _ in terms]
    if len(set(zs)) < len(zs):
        return
    g, h = from_partial_fractions(terms)
    try:
        bernstein.prove_density_nonnegative(g, h)
    except CheckFailure:
        return
    with mpmath.workdps(30):
        assert all(_density(terms, mpmath.mpf(k) / 16) >= -mpmath.mpf(10) ** -25 for k in range(1, 193))


@pytest.mark.parametrize("hint", [[F(-2), F(0), F(1)], [F(-1, 2), F(1)], [F(2), F(-4), F(1)],
                                  [F(4), F(-12), F(12), F(-6), F(1)]])
def test_the_pole_hint_is_never_believed(hint):
    """The claim's recorded pole only offers a modulus for Q(p*): sqrt 2 and 1/2 (not poles), p*'s own quadratic, and
    (x^2 - 4x + 2)(x^2 - 2x + 2), a product holding p* and two non-real non-poles: each leaves the proof of the issue's sextic
    intact (rho = oo proved); a wrong recorded pole is still rejected by the claim (it must be the smallest pole)."""
    g, h = ISSUE_SEXTIC.numerator, ISSUE_SEXTIC.denominator
    assert "f > 0 on (0, oo)" in bernstein.prove_completely_monotone(g, h, hint)
    cert = absolute_monotonicity_radius(ISSUE_SEXTIC).certificate
    cert["claims"][-1]["pole"] = {"poly": ["-2", "0", "1"], "interval": ["1", "2"]}
    report = check(cert)
    assert not report.ok and "recorded pole" in str(report)


# ------------------------------------------------------------------ resource


def test_issue_sextic_is_verified_cheaply():
    """1/h, h = ((z-2)^2 - 2)((z-2)^4 - 2(z-2)^2 + 9) (rho = oo): f ~ t^5/5! near 0, so the second-order march took
    3,577 steps from t = 1/64 (1.6e9 charged, 54 s of CPU); the longer Taylor bound at 0 reaches t = 2, where p*'s
    dominance holds: no step at all."""
    r = absolute_monotonicity_radius(ISSUE_SEXTIC)
    assert r.value == ei.INF and r.reason == "bernstein"
    report = check(r.certificate)
    assert report.ok, str(report)
    assert report.work < 10 ** 8
    assert "0 certified steps" in bernstein.prove_completely_monotone(ISSUE_SEXTIC.numerator, ISSUE_SEXTIC.denominator)


@settings(deadline=None, max_examples=12)
@given(st.lists(st.tuples(st.integers(1, 12), st.sampled_from([F(2), F(3), F(5), F(6), F(7), F(3, 4), F(5, 4)]),
                          st.fractions(min_value=F(1, 2), max_value=6, max_denominator=2)), min_size=1, max_size=2))
def test_products_of_shifted_sextics_are_verified_well_inside_the_budget(factors):
    """Random products of the issue's sextic, shifted: (w^2 - d)((w^2 + d + y^2)^2 - 4dw^2), w = z - a, a > sqrt d.
    Every rho = oo the engine claims is true by the exact reference (c_j(kappa) >= 0 for j < 40 at four kappa) and
    verified by the kernel at under a tenth of the certificate's budget (the Taylor bound at 0 and p*'s quadratic
    as Q(p*)'s modulus: before, degree 12 went over the budget in the inversions modulo the whole of h)."""
    h = [F(1)]
    for a4, d, y in factors:
        a = F(a4, 4)
        while a * a <= d:
            a += F(1, 2)
        h = product(h, sextic(a, d, y))
    method = _one_over(h)
    try:
        r = absolute_monotonicity_radius(method)
    except ei.Undecided:
        return
    if r.value == ei.INF:
        assert all(admissible(method.numerator, method.denominator, k, 40) for k in (F(0), F(1, 2), F(3), F(20)))
    report = check(r.certificate)
    assert report.ok, str(report)
    assert report.work < budget.CERTIFICATE_BUDGET // 10
