"""exactinv_check.line_algebraic: arithmetic in Q(alpha) for an irrational real algebraic alpha (dynamic evaluation,
m squarefree but not necessarily irreducible), the gcd G of f(alpha + iy)'s real and imaginary parts, the disk test
and the line-by-line proof lines_nonnegative, on the module's own functions.  The truths are independent: signs
of c + d sqrt(n) by squaring (the reduction modulo x^2 - n by python-flint), the line polynomial of
f = ((z - sqrt 2)^2 + y0^2)((z + sqrt 2)^2 + y0^2) = (z^2 + 2 + y0^2)^2 - 8 z^2, which is y^2 - y0^2 on Re z = sqrt 2,
disks checked against arb, and b/(1 - z) + (c (1 - z) + w)/((1 - z)^2 + Y), whose density
e^(-t) (b + c cos(yt) + (w/y) sin(yt)) (y = sqrt Y) is >= 0 iff b^2 >= c^2 + w^2/Y (b > 0)."""

from fractions import Fraction as F

import flint
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from exactinv_check.budget import MAX_LINE_DEGREE, account
from exactinv_check.failure import CheckFailure, OverBudget
from exactinv_check.line_algebraic import AlgebraicLine, lines_nonnegative
from exactinv_check.reals import Real

coefficient = st.fractions(min_value=-20, max_value=20, max_denominator=9)
nonsquare = st.integers(2, 60).filter(lambda n: int(n ** 0.5) ** 2 != n)
positive = st.fractions(min_value=F(1, 5), max_value=5, max_denominator=5)


def _flint(p):
    return flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in p])


def _fractions(q):
    return [F(int(c.p), int(c.q)) for c in q.coeffs()]


def _sign(x):
    return (x > 0) - (x < 0)


def _sign_c_plus_d_sqrt(c, d, n):
    """The sign of c + d sqrt n (n not a square), by squaring."""
    if _sign(c) * _sign(d) >= 0:
        return _sign(c) or _sign(d)
    return _sign(c) if c * c > n * d * d else _sign(d)


def _sqrt_line(n, extra=()):
    """The line Re z = sqrt n, alpha held as a root of (x^2 - n) prod (x - e) (squarefree, reducible)."""
    m = _flint([F(-n), F(0), F(1)])
    for e in extra:
        m *= _flint([-e, F(1)])
    return AlgebraicLine(Real.algebraic([F(-n), F(0), F(1)], F(0), F(n)), _fractions(m))


def _pair_polynomial(y0):
    """(z^2 + 2 + y0^2)^2 - 8 z^2: the roots +-sqrt 2 +- i y0."""
    q = _flint([2 + y0 * y0, F(0), F(1)])
    return q * q - _flint([F(0), F(0), F(8)])


# ------------------------------------------------------------------ soundness
@settings(max_examples=60, deadline=None)
@given(nonsquare, st.lists(coefficient, min_size=0, max_size=7), st.sampled_from([(), (F(3, 2),), (F(-1), F(7))]))
def test_the_exact_sign_of_an_element_of_q_sqrt_n(n, a, extra):
    line = _sqrt_line(n, extra)
    rest = _fractions(_flint(a) % _flint([F(-n), F(0), F(1)])) + [F(0), F(0)]
    truth = _sign_c_plus_d_sqrt(rest[0], rest[1], n)
    assert line.sign(a) == truth and line.is_zero(a) == (truth == 0)


@settings(max_examples=15, deadline=None)
@given(positive, positive, st.fractions(min_value=-3, max_value=3, max_denominator=4), st.booleans(),
       st.sampled_from([(), (F(3),), (F(1, 2), F(-5))]))
def test_the_line_gcd_has_exactly_the_roots_on_the_line(y0, y1, c, second_on_line, extra):
    line = _sqrt_line(2, extra)  # dynamic evaluation: m = (x^2 - 2) prod (x - e) is split on the way
    f = _pair_polynomial(y0) * _flint([-c, F(1)])  # a rational pole c is never on Re z = sqrt 2
    if second_on_line and y1 != y0:  # sqrt 2 +- i y1 as well: G = (y^2 - y0^2)(y^2 - y1^2)
        f *= _pair_polynomial(y1)
        expected = [y0 * y0 * y1 * y1, F(0), -y0 * y0 - y1 * y1, F(0), F(1)]
    else:  # 3 +- i y1: off the line, G = y^2 - y0^2
        f *= _flint([F(9) + y1 * y1, F(-6), F(1)])
        expected = [-y0 * y0, F(0), F(1)]
    G = line.line_gcd(_fractions(f))
    assert len(G) == len(expected) and G[-1] == [F(1)]
    for got, truth in zip(G, expected):
        assert line.is_zero(_fractions(_flint(got) - _flint([truth])))


