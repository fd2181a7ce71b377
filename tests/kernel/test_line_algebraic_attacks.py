"""Red team of radius claims whose rightmost real pole p* is irrational with poles on its line
(exactinv_check/line_algebraic.py, exactinv_check/bernstein.py; issue 22/23 rule).

The kernel recomputes everything from the method, so the attacks are methods and claims: rho = oo (reason
bernstein) forged onto methods whose density f = r(-x)'s inverse Laplace transform dips below 0 -- a pair just
off p*'s line (left or right, 10^-20), a pair on the line a hair beyond the balance b_*^2 = 4|beta|^2, a real
residue whose sign is flipped -- and :func:`lines_nonnegative` (the line-by-line proof) against the exact truth
line by line (sympy) on seeded random lines.  Nothing was found.

The examples (sympy, nothing from exactinv): for p_s = a - s sqrt d (s = +-1, Galois conjugates)
    S(z) = sum_s [b_s/(p_s + e - z) ... ]
built term by term in :func:`_method`; a term b/(p - z) is b e^(-p t) in f, a pair (c (p - z) + w)/((p - z)^2 + Y)
is e^(-p t) (c cos(yt) + (w/y) sin(yt)), y = sqrt Y: the line through p has B = b + c cos + (w/y) sin >= 0
iff b >= 0 and b^2 >= c^2 + w^2/Y.
"""


import random
from fractions import Fraction as F

import pytest
import sympy as sp

from exactinv_check import check
from exactinv_check.line_algebraic import lines_nonnegative

z = sp.symbols("z")


OO = {"type": "absolute_monotonicity_radius", "value": "oo", "reason": "bernstein", "attained": True}


def _method(lines, positive=True):
    """(g, h), h(0) = 1, of r = S/S(0), S(z) = sum over ``lines`` (p, b, pair or None, shift e) of b/(p - z) and
    (c (p + e - z) + w)/((p + e - z)^2 + Y) for pair = (c, w, Y): sympy, exact.  ``positive``: S(0) > 0 is
    asserted (so f has the signs of S's parts)."""
    S = 0
    for p, b, pair, e in lines:
        S += b / (p - z)
        if pair is not None:
            c, w, Y = pair
            S += (c * (p + e - z) + w) / ((p + e - z) ** 2 + Y)
    S0 = sp.radsimp(sp.expand(S.subs(z, 0)))
    assert S0 != 0 and (S0 > 0 or not positive)
    num, den = sp.fraction(sp.cancel(sp.together(sp.expand(S / S0))))
    g = [F(str(sp.nsimplify(x))) for x in reversed(sp.Poly(sp.expand(num), z).all_coeffs())]
    h = [F(str(sp.nsimplify(x))) for x in reversed(sp.Poly(sp.expand(den), z).all_coeffs())]
    return [x / h[0] for x in g], [x / h[0] for x in h]


def _conjugates(a, d, c, w, Y, e=0, b=1):
    """p_s = a - s sqrt d with residue b and a pair (c, w, Y) shifted by e off its line (both conjugates)."""
    return _method([(a - s * sp.sqrt(d), b, (sp.Rational(c), sp.Rational(w), Y), sp.Rational(e)) for s in (1, -1)])


def _oo_accepted(g, h):
    cert = {"format": "exactinv-certificate", "version": 3,
            "problem": {"method": {"name": "rational", "numerator": [str(x) for x in g],
                                   "denominator": [str(x) for x in h]}},
            "claims": [dict(OO)]}
    return check(cert).ok


def _random_lines(rng):
    a, d = rng.choice([(2, 2), (3, 2), (3, 5), (4, 3)])
    u, v = sp.Rational(rng.randint(1, 4)), sp.Rational(rng.randint(-2, 2), 4)
    c0, c1 = sp.Rational(rng.randint(-4, 4), rng.choice([1, 2, 4])), sp.Rational(rng.randint(-1, 1), 2)
    w0, w1 = sp.Rational(rng.randint(-4, 4), rng.choice([1, 2, 4])), sp.Rational(rng.randint(-1, 1), 2)
    Ye, Yf = sp.Rational(rng.randint(2, 6)), sp.Rational(rng.randint(-1, 1), 2)
    lines = [(a - s * sp.sqrt(d), u + s * v * sp.sqrt(d),
              (c0 + s * c1 * sp.sqrt(d), w0 + s * w1 * sp.sqrt(d), Ye + s * Yf * sp.sqrt(d)), 0) for s in (1, -1)]
    if rng.random() < 0.4:  # a rational pole (with a pair or not) off the conjugates' midpoint
        p = sp.Rational(rng.choice([1, 5, 9, 13]), 4)
        pair = (sp.Rational(rng.randint(-4, 4), 2), sp.Rational(rng.randint(-4, 4), 2), sp.Rational(rng.randint(1, 6)))
        lines.append((p, sp.Rational(rng.randint(1, 6), 2), pair if rng.random() < 0.5 else None, 0))
    return lines


def _truth(lines):
    """Every line part B >= 0 (exact, sympy; S(0) > 0, so f's parts have S's signs)."""
    for _, b, pair, _ in lines:
        if not b > 0:
            return False
        if pair is not None:
            c, w, Y = pair
            if sp.radsimp(sp.expand(b ** 2 - c ** 2 - w ** 2 / Y)) < 0:
                return False
    return True


# ------------------------------------------------------------------ soundness

def test_the_honest_balanced_line_is_accepted():
    """c = 1, w = 0, Y = 1 beside p* = 2 - sqrt 2: B = 1 + cos t >= 0 touches 0; rho = oo is true and accepted."""
    g, h = _conjugates(2, 2, 1, 0, 1)
    assert lines_nonnegative(g, h, True) is not None
    assert _oo_accepted(g, h)


