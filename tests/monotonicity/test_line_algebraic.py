"""Poles on the line Re z = p* for an IRRATIONAL p* (exactinv/monotonicity/line_algebraic.py, exactinv_check/line_algebraic.py;
issue 22 item 4): proved on the line in Q(p*), then decided; every certificate re-proved by the kernel, every radius
checked against the slow exact reference (c_j at rationals, many j: tests/radius_reference.py).

The examples are built by hand (sympy, nothing from exactinv): for p = a -+ sqrt d (Galois conjugates, both poles)
    r(z) = C + (1 - C) S(z)/S(0),   S(z) = sum_p [1/(p - z) + c (p - z)/((p - z)^2 + y^2)],
so r(-x) = C + (1 - C)/S(0) int_0^oo e^(-xt) f(t) dt with
    f(t) = (e^(-(a - sqrt d) t) + e^(-(a + sqrt d) t)) (1 + c cos(yt)),
poles a -+ sqrt d and a -+ sqrt d +- iy: p* = a - sqrt d (irrational) has the pair p* +- iy on its line.
By hand: f >= 0 iff |c| <= 1 (1 + c cos >= 1 - |c|), so with C = 0: rho = oo iff |c| <= 1 (Bernstein); with C < 0
and |c| <= 1, rho is the positive root of r(-kappa) (c_j >= 0 for j >= 1, c_0 = r(-kappa) decreases).
"""

from fractions import Fraction as F

import flint
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from radius_reference import admissible, coefficients_at

import exactinv as ei
from exactinv.core.real_algebraic import RealAlgebraic
from exactinv.core.scalars import INF
from exactinv.monotonicity.line_algebraic import algebraic_line_gcd, algebraic_pair_balance, algebraic_sign
from exactinv.monotonicity.radius import absolute_monotonicity_radius
from exactinv_check import check
from exactinv_check.line_algebraic import AlgebraicLine
from exactinv_check.reals import Real

_z = sp.symbols("z")


def _normalised(S, C):
    """(g, h), h(0) = 1, of r = C + (1 - C) S/S(0) for a sympy sum of partial fractions S in z (exact)."""
    S = sp.together(sp.expand(S))
    r = sp.Rational(C) + (1 - sp.Rational(C)) * S / sp.nsimplify(S.subs(_z, 0))
    num, den = sp.fraction(sp.cancel(sp.together(r)))
    g = [F(str(sp.nsimplify(x))) for x in reversed(sp.Poly(sp.expand(num), _z).all_coeffs())]
    h = [F(str(sp.nsimplify(x))) for x in reversed(sp.Poly(sp.expand(den), _z).all_coeffs())]
    return [x / h[0] for x in g], [x / h[0] for x in h]


def conjugate_lines(a, d, y, c, C=0, v=0):
    """(g, h), h(0) = 1, of the module docstring's r (sympy, exact); v != 0 gives the pair the residue
    beta = (c + 2iv)/2: B(t) = 1 + 2 Re(beta e^(-iyt)) >= 0 iff c^2 + 4v^2 <= 1 (the pair's two partial fractions
    add up to (2u (p - z) + 2 v y)/((p - z)^2 + y^2) for beta = u + iv)."""
    S = 0
    for s in (1, -1):
        p = a - s * sp.sqrt(d)
        S += 1 / (p - _z) + (c * (p - _z) + 2 * sp.Rational(v) * y) / ((p - _z) ** 2 + y ** 2)
    return _normalised(S, C)


def _radius(g, h):
    r = absolute_monotonicity_radius(ei.methods.rational(g, h))
    verdict = check(r.certificate)
    assert verdict.ok, str(verdict)
    return r


def _lower(v):
    return v.lower if isinstance(v, RealAlgebraic) else v


def _upper(v):
    return v.upper if isinstance(v, RealAlgebraic) else v


SQRT2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
# (z^2 - 2)(z^4 - 2z^2 + 9): roots +-sqrt 2 and +-sqrt 2 +- i (the minimal polynomial of sqrt 2 + i is the quartic)
H6 = flint.fmpq_poly([-18, 0, 13, 0, -4, 0, 1])