@settings(max_examples=40, deadline=None)
@given(positive, st.fractions(min_value=1, max_value=2, max_denominator=50), st.fractions(min_value=-1, max_value=6,
       max_denominator=50), st.fractions(min_value=F(1, 200), max_value=F(1, 2), max_denominator=200))
def test_a_disk_proved_on_the_line_holds_its_root(y0, re, im, rad):
    line = _sqrt_line(2)
    G = line.line_gcd(_fractions(_pair_polynomial(y0)))
    if line.disk_on_line(G, (re, im, rad)):  # then sqrt 2 + i y0 lies in the disk (the only root on the line, y > 0)
        dx = flint.arb(2).sqrt() - flint.arb(re.numerator) / re.denominator
        dy = flint.arb(y0.numerator) / y0.denominator - flint.arb(im.numerator) / im.denominator
        distance2 = dx * dx + dy * dy  # not ** 2: python-flint 0.9's arb ** 2 of a ball holding 0 is nan (im = y0)
        assert distance2.upper() < flint.arb(rad.numerator) ** 2 / rad.denominator ** 2
    if abs(re - F(14142135, 10 ** 7)) < rad / 8 and abs(im - y0) < rad / 8 and im > rad:  # a centred disk
        assert line.disk_on_line(G, (re, im, rad))


def test_disks_by_hand():
    line = _sqrt_line(2)
    G = line.line_gcd(_fractions(_pair_polynomial(F(1))))  # y^2 - 1: sqrt 2 +- i
    assert line.disk_on_line(G, (F(1414, 1000), F(1), F(1, 100)))
    assert not line.disk_on_line(G, (F(15, 10), F(1), F(1, 100)))  # 0.0858 from the line: no chord
    assert not line.disk_on_line(G, (F(1414, 1000), F(3, 2), F(1, 100)))  # on the line but no root in the chord
    assert not line.disk_on_line(G, (F(1414, 1000), F(0), F(1, 2)))  # the chord reaches y = 0
    assert not line.disk_on_line([[F(1)]], (F(1414, 1000), F(1), F(1, 100)))  # G = 1: no root on the line


@settings(max_examples=25, deadline=None)
@given(st.fractions(min_value=-2, max_value=2, max_denominator=4), positive,
       st.fractions(min_value=-2, max_value=2, max_denominator=4), st.fractions(min_value=-2, max_value=2, max_denominator=4))
def test_lines_nonnegative_is_exactly_the_balance_b2_at_least_c2_plus_w2_over_y(b, Y, c_, w):
    u = _flint([F(1), F(-1)])  # 1 - z
    pair = u * u + _flint([Y])
    h = u * pair
    g = _flint([b]) * pair + (_flint([c_]) * u + _flint([w])) * u
    sentence = lines_nonnegative(_fractions(g), _fractions(h), True)
    if b > 0 and b * b >= c_ * c_ + w * w / Y:
        assert sentence is not None and "b^2 >= 4|beta|^2" in sentence
    else:
        assert sentence is None
    assert lines_nonnegative(_fractions(g), _fractions(h), False) is None  # the caller did not prove h squarefree


def test_forged_lines_are_rejected_for_their_reason():
    sqrt2 = Real.algebraic([F(-2), F(0), F(1)], F(1), F(2))
    with pytest.raises(CheckFailure, match="alpha must be a finite real"):
        AlgebraicLine(Real(inf=1), [F(-2), F(0), F(1)])
    with pytest.raises(CheckFailure, match="p\\* is not a root of its polynomial"):
        AlgebraicLine(sqrt2, [F(-3), F(0), F(1)])
    with pytest.raises(CheckFailure, match="unsupported degree"):
        AlgebraicLine(sqrt2, [F(1)])
    with pytest.raises(CheckFailure, match="unsupported degree"):
        AlgebraicLine(sqrt2, _fractions(_flint([F(-2), F(0), F(1)]) * _flint([F(5), F(1)]) ** (MAX_LINE_DEGREE - 1)))
    line = AlgebraicLine(sqrt2, [F(-2), F(0), F(1)])
    with pytest.raises(CheckFailure, match=f"deg f > {MAX_LINE_DEGREE}"):
        line.parts([F(1)] * (MAX_LINE_DEGREE + 2))