@pytest.mark.parametrize("e", [F(-1, 10 ** 20), F(1, 10 ** 20)])
def test_a_pair_a_hair_off_the_line_is_not_taken_for_a_line_pole(e):
    """The balanced pair moved 10^-20 off p*'s line.  Left (e < 0): its e^(-(p* + e) t) c cos(yt) outgrows
    b e^(-p* t) for large t, so f < 0 somewhere: rho < oo.  Right with c = 11/10 > b = 1: f < 0 near t = pi while
    e^(-e t) ~ 1.  The forged rho = oo is rejected both times."""
    g, h = _conjugates(2, 2, 1 if e < 0 else F(11, 10), 0, 1, e)
    assert not _oo_accepted(g, h)


@pytest.mark.parametrize("c, w", [(1 + F(1, 10 ** 30), 0), (F(3, 5), F(4, 5) + F(1, 10 ** 30))])
def test_a_line_a_hair_past_the_balance_is_rejected(c, w):
    """b = 1, Y = 1: B = 1 + c cos t + w sin t >= 0 iff c^2 + w^2 <= 1; 10^-30 beyond it B < 0 somewhere, and
    the line dominates for large t (the other line decays faster): f < 0, rho = oo is false and rejected."""
    g, h = _conjugates(2, 2, c, w, 1)
    assert lines_nonnegative(g, h, True) is None
    assert not _oo_accepted(g, h)


def test_a_flipped_real_residue_is_rejected():
    """b = -1 on both lines, a pair c = 1/2, w = 3, Y = 1 (S(0) > 0): B = -1 + cos t/2 + 3 sin t < 0 somewhere, and
    p*'s line dominates: f < 0 somewhere, rho = oo is false."""
    g, h = _conjugates(2, 2, F(1, 2), 3, 1, b=-1)
    assert lines_nonnegative(g, h, True) is None
    assert not _oo_accepted(g, h)


def test_the_line_by_line_proof_against_the_exact_truth():
    """Seeded random conjugate lines (and a rational line): whenever lines_nonnegative claims f >= 0 line by line,
    every line part is >= 0 exactly; and it does claim some (the test is not vacuous)."""
    rng = random.Random(2322)
    claimed = 0
    for _ in range(7):
        lines = _random_lines(rng)
        try:
            g, h = _method(lines)
        except AssertionError:  # S(0) <= 0: f's parts have the opposite signs; not drawn
            continue
        if len(h) > 17 or len(g) >= len(h):
            continue
        if lines_nonnegative(g, h, True) is not None:
            claimed += 1
            assert _truth(lines), lines
    assert claimed >= 2


# ------------------------------------------------------------------ soundness: x_j alone by a Sturm count (d48d90e)

def _random_midway(rng):
    """Poles a - sqrt d, a, a + sqrt d (the rational pole midway: G = y(y^2 + d) on its line, non-real roots), each
    with a pair on its line or not; residues and pairs random (the conjugate lines' data Galois conjugates)."""
    a, d = rng.choice([(3, 2), (3, 5), (4, 3), (5, 7)])
    u, v = sp.Rational(rng.choice([-1, 1, 2, 3, 4])), sp.Rational(rng.randint(-2, 2), 4)  # u +- v sqrt d != 0
    lines = []
    conj_pair = rng.random() < 0.5
    c0, c1 = sp.Rational(rng.randint(-4, 4), rng.choice([1, 2, 4])), sp.Rational(rng.randint(-1, 1), 2)
    w0, w1 = sp.Rational(rng.randint(-4, 4), rng.choice([1, 2, 4])), sp.Rational(rng.randint(-1, 1), 2)
    Ye = sp.Rational(rng.randint(1, 6))
    for s in (1, -1):
        pair = (c0 + s * c1 * sp.sqrt(d), w0 + s * w1 * sp.sqrt(d), Ye) if conj_pair else None
        lines.append((a - s * sp.sqrt(d), u + s * v * sp.sqrt(d), pair, 0))
    b = sp.Rational(rng.choice([-2, -1, 1, 2, 3, 4, 5, 6]), 2)  # != 0: a pole
    mid_pair = None
    if rng.random() < 0.5:  # a pair on the midway line (then G has the real roots +- sqrt Y too: not alone)
        mid_pair = (sp.Rational(rng.randint(-4, 4), 2), sp.Rational(rng.randint(-4, 4), 2), sp.Rational(rng.choice([1, 3, 7])))
    lines.append((sp.Rational(a), b, mid_pair, 0))
    return lines


def test_midway_poles_line_by_line_against_the_exact_truth():
    """Red team of d48d90e (a line whose gcd G has no real root but y = 0 holds x_j alone, by a Sturm count over
    Q(alpha)): seeded random poles a, a +- sqrt d with random residues and pairs on their lines.  Whenever
    lines_nonnegative claims f >= 0, every line part is >= 0 exactly (sympy); forged residues (b <= 0 on the midway
    line, pairs past the balance) are never claimed.  14 drawn, the claims counted (not vacuous)."""
    rng = random.Random(4805)
    claimed = refused_false = 0
    for _ in range(14):
        lines = _random_midway(rng)
        try:
            g, h = _method(lines)
        except AssertionError:
            continue
        verdict = lines_nonnegative(g, h, True)
        truth = _truth(lines)
        if verdict is not None:
            claimed += 1
            assert truth, lines
        elif not truth:
            refused_false += 1
    assert claimed >= 2 and refused_false >= 2


# ------------------------------------------------------------------ resource
# No test here is about this module's work limits: the certificate's account is tested in test_budget.py.