def test_the_algebraic_line_gcd_is_y_cubed_minus_y():
    """On Re z = sqrt 2: h(sqrt 2 + iy) vanishes at y = 0 and y = +-1 only, so G = y^3 - y exactly."""
    G = algebraic_line_gcd(H6, SQRT2)
    assert [str(c) for c in G] == ["0", "(-1)", "0", "1"]
    minus = RealAlgebraic.from_isolating_interval([-2, 0, 1], -2, -1)  # -sqrt 2: the conjugate line holds +-i too
    assert [str(c) for c in algebraic_line_gcd(H6, minus)] == ["0", "(-1)", "0", "1"]
    third = RealAlgebraic.from_isolating_interval([-3, 0, 1], 1, 2)  # sqrt 3: no pole on its line
    assert [str(c) for c in algebraic_line_gcd(H6, third)] == ["1"]


def test_signs_in_q_sqrt2_are_exact():
    r2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    # 140 - 99 sqrt 2 = -0.0071 < 0; 577 - 408 sqrt 2 = 0.0012 > 0; (sqrt 2)^3 - 2 sqrt 2 = 0
    assert algebraic_sign(flint.fmpq_poly([140, -99]), r2) == -1
    assert algebraic_sign(flint.fmpq_poly([577, -408]), r2) == 1
    assert algebraic_sign(flint.fmpq_poly([0, -2, 0, 1]), r2) == 0


def _kernel_line(p_poly, lo, hi):
    return AlgebraicLine(Real.algebraic([F(c) for c in p_poly], F(lo), F(hi)), [F(c) for c in p_poly])


def test_the_kernel_proves_a_disk_on_the_line_and_rejects_one_off_it():
    """Disks around sqrt 2 + i (on the line), and around sqrt 2 + 10^-6 + i, whose pole is off the line."""
    line = _kernel_line([-2, 0, 1], 1, 2)
    G = line.line_gcd([F(c) for c in [-18, 0, 13, 0, -4, 0, 1]])
    r2 = F(14142135623730951, 10 ** 16)
    assert line.disk_on_line(G, (r2, F(1), F(1, 1000)))
    assert line.disk_on_line(G, (r2, F(-1), F(1, 1000)))
    assert not line.disk_on_line(G, (r2, F(2), F(1, 1000)))  # no pole there
    assert not line.disk_on_line(G, (r2 + F(1, 100), F(1), F(1, 1000)))  # the chord misses the disk
    # a pole slightly off the line: ((z - sqrt 2 - e)^2 + 1)((z + sqrt 2 - e)^2 + 1) (z^2 - 2), e = 10^-6
    e = sp.Rational(1, 10 ** 6)
    poly = sp.Poly(sp.expand(((_z - sp.sqrt(2) - e) ** 2 + 1) * ((_z + sp.sqrt(2) - e) ** 2 + 1) * (_z ** 2 - 2)), _z)
    off = [F(str(c)) for c in reversed(poly.all_coeffs())]
    G_off = line.line_gcd(off)
    assert len(G_off) == 2  # only y = 0 (the pole sqrt 2 itself) is on the line
    assert not line.disk_on_line(G_off, (r2 + F(1, 10 ** 6), F(1), F(1, 1000)))


def test_strict_dominance_gives_oo():
    """c = 3/4: f = (e^(-p t) + e^(-q t))(1 + 3/4 cos t) > 0, C = 0: rho = oo (was Undecided: p* irrational)."""
    g, h = conjugate_lines(2, 2, 1, F(3, 4))
    r = _radius(g, h)
    assert r.value == INF and r.reason == "bernstein"
    for kappa in (F(0), F(1, 2), F(5), F(100)):
        assert admissible(g, h, kappa, 300)


def test_the_first_example_with_g_one_is_oo():
    """1/h, h = (w^2 - 2)(w^4 - 2w^2 + 9), w = z - 2 (p* = 2 - sqrt 2, pair p* +- i): rho = oo, kernel-checked.
    (f ~ t^5/5! at 0: the kernel's march took 3,577 certified steps from t = 1/64, 22-54 s; the longer Taylor bound at
    0 now reaches t = 2, where p*'s dominance holds.)"""
    w = flint.fmpq_poly([-2, 1])
    hq = (w ** 2 - 2) * (w ** 4 - 2 * w ** 2 + 9)
    h = [F(int(c.p), int(c.q)) / F(int(hq(0).p), int(hq(0).q)) for c in hq.coeffs()]
    r = _radius([F(1)], h)
    assert r.value == INF and r.reason == "bernstein"
    for kappa in (F(0), F(3), F(40)):
        assert admissible([F(1)], h, kappa, 300)