@settings(max_examples=40, deadline=None)
@given(nonsquare, st.lists(st.tuples(st.fractions(min_value=-6, max_value=6, max_denominator=4),
                                     st.fractions(min_value=-3, max_value=3, max_denominator=4)), min_size=0, max_size=3),
       st.sampled_from([(), (F(3, 2),)]))
def test_the_sturm_count_over_q_alpha_counts_the_real_roots(n, factors, extra):
    """G = y prod (y^2 - Y_k), Y_k = c_k + d_k sqrt n in Q(sqrt n) (distinct, nonzero): G has 1 + 2 #{Y_k > 0} real
    roots, and :meth:`AlgebraicLine.real_root_count` (Sturm over the ordered field Q(sqrt n), alpha held as a root of a
    reducible m) finds exactly that many."""
    Ys = []
    for c, d in factors:
        if (c, d) != (0, 0) and (c, d) not in Ys:
            Ys.append((c, d))
    line = _sqrt_line(n, extra)
    G = [[], [F(1)]]  # y, coefficients in Q(alpha) as polynomials in x
    for c, d in Ys:
        factor = [[-c, -d], [], [F(1)]]  # y^2 - (c + d x)
        out = [[] for _ in range(len(G) + 2)]
        for i, a in enumerate(G):
            for j, b in enumerate(factor):
                if a and b:
                    out[i + j] = _add_q(out[i + j], line._mul(a, b))
        G = out
    expected = 1 + 2 * sum(1 for c, d in Ys if _sign_c_plus_d_sqrt(c, d, n) > 0)
    assert line.real_root_count(G) == expected


def _add_q(a, b):
    n = max(len(a), len(b))
    return [(a[i] if i < len(a) else F(0)) + (b[i] if i < len(b) else F(0)) for i in range(n)]


def test_a_rational_pole_midway_between_conjugate_real_poles_is_alone_on_its_line():
    """Poles 3 and 3 +- sqrt 2 (red team rt-lines): on Re z = 3, G = y(y^2 + 2) -- the roots y = +-i sqrt 2 are the
    real poles 3 -+ sqrt 2, off the line -- so 3 is alone there (1 real root), and with every residue positive f > 0
    line by line; a negative residue at 3 (b_3 < 0) is refused."""
    h = _fractions(_flint([F(-3), F(1)]) * _flint([F(7), F(-6), F(1)]))  # (z - 3)((z - 3)^2 - 2)
    three = Real.rational(F(3))
    line = AlgebraicLine(Real.root_in(h, F(5, 2), F(7, 2)), h)
    G = line.line_gcd(h)
    assert [line.sign(c) for c in G] == [0, 1, 0, 1] and line.real_root_count(G) == 1
    assert three.compare(line.alpha) == 0
    # r = 1/(3 - z) + 1/(3 - sqrt 2 - z) + 1/(3 + sqrt 2 - z), times a constant: every b > 0
    g = _fractions(_flint([F(7), F(-6), F(1)]) + 2 * _flint([F(-3), F(1)]) * _flint([F(-3), F(1)]))
    h_neg = [-c for c in h]  # 1/(p - z) = -1/(z - p): r = -(...)/h
    assert "b > 0" in lines_nonnegative(g, h_neg, True)
    assert lines_nonnegative([-c for c in g], h_neg, True) is None


# ------------------------------------------------------------------ resources
def test_the_euclid_steps_in_q_alpha_are_charged_and_stop_at_the_limit():
    f = _fractions(_pair_polynomial(F(1, 3)) * _pair_polynomial(F(2)))
    with account() as acc:
        assert len(_sqrt_line(2, (F(3),)).line_gcd(f)) == 5
    assert acc.spent > 0
    with account(limit=acc.spent // 3):
        with pytest.raises(OverBudget, match="over the certificate's work budget"):
            _sqrt_line(2, (F(3),)).line_gcd(f)


def test_a_denominator_over_the_line_degree_gets_no_claim_and_no_work():
    h = _fractions(_flint([F(1), F(-1)]) ** (MAX_LINE_DEGREE + 1))
    with account() as acc:
        assert lines_nonnegative([F(1)], h, True) is None
    assert acc.spent == 0