def test_g_one_plus_z_is_one_by_c0():
    """(1 + z)/h: c_0(kappa) = (1 - kappa)/h(-kappa) < 0 for kappa > 1, so rho <= 1; the engine proves rho = 1."""
    w = flint.fmpq_poly([-2, 1])
    hq = (w ** 2 - 2) * (w ** 4 - 2 * w ** 2 + 9)
    h = [F(int(c.p), int(c.q)) / F(int(hq(0).p), int(hq(0).q)) for c in hq.coeffs()]
    g = [F(1), F(1)]
    r = _radius(g, h)
    assert r.value == 1
    assert admissible(g, h, F(1), 300) and admissible(g, h, F(1, 2), 300)
    assert coefficients_at(g, h, F(1) + F(1, 10 ** 6), 1)[0] < 0


@pytest.mark.workload  # python-flint and the kernel only (python-flint is one version in both CI stages)
def test_an_unbalanced_pair_gives_a_finite_rho_with_a_witness():
    """c = 3/2: 1 + 3/2 cos t < 0 near t = pi, so f < 0 there for large t: rho < oo (the engine's exact sign of
    b_*^2 - 4|b|^2 in Q(p*) is -1), confirmed by the reference on both sides of rho."""
    g, h = conjugate_lines(2, 2, 1, F(3, 2))
    a = RealAlgebraic.from_isolating_interval([2, -4, 1], 0, 1)  # 2 - sqrt 2
    assert algebraic_pair_balance(g, h, a)[0] == -1
    r = _radius(g, h)
    assert r.value != INF and r.value > 0
    assert admissible(g, h, _lower(r.value) * F(127, 128), 300)
    c = coefficients_at(g, h, _upper(r.value) + F(1, 10 ** 9), r.binding + 1)
    assert c[r.binding] < 0


@pytest.mark.workload  # python-flint and the kernel only (python-flint is one version in both CI stages)
def test_a_negative_constant_gives_the_root_of_r():
    """C = -1/2, c = 3/4: f >= 0 and c_0 = r(-kappa) decreases to -1/2: rho is the positive root of g(-kappa)."""
    g, h = conjugate_lines(2, 2, 1, F(3, 4), F(-1, 2))
    r = _radius(g, h)
    assert r.reason == "bernstein-root"
    gm = sum(c * (-1) ** k * sp.Symbol("k") ** k for k, c in enumerate(g))
    lo, hi = _lower(r.value), _upper(r.value)
    assert gm.subs("k", lo) * gm.subs("k", hi) < 0  # a root of g(-kappa) inside the enclosure
    assert admissible(g, h, lo, 300) and not admissible(g, h, hi + F(1, 10 ** 6), 1)


def test_the_kernel_rejects_a_forged_oo_for_an_unbalanced_pair():
    """Claim rho = oo (reason bernstein) for c = 3/2, where f < 0 somewhere: rejected."""
    g, h = conjugate_lines(2, 2, 1, F(3, 4))
    cert = _radius(g, h).certificate
    g2, h2 = conjugate_lines(2, 2, 1, F(3, 2))
    forged = absolute_monotonicity_radius(ei.methods.rational(g2, h2)).certificate
    forged["claims"][0] = dict(cert["claims"][0])  # the oo claim of the good method on the bad method
    assert not check(forged).ok
    flipped = _radius(g, h).certificate
    flipped["claims"][0]["value"] = "0"  # a wrong value for the good method
    assert not check(flipped).ok


@pytest.mark.parametrize("c, v", [(F(1), F(0)), (F(-1), F(0)), (F(3, 5), F(2, 5))])
def test_lines_touching_zero_are_oo(c, v):
    """c^2 + 4v^2 = 1: B(t) = 1 + c cos(yt) + 2v sin(yt) >= 0 touches 0 (at t = pi for c = 1), so
    f = (e^(-pt) + e^(-qt)) B(t) >= 0 touches 0 too: no march can certify it, the line-by-line proof does (exact in
    Q(sqrt 2)): rho = oo, kernel-checked, and the reference agrees."""
    g, h = conjugate_lines(2, 2, 1, c, 0, v)
    r = _radius(g, h)
    assert r.value == INF and r.reason == "bernstein"
    for kappa in (F(0), F(2), F(30)):
        assert admissible(g, h, kappa, 300)


def test_the_kernel_line_by_line_proof_accepts_exactly_the_nonnegative_lines():
    """exactinv_check.line_algebraic.lines_nonnegative: B >= 0 touching 0 (c = 1) accepted, B < 0 somewhere (c = 3/2,
    or 4v^2 + c^2 = 1 + 1/100) rejected, and 1/h (f > 0, but the line through 2 + sqrt 2 has b_q < 2|beta_q|) not
    claimed line by line."""
    from exactinv_check.line_algebraic import lines_nonnegative
    assert lines_nonnegative(*conjugate_lines(2, 2, 1, F(1)), True) is not None
    assert lines_nonnegative(*conjugate_lines(2, 2, 1, F(3, 5), 0, F(2, 5)), True) is not None
    assert lines_nonnegative(*conjugate_lines(2, 2, 1, F(3, 2)), True) is None
    assert lines_nonnegative(*conjugate_lines(2, 2, 1, F(3, 5), 0, F(2, 5) + F(1, 80)), True) is None
    w = flint.fmpq_poly([-2, 1])
    hq = (w ** 2 - 2) * (w ** 4 - 2 * w ** 2 + 9)
    h = [F(int(c.p), int(c.q)) / F(int(hq(0).p), int(hq(0).q)) for c in hq.coeffs()]
    assert lines_nonnegative([F(1)], h, True) is None


def test_the_kernel_rejects_oo_for_touching_lines_with_a_negative_constant():
    """c = 1, C = -1/2: f >= 0 (line by line) but r(-x) -> -1/2 < 0, so rho < oo: the engine says bernstein-root,
    and the good certificate's claim re-labelled as rho = oo is rejected."""
    g, h = conjugate_lines(2, 2, 1, F(1), F(-1, 2))
    r = _radius(g, h)
    assert r.reason == "bernstein-root"
    forged = r.certificate
    forged["claims"][0].update({"value": "oo", "reason": "bernstein", "attained": True})
    assert not check(forged).ok


@pytest.mark.workload  # python-flint and the kernel only (python-flint is one version in both CI stages)
@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(a=st.integers(min_value=2, max_value=4), d=st.sampled_from([2, 3, 5]),
       y=st.fractions(min_value=F(1, 2), max_value=2, max_denominator=2),
       c=st.fractions(min_value=F(-2), max_value=F(2), max_denominator=4),
       C=st.sampled_from([F(0), F(1, 4), F(-1, 2)]),
       circle=st.sampled_from([None, (F(3, 5), F(2, 5)), (F(-5, 13), F(6, 13)), (F(0), F(1, 2))]))
def test_random_conjugate_lines_are_decided_checked_and_confirmed(a, d, y, c, C, circle):
    """p* = a - sqrt d (a^2 > d: both conjugates positive) with a pair on its line (residue (c + 2iv)/2; ``circle``
    puts it exactly on c^2 + 4v^2 = 1, B touching 0): decided or a named resource limit, the kernel re-proves every
    certificate, and the reference agrees: by hand rho = oo iff c^2 + 4v^2 <= 1 and C >= 0."""
    v = F(0)
    if circle is not None:
        c, v = circle
    if a * a <= d or (c == 0 and v == 0):
        return
    g, h = conjugate_lines(a, d, y, c, C, v)
    nonnegative = c * c + 4 * v * v <= 1
    try:
        r = _radius(g, h)
    except ei.Undecided as e:  # resource limits only, named
        assert "kernel's polynomial bound" in str(e) or "j <= 8192" in str(e) or "coefficients" in str(e), str(e)
        return
    assert (r.value == INF) == (nonnegative and C >= 0)
    if r.value == INF:
        for kappa in (F(0), F(1), F(10)):
            assert admissible(g, h, kappa, 200)
        return
    assert r.value > 0 or not r.attained
    if r.value > 0:
        assert admissible(g, h, _lower(r.value) * F(127, 128), 200)


def test_the_kernel_rejects_oo_when_the_pair_is_just_left_of_the_line():
    """The pair moved left by 10^-6 (poles 2 -+ sqrt 2 - 10^-6 +- i): for large kappa it comes closer to -kappa
    than p*, so rho < oo.  The genuine rho = oo claim of the on-line method, re-attached to this method (the
    same p*), is rejected: the pair is neither proved on Re z = p* nor to the right of it."""
    import dataclasses

    g = [F(1), F(-199, 86), F(229, 86), F(-263, 172), F(35, 86), F(-7, 172)]  # conjugate_lines(2, 2, 1, 3/4)

    def method(e):
        u = _z - 2
        poly = sp.Poly(sp.expand((u ** 2 - 2) * ((u + sp.sqrt(2) + e) ** 2 + 1) * ((u - sp.sqrt(2) + e) ** 2 + 1)), _z)
        h = [F(str(c)) for c in reversed(poly.all_coeffs())]
        return ei.methods.rational(g, [c / h[0] for c in h])

    good = absolute_monotonicity_radius(method(0))
    assert good.value == INF and check(good.certificate).ok
    forged = dataclasses.replace(good, method=method(sp.Rational(1, 10 ** 6)))
    assert not check(forged.certificate).ok


def symmetric_lines(a, d, c_a, y=None, beta=(0, 0), C=0):
    """(g, h), h(0) = 1: the poles a - sqrt d, a + sqrt d (residue 1 each, with the pairs a -+ sqrt d +- iy of residue
    beta = u + iv when y is given) and the rational pole a midway between them (residue c_a):
    f(t) = sum_(p = a -+ sqrt d) e^(-pt) (1 + 2 Re(beta e^(-iyt))) + c_a e^(-at); r = C + (1 - C) S/S(0)."""
    S = sp.Rational(c_a) / (a - _z)
    for s in (1, -1):
        p = a - s * sp.sqrt(d)
        S += 1 / (p - _z)
        if y is not None:
            S += (2 * sp.Rational(beta[0]) * (p - _z) + 2 * sp.Rational(beta[1]) * y) / ((p - _z) ** 2 + y ** 2)
    return _normalised(S, C)


def test_a_rational_pole_midway_between_conjugates_is_decided():
    """Poles 3 -+ sqrt 2 with pairs at height 1 touching (beta = 1/2: 1 + cos t) and the pole 3 midway (red team
    rt-lines): on Re z = 3, G = y(y^2 + 2)(a quartic with the roots +-1 +- i sqrt 2) has one real root, so 3 is alone
    on its line and f = (e^(-pt) + e^(-qt))(1 + cos t) + e^(-3t) >= 0 line by line: rho = oo (was Undecided), kernel-
    checked; the reference agrees (c_j >= 0, j < 300, at four kappa).  With c_a = -1/10, f < 0 at t = pi (mod 2 pi)
    for large t: the kernel refuses the oo claim."""
    g, h = symmetric_lines(3, 2, 1, sp.Integer(1), (F(1, 2), 0))
    r = _radius(g, h)
    assert r.value == INF and r.reason == "bernstein"
    for kappa in (F(0), F(1), F(7), F(60)):
        assert admissible(g, h, kappa, 300)
    g2, h2 = symmetric_lines(3, 2, F(-1, 10), sp.Integer(1), (F(1, 2), 0))
    forged = _radius(g, h).certificate
    forged["problem"]["method"]["numerator"] = [str(c) for c in g2]
    forged["problem"]["method"]["denominator"] = [str(c) for c in h2]
    assert not check(forged).ok


@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(2, 5), st.sampled_from([2, 3, 5, 6, 7]), st.fractions(min_value=F(1, 8), max_value=3, max_denominator=8),
       st.integers(1, 8), st.sampled_from([(F(1, 2), 0), (F(3, 10), F(2, 5)), (0, F(1, 2)), (F(1, 4), F(-1, 4)),
                                           (F(-5, 26), F(6, 13))]),
       st.sampled_from([0, F(1, 4)]))
def test_symmetric_configurations_against_the_reference(a, d, c_a, y, beta, C):
    """Poles a -+ sqrt d with pairs (touching, 4|beta|^2 = 1, or inside) and the rational pole a midway with a positive
    residue: f >= 0 line by line, so rho = oo must be decided (line by line or by dominance), verified by the kernel,
    and true by the slow exact reference (c_j(kappa) >= 0 for j < 150 at four kappa).  (A negative residue or
    4|beta|^2 > 1 gives a finite rho by the coefficient route, up to 80 s of engine time: the forged claim of
    test_a_rational_pole_midway_between_conjugates_is_decided covers it.)"""
    if a * a <= d:
        return
    g, h = symmetric_lines(a, d, c_a, sp.Integer(y), beta, C)
    r = _radius(g, h)
    assert r.value == INF and r.reason == "bernstein"
    for kappa in (F(0), F(1, 2), F(5), F(40)):
        assert admissible(g, h, kappa, 150)
